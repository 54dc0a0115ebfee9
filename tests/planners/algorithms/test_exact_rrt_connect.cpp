// ExactRRTConnect on a plain OMPL problem: a square with a wall and one gap,
// OMPL's own DiscreteMotionValidator at a fine resolution. It must solve it,
// return a valid path, and grow its trees up to obstacles (the point of
// extending to the first contact).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/PlannerData.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/RandomNumbers.h>

#include "mddual/error.h"
#include "mddual/planning/exact_rrt_connect.h"
#include "planner_budget.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

/// The planner's budget: iterations, not seconds (planner_budget.h).
ob::PlannerTerminationCondition budget() {
  return mddual::testing::iterationBudget(mddual::testing::kPlannerIterations);
}

/// [0,10]^2 with a wall x in [4.9, 5.1] except for the gap y in [8, 9].
bool free(const ob::State* s) {
  const auto* v = s->as<ob::RealVectorStateSpace::StateType>();
  const double x = v->values[0];
  const double y = v->values[1];
  return !(x >= 4.9 && x <= 5.1 && !(y >= 8.0 && y <= 9.0));
}

og::SimpleSetup makeSetup() {
  auto space = std::make_shared<ob::RealVectorStateSpace>(2);
  space->setBounds(0.0, 10.0);
  og::SimpleSetup ss(space);
  ss.setStateValidityChecker(free);
  ss.getSpaceInformation()->setStateValidityCheckingResolution(0.001);
  ob::ScopedState<> start(space);
  ob::ScopedState<> goal(space);
  start[0] = 1.0;
  start[1] = 1.0;
  goal[0] = 9.0;
  goal[1] = 1.0;
  ss.setStartAndGoalStates(start, goal);
  return ss;
}

TEST(ExactRRTConnect, SolvesThroughTheGapWithAValidPath) {
  ompl::RNG::setSeed(42);
  og::SimpleSetup ss = makeSetup();
  auto planner = std::make_shared<ExactRRTConnect>(ss.getSpaceInformation());
  ss.setPlanner(planner);
  ASSERT_EQ(ss.solve(budget()), ob::PlannerStatus::EXACT_SOLUTION);
  og::PathGeometric& path = ss.getSolutionPath();
  EXPECT_TRUE(path.check());
  // Re-check every segment densely: no point of the path is in the wall.
  for (unsigned i = 0; i + 1 < path.getStateCount(); ++i) {
    ob::State* s = ss.getSpaceInformation()->allocState();
    for (int k = 0; k <= 2000; ++k) {
      ss.getStateSpace()->interpolate(path.getState(i), path.getState(i + 1), k / 2000.0, s);
      EXPECT_TRUE(free(s)) << "segment " << i << " at " << k / 2000.0;
    }
    ss.getSpaceInformation()->freeState(s);
  }
  const auto* first = path.getState(0)->as<ob::RealVectorStateSpace::StateType>();
  const auto* last =
      path.getState(static_cast<unsigned>(path.getStateCount() - 1))->as<ob::RealVectorStateSpace::StateType>();
  EXPECT_NEAR(first->values[0], 1.0, 1e-12);
  EXPECT_NEAR(last->values[0], 9.0, 1e-12);
}

/// Whether the state is within 0.01 of makeSetup's wall faces.
bool atTheWall(const ob::State* s) {
  const double x = s->as<ob::RealVectorStateSpace::StateType>()->values[0];
  return std::abs(x - 4.9) < 0.01 || std::abs(x - 5.1) < 0.01;
}

/// The planner's tree states at the wall (atTheWall).
int statesAtTheWall(const ExactRRTConnect& planner, const ob::SpaceInformationPtr& si) {
  ob::PlannerData data(si);
  planner.getPlannerData(data);
  int at_wall = 0;
  for (unsigned i = 0; i < data.numVertices(); ++i) at_wall += atTheWall(data.getVertex(i).getState());
  return at_wall;
}

