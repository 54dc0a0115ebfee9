// The Bullet peer in the checker tables (built with mddual_hull_cast only):
// registerHullCastCheckers() appends "hull-cast" once, after the built-in
// checkers; addRigidChecker / addArmChecker refuse bad or clashing entries;
// hull-cast installs and checks the edges of a small scene; the benchmark
// runner runs it on the tiny config with verified solutions.
#include <gtest/gtest.h>
#include <unistd.h>

#include <ompl/base/ScopedState.h>
#include <ompl/util/Console.h>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "mddual/error.h"
#include "mddual/planning/arm_problem.h"
#include "mddual/planning/bench_runner.h"
#include "mddual/planning/checker_registry.h"
#include "mddual/planning/hull_cast_checkers.h"
#include "mddual/scene/loaders.h"
#include "planner_budget.h"
#include "tiny_config.h"

namespace mddual::planning {
namespace {

namespace fs = std::filesystem;
namespace ob = ompl::base;

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "";
}

InstalledChecker installNothing(const RigidCheckerContext&) {
  return {};
}

InstalledChecker installNoArm(const ArmCheckerContext&) {
  return {};
}

TEST(HullCastRegistry, RegistersOnceAfterTheBuiltInCheckers) {
  registerHullCastCheckers();
  registerHullCastCheckers();  // a second call adds nothing
  EXPECT_EQ(rigidCheckerNames(), (std::vector<std::string>{"mdd", "fcl", "fcl-continuous", "hull-cast"}));
  EXPECT_STREQ(findRigidChecker("hull-cast").name, "hull-cast");
  EXPECT_EQ(parseCheckerList("mdd,fcl,hull-cast"), (std::vector<std::string>{"mdd", "fcl", "hull-cast"}));
  EXPECT_EQ(errorOf([] { findRigidChecker("moveit"); }),
            "unknown checker 'moveit' (known: mdd, fcl, fcl-continuous, hull-cast)");
  // The benchmark's default set is the table's.
  EXPECT_EQ(BenchOptions().checkers, rigidCheckerNames());
}

TEST(HullCastRegistry, AddingRefusesBadAndClashingEntries) {
  registerHullCastCheckers();
  EXPECT_NE(errorOf([] {
              addRigidChecker({"hull-cast", "another", &installNothing});
            }).find("already"),
            std::string::npos);
  EXPECT_NE(errorOf([] { addRigidChecker({"mdd", "another", &installNothing}); }).find("already"), std::string::npos);
  EXPECT_NE(errorOf([] { addRigidChecker({"a,b", "comma", &installNothing}); }).find("bad name"), std::string::npos);
  EXPECT_NE(errorOf([] { addRigidChecker({"", "empty", &installNothing}); }).find("bad name"), std::string::npos);
  EXPECT_NE(errorOf([] { addRigidChecker({"x", nullptr, &installNothing}); }).find("must be set"), std::string::npos);
  EXPECT_NE(errorOf([] { addRigidChecker({"x", "no install", nullptr}); }).find("must be set"), std::string::npos);
  EXPECT_NE(errorOf([] { addArmChecker({"fcl-fine", "another", &installNoArm}); }).find("already"), std::string::npos);
  EXPECT_EQ(rigidCheckerNames().size(), 4u);  // nothing added by the refused calls
}

Eigen::Isometry3d at(double x, double y, double z) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(x, y, z);
  return X;
}

