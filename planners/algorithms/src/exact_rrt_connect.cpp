#include "mddual/planning/exact_rrt_connect.h"

#include <ompl/base/PlannerData.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/tools/config/MagicConstants.h>
#include <ompl/tools/config/SelfConfig.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "mddual/error.h"

namespace mddual::planning {

namespace ob = ompl::base;

ExactRRTConnect::ExactRRTConnect(const ob::SpaceInformationPtr& si) : ob::Planner(si, kExactRRTConnectName) {
  specs_.recognizedGoal = ob::GOAL_SAMPLEABLE_REGION;
  specs_.directed = true;
  Planner::declareParam<double>("range", this, &ExactRRTConnect::setRange, &ExactRRTConnect::getRange, "0.:1.:10000.");
  Planner::declareParam<double>("blocked_range", this, &ExactRRTConnect::setBlockedRange,
                                &ExactRRTConnect::getBlockedRange, "0.:1.:10000.");
  Planner::declareParam<bool>("whole_edge_last_valid", this, &ExactRRTConnect::setWholeEdgeLastValid,
                              &ExactRRTConnect::getWholeEdgeLastValid, "0,1");
  Planner::declareParam<double>("min_progress", this, &ExactRRTConnect::setMinProgress,
                                &ExactRRTConnect::getMinProgress, "0.:0.1:100.");
  Planner::declareParam<double>("probe_steps", this, &ExactRRTConnect::setProbeSteps, &ExactRRTConnect::getProbeSteps,
                                "0.:1.:100.");
  Planner::declareParam<bool>("rotate_first", this, &ExactRRTConnect::setRotateFirst, &ExactRRTConnect::getRotateFirst,
                              "0,1");
}

namespace {

/// Relative slack of the min_progress comparison (in steps): a fraction j /
/// steps times steps is j within a few ulps.
constexpr double kStepRoundoff = 1e-9;
/// A blocked edge gaining less than this many steps adds nothing, whatever
/// min_progress says. With min_progress = 0, edges gaining round-off (their
/// lastValid fraction a few ulps above 0) were kept: near-copies of their
/// start state, on which OMPL's nearest-neighbour structure (GNAT) spent 97%
/// of the run (a hostile-input hunt: thin_walls, 0 of 2 runs solved in 3 s;
/// 2 of 2 in 1 s with min_progress = 1e-14, none with 1e-300).
constexpr double kMinGainSteps = 1e-9;

/// The value in ostream's default format (6 significant digits, "nan", "inf").
std::string text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace

void ExactRRTConnect::setRange(double range) {
  if (!(range >= 0.0)) {
    throw InvalidInputError(std::string(kExactRRTConnectName) + ": range must be >= 0 (0: unlimited), got " +
                            text(range));
  }
  range_ = range;
}

void ExactRRTConnect::setBlockedRange(double range) {
  if (!(range >= 0.0) || !std::isfinite(range)) {
    throw InvalidInputError(std::string(kExactRRTConnectName) +
                            ": blocked_range must be a finite distance >= 0 (0: OMPL's default range), got " +
                            text(range));
  }
  blocked_range_ = range;
}

void ExactRRTConnect::setMinProgress(double steps) {
  if (!(steps >= 0.0) || !std::isfinite(steps)) {
    throw InvalidInputError(std::string(kExactRRTConnectName) +
                            ": min_progress must be a finite number of steps >= 0, got " + text(steps));
  }
  min_progress_ = steps;
}

void ExactRRTConnect::setProbeSteps(double steps) {
  if (!(steps >= 0.0) || !std::isfinite(steps)) {
    throw InvalidInputError(std::string(kExactRRTConnectName) +
                            ": probe_steps must be a finite number of steps >= 0 (0: no probe), got " + text(steps));
  }
  probe_steps_ = steps;
}

ExactRRTConnect::~ExactRRTConnect() {
  freeTree(start_tree_);
  freeTree(goal_tree_);
}

void ExactRRTConnect::setup() {
  Planner::setup();
  // 0: OMPL's default planner range (0.2 of the space's maximum extent),
  // configured as OMPL's RRT-Connect configures its range.
  ompl::tools::SelfConfig config(si_, getName());
  config.configurePlannerRange(blocked_range_);
  auto make = [this]() {
    Tree tree(ompl::tools::SelfConfig::getDefaultNearestNeighbors<Motion*>(this));
    tree->setDistanceFunction([this](const Motion* a, const Motion* b) { return distance(a, b); });
    return tree;
  };
  if (!start_tree_) start_tree_ = make();
  if (!goal_tree_) goal_tree_ = make();
}

void ExactRRTConnect::clear() {
  Planner::clear();
  sampler_.reset();
  freeTree(start_tree_);
  freeTree(goal_tree_);
  connection_ = {nullptr, nullptr};
}

void ExactRRTConnect::freeTree(const Tree& tree) {
  if (!tree) return;
  std::vector<Motion*> motions;
  tree->list(motions);
  for (Motion* m : motions) {
    si_->freeState(m->state);
    delete m;
  }
  tree->clear();
}

double ExactRRTConnect::distance(const Motion* a, const Motion* b) const {
  return si_->distance(a->state, b->state);
}

ExactRRTConnect::Motion* ExactRRTConnect::addMotion(const Tree& tree, Motion* parent, const ob::State* state) {
  auto* m = new Motion;
  m->state = si_->cloneState(state);
  m->parent = parent;
  m->root = parent != nullptr ? parent->root : m->state;
  tree->add(m);
  return m;
}

bool ExactRRTConnect::rotationInPlace(const ob::State* from, const ob::State* to, ob::State* out) const {
  if (!rotate_first_) return false;
  const ob::StateSpace* space = si_->getStateSpace().get();
  if (dynamic_cast<const ob::SE3StateSpace*>(space) != nullptr) {
    const auto* f = from->as<ob::SE3StateSpace::StateType>();
    const auto* t = to->as<ob::SE3StateSpace::StateType>();
    auto* o = out->as<ob::SE3StateSpace::StateType>();
    o->setXYZ(f->getX(), f->getY(), f->getZ());
    o->rotation().x = t->rotation().x;
    o->rotation().y = t->rotation().y;
    o->rotation().z = t->rotation().z;
    o->rotation().w = t->rotation().w;
    return true;
  }
  if (dynamic_cast<const ob::SE2StateSpace*>(space) != nullptr) {
    const auto* f = from->as<ob::SE2StateSpace::StateType>();
    const auto* t = to->as<ob::SE2StateSpace::StateType>();
    auto* o = out->as<ob::SE2StateSpace::StateType>();
    o->setXY(f->getX(), f->getY());
    o->setYaw(t->getYaw());
    return true;
  }
  return false;
}

bool ExactRRTConnect::isProgress(double fraction, const ob::State* from, const ob::State* to) const {
  // Counted in steps from the fraction: OMPL's discrete validator keeps whole
  // steps (j / steps), and a gain of exactly min_progress steps must not be
  // lost to the round-off of a distance comparison (kStepRoundoff).
  const double gain = fraction * std::max(1u, si_->getStateSpace()->validSegmentCount(from, to));
  return gain >= min_progress_ * (1.0 - kStepRoundoff) && gain >= kMinGainSteps;
}

double ExactRRTConnect::blockedStep() const {
  if (blocked_range_ > 0.0) return blocked_range_;
  return ompl::magic::MAX_MOTION_LENGTH_AS_SPACE_EXTENT_FRACTION * si_->getMaximumExtent();
}

ExactRRTConnect::Motion* ExactRRTConnect::upToLastValid(const Tree& tree, Motion* from, const ob::State* to,
                                                        bool* free) {
  ob::State* last = si_->allocState();
  std::pair<ob::State*, double> last_valid(last, 0.0);
  Motion* added = nullptr;
  *free = si_->checkMotion(from->state, to, last_valid);
  if (*free) {
    added = addMotion(tree, from, to);
  } else if (last_valid.second > 0.0 && isProgress(last_valid.second, from->state, to)) {
    added = addMotion(tree, from, last);
  }
  si_->freeState(last);
  return added;
}

ExactRRTConnect::Motion* ExactRRTConnect::edge(const Tree& tree, Motion* from, const ob::State* to, bool* reached) {
  *reached = false;
  const ob::StateSpacePtr& space = si_->getStateSpace();
  ob::State* work = si_->allocState();
  Motion* added = nullptr;
  // 1. The probe (edges longer than probe_steps steps): the state
  //    probe_steps steps in. When it collides the edge is blocked within
  //    them and adds nothing, without its motion check (the header says why).
  const unsigned steps = std::max(1u, space->validSegmentCount(from->state, to));
  if (probe_steps_ > 0.0 && probe_steps_ < steps) {
    space->interpolate(from->state, to, probe_steps_ / steps, work);
    if (!si_->isValid(work)) {
      si_->freeState(work);
      return nullptr;
    }
  }
  // 2. whole_edge_last_valid: the whole edge, kept up to lastValid when
  //    blocked and that is progress (one motion check).
  if (whole_edge_last_valid_) {
    added = upToLastValid(tree, from, to, reached);
  } else if (si_->checkMotion(from->state, to)) {
    // 3. Otherwise the whole edge: one validity check.
    added = addMotion(tree, from, to);
    *reached = true;
  } else if (const double d = si_->distance(from->state, to), step = blockedStep();
             d > step && step / d * steps >= kMinGainSteps) {
    // 4. Blocked, and longer than blocked_range: RRT-Connect's step of
    //    blocked_range toward `to` (a prefix of the edge under OMPL's
    //    interpolation), kept whole when free, else up to lastValid when that
    //    is progress (min_progress of the step's own steps). A blocked edge
    //    no longer than blocked_range adds nothing (the header says why),
    //    nor a step of less than kMinGainSteps of the edge's steps.
    space->interpolate(from->state, to, step / d, work);
    bool step_free = false;
    added = upToLastValid(tree, from, work, &step_free);
  }
  si_->freeState(work);
  return added;
}

ExactRRTConnect::Extend ExactRRTConnect::extend(const Tree& tree, const ob::State* target, Motion** added) {
  // 1. The nearest motion, and the target cut to `range` when one is set.
  Motion probe;
  probe.state = const_cast<ob::State*>(target);  // NearestNeighbors wants a Motion*; it is only read
  Motion* nearest = tree->nearest(&probe);
  const double d = si_->distance(nearest->state, target);
  ob::State* cut = nullptr;
  const ob::State* goal = target;
  if (range_ > 0.0 && d > range_) {
    cut = si_->allocState();
    si_->getStateSpace()->interpolate(nearest->state, target, range_ / d, cut);
    goal = cut;
  }
  // 2. SE(2)/SE(3): first the rotation in place to the goal's orientation
  //    (skipped when there is none to make); a blocked rotation ends the
  //    extension at its last valid state.
  Motion* from = nearest;
  bool reached = false;
  ob::State* turned = si_->allocState();
  bool blocked = false;
  if (rotationInPlace(nearest->state, goal, turned) && si_->distance(nearest->state, turned) > 0.0 &&
      si_->distance(turned, goal) > 0.0) {
    Motion* m = edge(tree, nearest, turned, &reached);
    if (m != nullptr) from = m;
    blocked = !reached;
  }
  si_->freeState(turned);
  // 3. The (remaining) edge to the goal (edge(): the whole edge, or when
  //    blocked its step, kept up to lastValid).
  if (!blocked) {
    Motion* m = edge(tree, from, goal, &reached);
    if (m != nullptr) from = m;
  }
  if (cut != nullptr) si_->freeState(cut);
  if (from == nearest) return Extend::kTrapped;
  *added = from;
  return reached && !blocked && cut == nullptr ? Extend::kReached : Extend::kAdvanced;
}

ob::PlannerStatus ExactRRTConnect::solve(const ob::PlannerTerminationCondition& ptc) {
  // 1. Set-up: start states, goal region, sampler.
  checkValidity();
  auto* goal = dynamic_cast<ob::GoalSampleableRegion*>(pdef_->getGoal().get());
  if (goal == nullptr) {
    OMPL_ERROR("%s: unknown type of goal", getName().c_str());
    return ob::PlannerStatus::UNRECOGNIZED_GOAL_TYPE;
  }
  while (const ob::State* st = pis_.nextStart()) addMotion(start_tree_, nullptr, st);
  if (start_tree_->size() == 0) {
    OMPL_ERROR("%s: motion planning start tree could not be initialized", getName().c_str());
    return ob::PlannerStatus::INVALID_START;
  }
  if (!goal->couldSample()) {
    OMPL_ERROR("%s: insufficient states in sampleable goal region", getName().c_str());
    return ob::PlannerStatus::INVALID_GOAL;
  }
  if (!sampler_) sampler_ = si_->allocStateSampler();
  ob::State* sample = si_->allocState();
  bool start_side = true;
  bool solved = false;

  // 2. Alternate: EXTEND one tree toward a random state, then CONNECT the
  //    other tree to the new node (one exact edge: it reaches it or stops).
  while (!ptc && !solved) {
    if (goal_tree_->size() == 0 || pis_.getSampledGoalsCount() < goal_tree_->size() / 2) {
      const ob::State* g = goal_tree_->size() == 0 ? pis_.nextGoal(ptc) : pis_.nextGoal();
      if (g != nullptr) addMotion(goal_tree_, nullptr, g);
      if (goal_tree_->size() == 0) {
        OMPL_ERROR("%s: unable to sample any valid states for goal tree", getName().c_str());
        break;
      }
    }
    const Tree& tree = start_side ? start_tree_ : goal_tree_;
    const Tree& other = start_side ? goal_tree_ : start_tree_;
    sampler_->sampleUniform(sample);
    Motion* added = nullptr;
    if (extend(tree, sample, &added) != Extend::kTrapped) {
      Motion* joined = nullptr;
      // CONNECT: extend the other tree toward the new node while it advances
      // (a step kept whole or up to lastValid; see the header) until it
      // reaches the node or adds nothing.
      Extend connect = Extend::kAdvanced;
      while (connect == Extend::kAdvanced && !ptc) connect = extend(other, added->state, &joined);
      if (connect == Extend::kReached) {
        Motion* from_start = start_side ? added : joined;
        Motion* from_goal = start_side ? joined : added;
        // 3. The path: start root ... from_start, then from_goal's ancestors
        //    (from_goal itself is a copy of the joining state).
        auto path = std::make_shared<ompl::geometric::PathGeometric>(si_);
        std::vector<Motion*> chain;
        for (Motion* m = from_start; m != nullptr; m = m->parent) chain.push_back(m);
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) path->append((*it)->state);
        for (Motion* m = from_goal->parent; m != nullptr; m = m->parent) path->append(m->state);
        connection_ = {from_start->state, from_goal->state};
        pdef_->addSolutionPath(path, false, 0.0, getName());
        solved = true;
      }
    }
    start_side = !start_side;
  }
  si_->freeState(sample);
  OMPL_INFORM("%s: created %u states (%u start + %u goal)", getName().c_str(), start_tree_->size() + goal_tree_->size(),
              start_tree_->size(), goal_tree_->size());
  return solved ? ob::PlannerStatus::EXACT_SOLUTION : ob::PlannerStatus::TIMEOUT;
}

void ExactRRTConnect::getPlannerData(ob::PlannerData& data) const {
  Planner::getPlannerData(data);
  auto add = [&](const Tree& tree, bool start) {
    if (!tree) return;
    std::vector<Motion*> motions;
    tree->list(motions);
    for (const Motion* m : motions) {
      if (m->parent == nullptr) {
        start ? data.addStartVertex(ob::PlannerDataVertex(m->state, 1))
              : data.addGoalVertex(ob::PlannerDataVertex(m->state, 2));
      } else if (start) {
        data.addEdge(ob::PlannerDataVertex(m->parent->state, 1), ob::PlannerDataVertex(m->state, 1));
      } else {
        data.addEdge(ob::PlannerDataVertex(m->state, 2), ob::PlannerDataVertex(m->parent->state, 2));
      }
    }
  };
  add(start_tree_, true);
  add(goal_tree_, false);
  if (connection_.first != nullptr) {
    data.addEdge(ob::PlannerDataVertex(connection_.first, 1), ob::PlannerDataVertex(connection_.second, 2));
  }
}

}  // namespace mddual::planning