TEST(ExactRRTConnect, ExtensionsStopAtTheWall) {
  // Blocked extensions keep the part up to the first contact: some tree
  // nodes end within the validator's resolution of the wall's faces.
  ompl::RNG::setSeed(7);
  og::SimpleSetup ss = makeSetup();
  auto planner = std::make_shared<ExactRRTConnect>(ss.getSpaceInformation());
  ss.setPlanner(planner);
  ss.solve(budget());
  EXPECT_GT(statesAtTheWall(*planner, ss.getSpaceInformation()), 0);
}

TEST(ExactRRTConnect, RangeLimitsExtensions) {
  ompl::RNG::setSeed(3);
  og::SimpleSetup ss = makeSetup();
  auto planner = std::make_shared<ExactRRTConnect>(ss.getSpaceInformation());
  planner->setRange(0.5);
  ss.setPlanner(planner);
  ASSERT_EQ(ss.solve(budget()), ob::PlannerStatus::EXACT_SOLUTION);
  ob::PlannerData data(ss.getSpaceInformation());
  planner->getPlannerData(data);
  // Every tree edge (not the final joining edge) is at most `range` long.
  int longer = 0;
  for (unsigned i = 0; i < data.numVertices(); ++i) {
    std::vector<unsigned> out;
    data.getEdges(i, out);
    for (unsigned j : out) {
      if (ss.getSpaceInformation()->distance(data.getVertex(i).getState(), data.getVertex(j).getState()) > 0.5 + 1e-9) {
        ++longer;
      }
    }
  }
  EXPECT_LE(longer, 1);
}

TEST(ExactRRTConnect, ConnectStepsByRangeUntilItReachesTheNewNode) {
  // No obstacle, range 0.5, start and goal 8 apart: the first EXTEND adds one
  // node to the start tree, and CONNECT then steps the goal tree toward it by
  // the range until it reaches it, so the first iteration solves: the start
  // tree holds two states and the path has at most 2 + ceil(8.5 / 0.5) of
  // them, every edge no longer than the range. (A CONNECT of one step would
  // need about 16 iterations, growing the start tree at each.)
  ompl::RNG::setSeed(5);
  auto space = std::make_shared<ob::RealVectorStateSpace>(2);
  space->setBounds(0.0, 10.0);
  og::SimpleSetup ss(space);
  ss.setStateValidityChecker([](const ob::State*) { return true; });
  ob::ScopedState<> start(space), goal(space);
  start[0] = 1.0;
  start[1] = 1.0;
  goal[0] = 9.0;
  goal[1] = 1.0;
  ss.setStartAndGoalStates(start, goal);
  auto planner = std::make_shared<ExactRRTConnect>(ss.getSpaceInformation());
  constexpr double kRange = 0.5;
  planner->setRange(kRange);
  ss.setPlanner(planner);
  ASSERT_EQ(ss.solve(budget()), ob::PlannerStatus::EXACT_SOLUTION);
  ob::PlannerData data(ss.getSpaceInformation());
  planner->getPlannerData(data);
  int start_tree = 0;
  for (unsigned i = 0; i < data.numVertices(); ++i) start_tree += data.getVertex(i).getTag() == 1;
  EXPECT_EQ(start_tree, 2);
  const og::PathGeometric& path = ss.getSolutionPath();
  // The new node is within the range of the start, so within 8 + 0.5 of the goal.
  EXPECT_LE(path.getStateCount(), 2u + static_cast<unsigned>(std::ceil(8.5 / kRange)));
  for (unsigned i = 0; i + 1 < path.getStateCount(); ++i) {
    EXPECT_LE(ss.getSpaceInformation()->distance(path.getState(i), path.getState(i + 1)), kRange + 1e-9) << i;
  }
}