// A 0.5 m cube in a 10 m box with a 2 cm wall at x = 5 (as the tables' own
// test): hull-cast passes an edge beside the wall and refuses one through it.
TEST(HullCastRegistry, RigidEntryInstallsAndChecksEdges) {
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  registerHullCastCheckers();
  std::vector<scene::Piece> robot_pieces;
  robot_pieces.push_back(scene::boxPiece(Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Isometry3d::Identity(), "cube"));
  const auto robot = std::make_shared<const scene::RigidBody>(std::move(robot_pieces), "cube");
  std::vector<scene::Piece> world_pieces;
  world_pieces.push_back(scene::boxPiece(Eigen::Vector3d(0.02, 10, 10), at(5, 5, 5), "wall"));
  const auto world = std::make_shared<const scene::World>(std::move(world_pieces), "wall");
  const Eigen::AlignedBox3d bounds(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(10));
  const PlanningSpacePtr space = PlanningSpace::make(SpaceKind::kR3, bounds, 5.0);
  auto si = std::make_shared<ob::SpaceInformation>(space->stateSpace());
  const InstalledChecker installed = findRigidChecker("hull-cast").install({si, space, robot, world, SetupOptions()});
  ASSERT_TRUE(installed.counts);
  ASSERT_NE(std::dynamic_pointer_cast<HullCastMotionValidator>(si->getMotionValidator()), nullptr);
  si->setup();
  ob::ScopedState<> a(si), b(si), c(si);
  space->setPose(at(2, 5, 5), a.get());
  space->setPose(at(2, 8, 5), b.get());
  space->setPose(at(8, 5, 5), c.get());  // beyond the wall: only the edge crosses it
  installed.reset_counts();
  EXPECT_TRUE(si->isValid(a.get()));
  EXPECT_TRUE(si->isValid(c.get()));
  EXPECT_TRUE(si->checkMotion(a.get(), b.get()));
  // A free edge checks the end state of each of OMPL's segments.
  const unsigned n_ab = si->getStateSpace()->validSegmentCount(a.get(), b.get());
  ASSERT_GT(n_ab, 1u);
  EXPECT_EQ(installed.counts().state_checks, 2u + n_ab);
  EXPECT_FALSE(si->checkMotion(a.get(), c.get()));
  const CheckerCounts counts = installed.counts();
  // The edge through the wall stops at its first failing segment.
  EXPECT_GT(counts.state_checks, 2u + n_ab);
  EXPECT_LT(counts.state_checks, 2u + n_ab + si->getStateSpace()->validSegmentCount(a.get(), c.get()));
  EXPECT_EQ(counts.motion_checks, 2u);
  EXPECT_GE(counts.pair_queries, 1u);
}

// The arm table: hull-cast after the built-in arm checkers; on arm7's first
// bookshelf problem it passes the start and the trivial edge from it.
TEST(HullCastRegistry, ArmEntryInstallsAndChecksAnEdge) {
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  registerHullCastCheckers();
  EXPECT_EQ(armCheckerNames(), (std::vector<std::string>{"mdd", "fcl", "fcl-fine", "hull-cast"}));
  EXPECT_EQ(parseArmCheckerList("hull-cast,mdd"), (std::vector<std::string>{"hull-cast", "mdd"}));
  const fs::path arm7 = fs::path(MDDUAL_CONFIGS_DIR) / "arm7";
  const ArmRobot robot = loadArmRobot(arm7 / "arm7.urdf", arm7 / "arm7.srdf");
  const std::vector<scene::MbmProblemFiles> files = scene::listMbmProblems(arm7 / "problems" / "bookshelf_thin");
  ASSERT_FALSE(files.empty());
  const ArmProblem p = loadArmProblem(robot, files[0]);
  const ArmSpacePtr space = ArmSpace::make(p.space->modelPtr(), p.space->variables(), p.start);
  auto si = std::make_shared<ob::SpaceInformation>(space->stateSpace());
  const InstalledChecker installed =
      findArmChecker("hull-cast").install({si, space, p.scene, std::make_shared<const FclArmScene>(p.scene), 1.0 / 32});
  ASSERT_NE(std::dynamic_pointer_cast<ArmHullCastMotionValidator>(si->getMotionValidator()), nullptr);
  si->setup();
  ob::ScopedState<> start(si);
  space->setState(start.get(), p.start.data());
  installed.reset_counts();
  EXPECT_TRUE(si->isValid(start.get()));
  EXPECT_TRUE(si->checkMotion(start.get(), start.get()));
  EXPECT_EQ(installed.counts().state_checks, 2u);  // the start, then the one segment's end
  EXPECT_EQ(installed.counts().motion_checks, 1u);
}

// The tiny config (a wall with a door, translation only: the cast is exact
// there) with mdd and hull-cast: one log each, every run solved and verified.
TEST(HullCastRegistry, BenchRunsHullCastOnTheTinyConfig) {
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  registerHullCastCheckers();
  const fs::path dir =
      fs::temp_directory_path() / ("mddual_hull_cast_registry_" + std::to_string(static_cast<long>(::getpid())));
  fs::remove_all(dir);
  const Problem problem = loadProblem(testing::writeTinyConfig(dir / "cfg"));
  BenchOptions options;
  options.output_dir = dir / "out";
  options.checkers = {"mdd", "hull-cast"};
  options.time_limit = testing::kPlannerSafetyNetSeconds;
  const std::vector<BenchLog> logs = runBench(problem, options);
  ASSERT_EQ(logs.size(), 2u);
  EXPECT_EQ(logs[1].checker, "hull-cast");
  for (const BenchLog& l : logs) {
    EXPECT_TRUE(fs::is_regular_file(dir / "out" / ("tiny-" + l.checker + ".log"))) << l.checker;
    EXPECT_EQ(l.solved, 4) << l.checker;
    EXPECT_EQ(l.verified, 4) << l.checker;
    EXPECT_EQ(l.invalid, 0) << l.checker;
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
}

}  // namespace
}  // namespace mddual::planning
