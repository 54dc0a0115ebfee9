// A planning program against the installed mddual package (examples/README.md;
// built and run by the ctest install.find_package_consumer):
//
//   plan_with_mddual CONFIG.cfg [SECONDS]
//
// loads the scene of an OMPL.app-style config, puts mddual's exact checkers on
// an OMPL SpaceInformation, plans with RRT-Connect, re-checks the solution
// independently (PathVerifier) and prints the directed clearance ahead of each
// segment of the path: how far the robot could go on along the segment's
// direction before it touches the world. Exit status 0 on success, 1 when no
// valid solution is found or a check fails, 2 for bad input.
#include <mddual/planning/clearance.h>
#include <mddual/planning/mdd_checkers.h>
#include <mddual/planning/path_verifier.h>
#include <mddual/planning/problem_setup.h>
#include <mddual/planning/state_space.h>
#include <ompl/base/ScopedState.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>

namespace {

namespace mp = mddual::planning;
namespace ob = ompl::base;
namespace og = ompl::geometric;

/// Default planning time limit, seconds. RRT-Connect stops at its first
/// solution (a few milliseconds on configs/thin_walls); this only bounds a
/// hard problem.
constexpr double kDefaultPlanningSeconds = 5.0;
/// Time for OMPL's path simplification, seconds.
constexpr double kSimplifySeconds = 0.5;
/// OMPL's random seed: the same run every time.
constexpr std::uint32_t kSeed = 1;

int fail(const std::string& what) {
  std::fprintf(stderr, "plan_with_mddual: %s\n", what.c_str());
  return 1;
}

int run(const std::string& cfg, double seconds) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  ompl::RNG::setSeed(kSeed);

  // 1. The scene of the config: robot and world of convex pieces, the kind of
  //    state space, its position bounds, the start and the goal.
  const mp::Problem problem = mp::loadProblem(cfg);
  mp::checkStartAndGoal(problem);  // a start or goal in collision is named, not planned from
  const mddual::scene::ProblemScene& sc = *problem.scene;
  std::printf("scene %s: robot of %zu pieces, world of %zu pieces\n", problem.name.c_str(), sc.robot.pieces().size(),
              sc.world.pieces().size());

  // 2. OMPL with mddual's checkers: exact state validity (MDD-DUAL intersect)
  //    and motion validation (exact for translation edges, sound for rotating ones).
  const mp::PlanningSpacePtr space = mp::PlanningSpace::make(
      mp::toPlanningKind(sc.space), sc.bounds, sc.start.translation().z(), Eigen::Quaterniond(sc.start.linear()));
  og::SimpleSetup ss(space->stateSpace());
  const ob::SpaceInformationPtr& si = ss.getSpaceInformation();
  const auto scene = std::make_shared<const mp::MddScene>(problem.robot(), problem.world());
  si->setStateValidityChecker(std::make_shared<mp::MddStateValidityChecker>(si, space, scene));
  si->setMotionValidator(std::make_shared<mp::MddMotionValidator>(si, space, scene));

  ob::ScopedState<> start(space->stateSpace());
  ob::ScopedState<> goal(space->stateSpace());
  space->setPose(sc.start, start.get());
  space->setPose(sc.goal, goal.get());
  ss.setStartAndGoalStates(start, goal);
  ss.setPlanner(std::make_shared<og::RRTConnect>(si));
  ss.setup();

  // 3. Plan.
  const ob::PlannerStatus status = ss.solve(seconds);
  if (status != ob::PlannerStatus::EXACT_SOLUTION) {
    char limit[32];
    std::snprintf(limit, sizeof limit, "%g", seconds);
    return fail(std::string("RRT-Connect found no exact solution in ") + limit + " s (" + status.asString() + ")");
  }
  ss.simplifySolution(kSimplifySeconds);
  const og::PathGeometric& path = ss.getSolutionPath();
  std::printf("solution: %zu states, length %.6g\n", path.getStateCount(), path.length());

  // 4. Independent re-check: exact MDD edges at a finer rotation tolerance
  //    plus a dense FCL check of the same pieces.
  const mp::PathVerifier verifier(problem.robot(), problem.world(), sc.bounds);
  const mp::VerifyResult verdict = verifier.verify(*space, path);
  if (!verdict.valid) {
    return fail("the solution is not valid (mdd segment " + std::to_string(verdict.mdd_segment) + ", fcl segment " +
                std::to_string(verdict.fcl_segment) + ")");
  }
  std::printf("verified: valid (%lld FCL samples)\n", verdict.fcl_samples);

  // 5. Directed clearance ahead of each segment: along the segment's
  //    direction, from its start. A free translation segment ends before the
  //    first contact (touching counts as collision), so clearance > length.
  int errors = 0;
  const auto n_states = static_cast<unsigned int>(path.getStateCount());
  for (unsigned int i = 0; i + 1 < n_states; ++i) {
    const ob::State* s1 = path.getState(i);
    const ob::State* s2 = path.getState(i + 1);
    const mp::EdgeMotion motion = space->motion(s1, s2);
    const mp::EdgeContact edge = mp::edgeContact(*scene, *space, s1, s2);
    if (edge.collides) {
      std::printf("segment %u: collides at fraction %.6g\n", i, edge.fraction);
      ++errors;
      continue;
    }
    if (motion.length() == 0.0) {
      std::printf("segment %u: rotation only\n", i);
      continue;
    }
    const mp::DirectedClearance c = mp::directedClearance(*scene, *space, s1, motion.p_end - motion.p_start);
    std::string contact = "nothing ahead";
    if (std::isfinite(c.distance) && c.contact.world_piece >= 0) {
      contact = "first contact: " + sc.world.pieces()[static_cast<std::size_t>(c.contact.world_piece)].origin;
    }
    std::printf("segment %u: length %.6g%s, clearance ahead %.6g (%s)\n", i, motion.length(),
                motion.rotates() ? " (rotating)" : "", c.distance, contact.c_str());
    if (c.start_collides || (!motion.rotates() && !(c.distance > motion.length()))) {
      std::printf("  error: a free translation segment must end before the first contact\n");
      ++errors;
    }
  }
  if (errors > 0) return fail(std::to_string(errors) + " segment(s) failed the clearance checks");
  std::printf("ok\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: plan_with_mddual CONFIG.cfg [SECONDS]\n");
    return 2;
  }
  double seconds = kDefaultPlanningSeconds;
  if (argc == 3) {
    char* end = nullptr;
    seconds = std::strtod(argv[2], &end);
    if (end == argv[2] || *end != '\0' || !(seconds > 0.0) || !std::isfinite(seconds)) {
      std::fprintf(stderr, "plan_with_mddual: SECONDS must be a positive number, not '%s'\n", argv[2]);
      return 2;
    }
  }
  try {
    return run(argv[1], seconds);
  } catch (const std::exception& e) {  // mddual's errors name the file, line or value at fault
    std::fprintf(stderr, "plan_with_mddual: %s\n", e.what());
    return 2;
  }
}