/// SE(2): a rod of half length 0.6 centred at the state, along its heading,
/// in [0,10]^2 with the wall and gap of makeSetup(): free when 25 points of
/// the rod are (the test's own check, also used densely on the path).
bool rodFree(const ob::State* s) {
  const auto* q = s->as<ob::SE2StateSpace::StateType>();
  for (int k = -12; k <= 12; ++k) {
    const double x = q->getX() + 0.05 * k * std::cos(q->getYaw());
    const double y = q->getY() + 0.05 * k * std::sin(q->getYaw());
    if (x < 0.0 || x > 10.0 || y < 0.0 || y > 10.0) return false;
    if (x >= 4.9 && x <= 5.1 && !(y >= 8.0 && y <= 9.0)) return false;
  }
  return true;
}

/// SE(2) on [0,10]^2 with the rod checker; start (1, 1) heading 0 (the rod
/// along x), goal at (x, y) with heading `yaw`.
og::SimpleSetup makeRodSetup(double x, double y, double yaw) {
  auto space = std::make_shared<ob::SE2StateSpace>();
  ob::RealVectorBounds bounds(2);
  bounds.setLow(0.0);
  bounds.setHigh(10.0);
  space->setBounds(bounds);
  og::SimpleSetup ss(space);
  ss.setStateValidityChecker(rodFree);
  ob::ScopedState<ob::SE2StateSpace> start(space), goal(space);
  start->setXY(1.0, 1.0);
  start->setYaw(0.0);
  goal->setXY(x, y);
  goal->setYaw(yaw);
  ss.setStartAndGoalStates(start, goal);
  return ss;
}

TEST(ExactRRTConnect, Se2ExtensionsRotateInPlaceThenTranslate) {
  ompl::RNG::setSeed(11);
  og::SimpleSetup ss = makeRodSetup(9.0, 1.0, 0.0);  // the rod must turn to pass the 1 m gap
  ss.getSpaceInformation()->setStateValidityCheckingResolution(0.0005);
  const ob::StateSpacePtr& space = ss.getStateSpace();
  auto planner = std::make_shared<ExactRRTConnect>(ss.getSpaceInformation());
  planner->params().setParam("rotate_first", "1");
  ASSERT_TRUE(planner->getRotateFirst());
  ss.setPlanner(planner);
  ASSERT_EQ(ss.solve(budget()), ob::PlannerStatus::EXACT_SOLUTION);
  const og::PathGeometric& path = ss.getSolutionPath();
  int rotations = 0, translations = 0;
  for (unsigned i = 0; i + 1 < path.getStateCount(); ++i) {
    const auto* a = path.getState(i)->as<ob::SE2StateSpace::StateType>();
    const auto* b = path.getState(i + 1)->as<ob::SE2StateSpace::StateType>();
    const bool same_position = a->getX() == b->getX() && a->getY() == b->getY();
    const bool same_heading = a->getYaw() == b->getYaw();
    // Every segment is a rotation in place or a pure translation (the
    // joining edge of CONNECT included).
    EXPECT_TRUE(same_position || same_heading) << "segment " << i;
    rotations += same_position && !same_heading;
    translations += same_heading && !same_position;
    ob::State* s = ss.getSpaceInformation()->allocState();
    for (int k = 0; k <= 2000; ++k) {
      space->interpolate(path.getState(i), path.getState(i + 1), k / 2000.0, s);
      EXPECT_TRUE(rodFree(s)) << "segment " << i << " at " << k / 2000.0;
    }
    ss.getSpaceInformation()->freeState(s);
  }
  EXPECT_GT(rotations, 0);
  EXPECT_GT(translations, 0);
}

/// Every motion is blocked, and lastValid keeps `gain_steps` validity-checking
/// steps of it (the edge's length over validSegmentCount; at most half of
/// it): a validator whose bound lies short of the contact, as MDD-DUAL's may
/// by up to one step.
class ShortGainValidator : public ob::MotionValidator {
 public:
  ShortGainValidator(const ob::SpaceInformationPtr& si, double gain_steps)
      : ob::MotionValidator(si), gain_steps_(gain_steps) {}
  bool checkMotion(const ob::State*, const ob::State*) const override { return false; }
  bool checkMotion(const ob::State* s1, const ob::State* s2, std::pair<ob::State*, double>& lastValid) const override {
    ++checks;
    const unsigned steps = std::max(1u, si_->getStateSpace()->validSegmentCount(s1, s2));
    lastValid.second = std::min(0.5, gain_steps_ / steps);
    if (lastValid.first != nullptr) si_->getStateSpace()->interpolate(s1, s2, lastValid.second, lastValid.first);
    return false;
  }
  mutable int checks = 0;

 private:
  double gain_steps_;
};

/// States in the trees of `ss` after 400 evaluations of the termination
/// condition, every motion blocked after `gain_steps` steps, min_progress
/// set to `min_progress` steps; *checks: the lastValid checks made (of
/// blocked edges' steps of blocked_range, 0: the default).
unsigned statesWithShortGains(og::SimpleSetup ss, double gain_steps, double min_progress, int* checks,
                              bool rotate_first = false, double probe_steps = 4.0, double blocked_range = 0.0) {
  ompl::RNG::setSeed(13);
  const ob::SpaceInformationPtr& si = ss.getSpaceInformation();
  auto planner = std::make_shared<ExactRRTConnect>(si);
  EXPECT_DOUBLE_EQ(planner->getMinProgress(), 1.0);  // the default: one step
  EXPECT_DOUBLE_EQ(planner->getProbeSteps(), 4.0);   // the default: four steps
  planner->setMinProgress(min_progress);
  planner->setProbeSteps(probe_steps);
  planner->setRotateFirst(rotate_first);
  planner->setBlockedRange(blocked_range);
  ss.setPlanner(planner);
  ss.setup();
  auto validator = std::make_shared<ShortGainValidator>(si, gain_steps);
  si->setMotionValidator(validator);
  int evaluations = 0;
  ss.solve(ob::PlannerTerminationCondition([&evaluations] { return ++evaluations > 400; }));
  ob::PlannerData data(si);
  planner->getPlannerData(data);
  *checks = validator->checks;
  return data.numVertices();
}

TEST(ExactRRTConnect, BlockedExtensionsShorterThanMinProgressStepsAddNothing) {
  // A blocked edge kept up to lastValid is a new state only when it gains at
  // least min_progress steps: extending again toward the same target from a
  // kept state follows the same blocked path (the creep this rule stops).
  int checks = 0;
  EXPECT_EQ(statesWithShortGains(makeSetup(), 0.4, 1.0, &checks), 2u);  // start and goal only
  EXPECT_GT(checks, 10);                                                // extensions were tried
  EXPECT_GT(statesWithShortGains(makeSetup(), 0.4, 0.25, &checks), 10u);
  EXPECT_GT(statesWithShortGains(makeSetup(), 0.4, 0.0, &checks), 10u);  // any gain, as before
  // ... but a gain of round-off adds nothing even then (kMinGainSteps, 1e-9
  // steps: near-copies of a state stalled OMPL's nearest-neighbour search).
  EXPECT_EQ(statesWithShortGains(makeSetup(), 1e-12, 0.0, &checks), 2u);
  EXPECT_GT(checks, 10);
  EXPECT_GT(statesWithShortGains(makeSetup(), 1e-8, 0.0, &checks), 10u);
  // Exactly one step (what OMPL's discrete validator keeps when its second
  // sample collides) is progress: every blocked check adds its state.
  const unsigned states = statesWithShortGains(makeSetup(), 1.0, 1.0, &checks);
  EXPECT_GT(checks, 10);
  EXPECT_EQ(states, 2u + static_cast<unsigned>(checks));
}

/// makeSetup's problem with another state validity checker.
og::SimpleSetup makeSetupWith(const ob::StateValidityCheckerFn& valid) {
  og::SimpleSetup ss = makeSetup();
  ss.setStateValidityChecker(valid);
  return ss;
}

/// The state's distance from the nearer of makeSetup's start and goal.
double toStartOrGoal(const ob::State* s) {
  const auto* v = s->as<ob::RealVectorStateSpace::StateType>();
  const double y = v->values[1] - 1.0;
  return std::min(std::hypot(v->values[0] - 1.0, y), std::hypot(v->values[0] - 9.0, y));
}

TEST(ExactRRTConnect, AProbeStateThatCollidesEndsTheExtensionWithoutAMotionCheck) {
  // Every state but the start and the goal collides: each extension's probe
  // (four steps in) says so, and no motion check is made. Without the probe
  // (0) the validator is asked.
  const auto walled = [] { return makeSetupWith([](const ob::State* s) { return toStartOrGoal(s) == 0.0; }); };
  int checks = -1;
  EXPECT_EQ(statesWithShortGains(walled(), 5.0, 1.0, &checks), 2u);
  EXPECT_EQ(checks, 0);
  EXPECT_GT(statesWithShortGains(walled(), 5.0, 1.0, &checks, false, 0.0), 10u);
  EXPECT_GT(checks, 10);
}

TEST(ExactRRTConnect, TheProbeIsProbeStepsIntoTheEdge) {
  // Free only within 3.5 steps (of the edge's length over validSegmentCount:
  // 0.001 of the maximum extent, sqrt(200), at most) of the start and the
  // goal, the only tree states while every probe collides. Every edge starts
  // at one of them: a probe 4 steps in (at most, and at least 4 (1 - s / d)
  // steps for an edge of length d and step s) collides, one 3 steps in does
  // not (then the validator keeps 5 steps of the edge, and edges from there
  // probe outside the disks).
  const double step = 0.001 * std::sqrt(200.0);
  const auto disks = [step] {
    return makeSetupWith([step](const ob::State* s) { return toStartOrGoal(s) < 3.5 * step; });
  };
  int checks = -1;
  EXPECT_EQ(statesWithShortGains(disks(), 5.0, 1.0, &checks), 2u);
  EXPECT_EQ(checks, 0);
  EXPECT_GT(statesWithShortGains(disks(), 5.0, 1.0, &checks, false, 3.0), 2u);
  EXPECT_GT(checks, 0);
}

TEST(ExactRRTConnect, AProbeStateThatIsFreeChangesNothing) {
  // Nothing collides: the trees grow exactly as without the probe (it draws
  // no random numbers), with the same motion checks.
  const auto open = [] { return makeSetupWith([](const ob::State*) { return true; }); };
  int with_probe = 0, without = 0;
  const unsigned states = statesWithShortGains(open(), 5.0, 1.0, &with_probe);
  EXPECT_GT(with_probe, 10);
  EXPECT_EQ(states, statesWithShortGains(open(), 5.0, 1.0, &without, false, 0.0));
  EXPECT_EQ(with_probe, without);
}

TEST(ExactRRTConnect, MinProgressCountsTheEdgesOwnSteps) {
  // SE(2) in a 100 m square, rotating in place first: a rotation's steps
  // (OMPL's validSegmentCount, from the yaw's extent) are 0.016 long, while
  // the space's longest valid segment (resolution x the sum of the extents)
  // is 1.43. Every motion is blocked, so every extension is one rotation in
  // place, whose step of blocked_range (0.1: a turn of 0.2 rad) is kept up
  // to lastValid or not: a gain of 1.5 of the step's steps is progress, 0.6
  // is not.
  const auto square = [] {
    og::SimpleSetup ss = makeRodSetup(80.0, 80.0, 1.0);
    ob::RealVectorBounds bounds(2);
    bounds.setLow(0.0);
    bounds.setHigh(100.0);
    ss.getStateSpace()->as<ob::SE2StateSpace>()->setBounds(bounds);
    ss.setStateValidityChecker([](const ob::State*) { return true; });
    ss.getSpaceInformation()->setStateValidityCheckingResolution(0.01);
    return ss;
  };
  int checks = 0;
  EXPECT_EQ(statesWithShortGains(square(), 0.6, 1.0, &checks, true, 4.0, 0.1), 2u);
  EXPECT_GT(checks, 10);
  EXPECT_GT(statesWithShortGains(square(), 1.5, 1.0, &checks, true, 4.0, 0.1), 10u);
}

/// OMPL's discrete validator, recording the length of every edge it is
/// asked about and whether the edge was free, by overload.
class RecordingValidator : public ob::DiscreteMotionValidator {
 public:
  using ob::DiscreteMotionValidator::DiscreteMotionValidator;
  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    const bool valid = ob::DiscreteMotionValidator::checkMotion(s1, s2);
    if (recording) validity.push_back({si_->distance(s1, s2), valid});
    return valid;
  }
  bool checkMotion(const ob::State* s1, const ob::State* s2, std::pair<ob::State*, double>& lastValid) const override {
    const bool valid = ob::DiscreteMotionValidator::checkMotion(s1, s2, lastValid);
    if (recording) last_valid.push_back({si_->distance(s1, s2), valid});
    return valid;
  }
  struct Check {
    double length;
    bool valid;
  };
  mutable std::vector<Check> validity, last_valid;
  bool recording = true;
};

/// The planner's tree edges: their lengths and whether their newer end is
/// at the wall (atTheWall).
struct TreeEdge {
  double length;
  bool to_wall;
};
std::vector<TreeEdge> treeEdges(const ExactRRTConnect& planner, const ob::SpaceInformationPtr& si) {
  ob::PlannerData data(si);
  planner.getPlannerData(data);
  std::vector<TreeEdge> edges;
  for (unsigned i = 0; i < data.numVertices(); ++i) {
    std::vector<unsigned> out;
    data.getEdges(i, out);
    for (const unsigned j : out) {
      // Start tree edges point away from the root, goal tree ones toward it.
      const bool start_tree = data.getVertex(i).getTag() == 1;
      const ob::State* newer = data.getVertex(start_tree ? j : i).getState();
      edges.push_back({si->distance(data.getVertex(i).getState(), data.getVertex(j).getState()), atTheWall(newer)});
    }
  }
  return edges;
}

/// Solves `ss` with `planner` (no probe: every blocked edge reaches its
/// motion checks), its motions checked by a RecordingValidator, which it
/// returns; the path found must be valid.
std::shared_ptr<RecordingValidator> solveRecorded(og::SimpleSetup& ss,
                                                  const std::shared_ptr<ExactRRTConnect>& planner) {
  planner->setProbeSteps(0.0);
  ss.setPlanner(planner);
  ss.setup();
  auto validator = std::make_shared<RecordingValidator>(ss.getSpaceInformation());
  ss.getSpaceInformation()->setMotionValidator(validator);
  EXPECT_EQ(ss.solve(budget()), ob::PlannerStatus::EXACT_SOLUTION);
  validator->recording = false;  // the planner's checks only
  EXPECT_TRUE(ss.getSolutionPath().check());
  return validator;
}

TEST(ExactRRTConnect, BlockedRangeIsOmplsDefaultRangeUnlessSet) {
  og::SimpleSetup ss = makeSetup();
  auto planner = std::make_shared<ExactRRTConnect>(ss.getSpaceInformation());
  EXPECT_EQ(planner->getBlockedRange(), 0.0);
  ss.setPlanner(planner);
  ss.setup();
  EXPECT_DOUBLE_EQ(planner->getBlockedRange(), 0.2 * std::sqrt(200.0));  // 0.2 of the square's diagonal
  EXPECT_NEAR(std::stod(planner->params().getParam("blocked_range")->getValue()), 2.82843, 1e-5);  // as OMPL prints it
  auto set = std::make_shared<ExactRRTConnect>(ss.getSpaceInformation());
  set->setBlockedRange(1.5);
  ss.setPlanner(set);
  ss.setup();
  EXPECT_EQ(set->getBlockedRange(), 1.5);
}

TEST(ExactRRTConnect, ABlockedEdgeFallsBackToAStepOfBlockedRange) {
  // Each edge is first checked whole for validity; only a blocked one
  // longer than blocked_range (1.5) is followed by a lastValid check, of its
  // step of 1.5 toward the target; a blocked one no longer adds nothing.
  ompl::RNG::setSeed(19);
  og::SimpleSetup ss = makeSetup();
  auto planner = std::make_shared<ExactRRTConnect>(ss.getSpaceInformation());
  constexpr double kStep = 1.5;
  planner->setBlockedRange(kStep);
  const auto validator = solveRecorded(ss, planner);
  int blocked_long = 0, blocked_short = 0;
  for (const RecordingValidator::Check& c : validator->validity) {
    if (!c.valid) ++(c.length > kStep ? blocked_long : blocked_short);
  }
  EXPECT_GT(blocked_long, 5);
  EXPECT_GT(blocked_short, 0);  // the test's sample holds both kinds
  EXPECT_EQ(static_cast<int>(validator->last_valid.size()), blocked_long);
  int steps_blocked = 0;
  for (const RecordingValidator::Check& c : validator->last_valid) {
    EXPECT_NEAR(c.length, kStep, 1e-9);
    steps_blocked += !c.valid;
  }
  EXPECT_GT(steps_blocked, 0);  // some steps were blocked
  // In the trees: steps kept whole (exactly kStep long), steps kept up to
  // lastValid (shorter, ending at the wall), and nothing else that ends at
  // the wall (a whole edge ends at its target, never at the wall).
  int whole_steps = 0, cut_steps = 0;
  for (const TreeEdge& e : treeEdges(*planner, ss.getSpaceInformation())) {
    whole_steps += std::abs(e.length - kStep) < 1e-9;
    if (e.to_wall) {
      EXPECT_LT(e.length, kStep - 1e-9);
      ++cut_steps;
    }
  }
  EXPECT_GT(whole_steps, 0);
  EXPECT_GT(cut_steps, 0);
}

TEST(ExactRRTConnect, ABlockedRangeSetToZeroAfterSetupIsOmplsRangeAgain) {
  // 0 set after setup() (which configures it once) must not make steps of
  // length 0 (copies of a tree state, which CONNECT repeated without end):
  // the step is OMPL's default range then, as before setup().
  ompl::RNG::setSeed(23);
  og::SimpleSetup ss = makeSetup();
  auto planner = std::make_shared<ExactRRTConnect>(ss.getSpaceInformation());
  ss.setPlanner(planner);
  ss.setup();
  planner->setBlockedRange(0.0);
  ASSERT_EQ(ss.solve(budget()), ob::PlannerStatus::EXACT_SOLUTION);
  int copies = 0;
  for (const TreeEdge& e : treeEdges(*planner, ss.getSpaceInformation())) copies += e.length <= 1e-6;
  EXPECT_LE(copies, 1);  // the joining edge's: its goal-tree end is a copy of the joining state
}

TEST(ExactRRTConnect, WholeEdgeLastValidKeepsEveryBlockedEdgeUpToLastValid) {
  // whole_edge_last_valid: every edge is one lastValid check, none a
  // validity check first, and blocked edges of any length are kept up to
  // lastValid: tree states end at the wall's faces.
  ompl::RNG::setSeed(19);
  og::SimpleSetup ss = makeSetup();
  auto planner = std::make_shared<ExactRRTConnect>(ss.getSpaceInformation());
  EXPECT_FALSE(planner->getWholeEdgeLastValid());  // off by default
  planner->setWholeEdgeLastValid(true);
  const auto validator = solveRecorded(ss, planner);
  EXPECT_TRUE(validator->validity.empty());
  int blocked_short = 0;
  for (const RecordingValidator::Check& c : validator->last_valid) blocked_short += !c.valid && c.length < 2.8;
  EXPECT_GT(blocked_short, 0);
  // Blocked edges longer than the default step (2.83) kept up to their
  // contact: tree edges ending at the wall that long (the default mode's end
  // there after a step, no longer).
  int long_to_wall = 0;
  for (const TreeEdge& e : treeEdges(*planner, ss.getSpaceInformation())) long_to_wall += e.to_wall && e.length > 2.9;
  EXPECT_GT(long_to_wall, 0);
}

TEST(ExactRRTConnect, NegativeOrNanParametersAreRefused) {
  og::SimpleSetup ss = makeSetup();
  ExactRRTConnect planner(ss.getSpaceInformation());
  for (const double bad : {-1.0, std::nan("")}) {
    EXPECT_THROW(planner.setRange(bad), InvalidInputError) << bad;
    EXPECT_THROW(planner.setMinProgress(bad), InvalidInputError) << bad;
    EXPECT_THROW(planner.setProbeSteps(bad), InvalidInputError) << bad;
    EXPECT_THROW(planner.setBlockedRange(bad), InvalidInputError) << bad;
  }
  EXPECT_THROW(planner.setBlockedRange(HUGE_VAL), InvalidInputError);
  EXPECT_THROW(planner.setMinProgress(HUGE_VAL), InvalidInputError);
  EXPECT_THROW(planner.setProbeSteps(HUGE_VAL), InvalidInputError);
  try {
    planner.setProbeSteps(-1.0);
    ADD_FAILURE() << "-1 accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "mdd_rrtconnect: probe_steps must be a finite number of steps >= 0 (0: no probe), got -1");
  }
  try {
    planner.setMinProgress(-0.5);
    ADD_FAILURE() << "-0.5 accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_EQ(std::string(e.what()), "mdd_rrtconnect: min_progress must be a finite number of steps >= 0, got -0.5");
  }
  EXPECT_DOUBLE_EQ(planner.getRange(), 0.0);  // unchanged by the refused values
  EXPECT_DOUBLE_EQ(planner.getMinProgress(), 1.0);
  EXPECT_DOUBLE_EQ(planner.getProbeSteps(), 4.0);
  EXPECT_DOUBLE_EQ(planner.getBlockedRange(), 0.0);
  planner.setRange(HUGE_VAL);  // an infinite range is no limit, as 0
  planner.setMinProgress(0.0);
  EXPECT_EQ(planner.getMinProgress(), 0.0);
}

TEST(ExactRRTConnect, RotateFirstOffByDefaultKeepsStraightEdges) {
  ompl::RNG::setSeed(11);
  og::SimpleSetup ss = makeRodSetup(2.0, 3.0, 1.0);
  auto planner = std::make_shared<ExactRRTConnect>(ss.getSpaceInformation());
  EXPECT_FALSE(planner->getRotateFirst());
  ss.setPlanner(planner);
  ASSERT_EQ(ss.solve(budget()), ob::PlannerStatus::EXACT_SOLUTION);
  // Straight edges: some segment turns and moves at once.
  const og::PathGeometric& path = ss.getSolutionPath();
  int mixed = 0;
  for (unsigned i = 0; i + 1 < path.getStateCount(); ++i) {
    const auto* a = path.getState(i)->as<ob::SE2StateSpace::StateType>();
    const auto* b = path.getState(i + 1)->as<ob::SE2StateSpace::StateType>();
    mixed += (a->getX() != b->getX() || a->getY() != b->getY()) && a->getYaw() != b->getYaw();
  }
  EXPECT_GT(mixed, 0);
}

}  // namespace
}  // namespace mddual::planning
