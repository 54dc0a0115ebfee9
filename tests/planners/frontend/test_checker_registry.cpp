// The checker tables (checker_registry.h): names unique and found, lists
// parsed with the known names in the errors, and every entry of each table
// installs a state checker and a motion validator that check a trivial edge
// and count their work.
#include <gtest/gtest.h>

#include <ompl/base/ScopedState.h>
#include <ompl/util/Console.h>
#include <filesystem>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "mddual/error.h"
#include "mddual/planning/arm_problem.h"
#include "mddual/planning/checker_registry.h"
#include "mddual/scene/loaders.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;

/// The message of the InvalidInputError `f` throws ("" when it throws none).
std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "";
}

/// Names and descriptions: set, unique, and what the names functions list.
template <class Entry>
void expectConsistent(const std::vector<Entry>& table, const std::vector<std::string>& names) {
  ASSERT_FALSE(table.empty());
  ASSERT_EQ(names.size(), table.size());
  std::set<std::string> seen;
  for (std::size_t i = 0; i < table.size(); ++i) {
    const Entry& e = table[i];
    ASSERT_NE(e.name, nullptr);
    ASSERT_NE(e.description, nullptr);
    EXPECT_NE(std::string(e.name), "");
    EXPECT_NE(std::string(e.description), "") << e.name;
    EXPECT_EQ(std::string(e.name).find(','), std::string::npos) << e.name;  // lists are comma-separated
    EXPECT_NE(e.install, nullptr) << e.name;
    EXPECT_TRUE(seen.insert(e.name).second) << "two checkers named " << e.name;
    EXPECT_EQ(names[i], e.name);
  }
}

TEST(CheckerRegistry, RigidTableIsConsistent) {
  expectConsistent(rigidCheckers(), rigidCheckerNames());
  EXPECT_EQ(rigidCheckerNames(), (std::vector<std::string>{"mdd", "fcl", "fcl-continuous"}));
  for (const RigidChecker& c : rigidCheckers()) EXPECT_EQ(&findRigidChecker(c.name), &c);
  EXPECT_EQ(errorOf([] { findRigidChecker("foo"); }), "unknown checker 'foo' (known: mdd, fcl, fcl-continuous)");
  EXPECT_EQ(parseCheckerList("fcl,mdd"), (std::vector<std::string>{"fcl", "mdd"}));
  EXPECT_NE(errorOf([] { parseCheckerList("mdd,foo"); }).find("unknown checker 'foo'"), std::string::npos);
  EXPECT_NE(errorOf([] { parseCheckerList("mdd,mdd"); }).find("given twice"), std::string::npos);
  EXPECT_NE(errorOf([] { parseCheckerList(""); }).find("no checker"), std::string::npos);
  EXPECT_NE(errorOf([] { parseCheckerList("mdd,"); }).find("no checker"), std::string::npos);
  EXPECT_NE(errorOf([] { parseCheckerList("mdd,,fcl"); }).find("empty checker name"), std::string::npos);
}

TEST(CheckerRegistry, ArmTableIsConsistent) {
  expectConsistent(armCheckers(), armCheckerNames());
  EXPECT_EQ(armCheckerNames(), (std::vector<std::string>{"mdd", "fcl", "fcl-fine"}));
  for (const ArmChecker& c : armCheckers()) EXPECT_EQ(&findArmChecker(c.name), &c);
  EXPECT_EQ(errorOf([] { findArmChecker("vamp"); }), "unknown arm checker 'vamp' (known: mdd, fcl, fcl-fine)");
  EXPECT_EQ(parseArmCheckerList("fcl-fine,mdd"), (std::vector<std::string>{"fcl-fine", "mdd"}));
  EXPECT_NE(errorOf([] { parseArmCheckerList("mdd,fcl-continuous"); }).find("unknown arm checker 'fcl-continuous'"),
            std::string::npos);
  EXPECT_NE(errorOf([] { parseArmCheckerList("fcl,fcl"); }).find("given twice"), std::string::npos);
}

/// What every install must leave: both checkers on si, counts that count.
void expectInstalled(const ob::SpaceInformationPtr& si, const InstalledChecker& installed, const char* name) {
  EXPECT_NE(si->getStateValidityChecker(), nullptr) << name;
  EXPECT_NE(si->getMotionValidator(), nullptr) << name;
  ASSERT_TRUE(installed.counts) << name;
  ASSERT_TRUE(installed.reset_counts) << name;
}

Eigen::Isometry3d at(double x, double y, double z) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(x, y, z);
  return X;
}

// A 0.5 m cube in a 10 m box with a 2 cm wall at x = 5: an edge beside the
// wall is free for every checker, an edge ending inside it is not.
TEST(CheckerRegistry, EveryRigidCheckerInstallsAndChecksAnEdge) {
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  std::vector<scene::Piece> robot_pieces;
  robot_pieces.push_back(scene::boxPiece(Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Isometry3d::Identity(), "cube"));
  const auto robot = std::make_shared<const scene::RigidBody>(std::move(robot_pieces), "cube");
  std::vector<scene::Piece> world_pieces;
  world_pieces.push_back(scene::boxPiece(Eigen::Vector3d(0.02, 10, 10), at(5, 5, 5), "wall"));
  const auto world = std::make_shared<const scene::World>(std::move(world_pieces), "wall");
  const Eigen::AlignedBox3d bounds(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(10));
  for (const RigidChecker& checker : rigidCheckers()) {
    const PlanningSpacePtr space = PlanningSpace::make(SpaceKind::kR3, bounds, 5.0);
    auto si = std::make_shared<ob::SpaceInformation>(space->stateSpace());
    const InstalledChecker installed = checker.install({si, space, robot, world, SetupOptions()});
    expectInstalled(si, installed, checker.name);
    si->setup();
    ob::ScopedState<> a(si), b(si), c(si);
    space->setPose(at(2, 5, 5), a.get());
    space->setPose(at(2, 8, 5), b.get());
    space->setPose(at(5, 5, 5), c.get());
    installed.reset_counts();
    EXPECT_TRUE(si->isValid(a.get())) << checker.name;
    EXPECT_TRUE(si->checkMotion(a.get(), b.get())) << checker.name;
    EXPECT_FALSE(si->checkMotion(a.get(), c.get())) << checker.name;
    EXPECT_GE(installed.counts().state_checks, 1u) << checker.name;
    installed.reset_counts();
    EXPECT_EQ(installed.counts().state_checks, 0u) << checker.name;
    EXPECT_EQ(installed.mdd_scene != nullptr, std::string(checker.name) == "mdd") << checker.name;
  }
}

// arm7 on its first bookshelf problem: the start is free, and so is the
// trivial edge from the start to itself, for every arm checker.
TEST(CheckerRegistry, EveryArmCheckerInstallsAndChecksAnEdge) {
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  const std::filesystem::path arm7 = std::filesystem::path(MDDUAL_CONFIGS_DIR) / "arm7";
  const ArmRobot robot = loadArmRobot(arm7 / "arm7.urdf", arm7 / "arm7.srdf");
  const std::vector<scene::MbmProblemFiles> files = scene::listMbmProblems(arm7 / "problems" / "bookshelf_thin");
  ASSERT_FALSE(files.empty());
  const ArmProblem p = loadArmProblem(robot, files[0]);
  const auto fcl = std::make_shared<const FclArmScene>(p.scene);
  for (const ArmChecker& checker : armCheckers()) {
    const ArmSpacePtr space = ArmSpace::make(p.space->modelPtr(), p.space->variables(), p.start);
    auto si = std::make_shared<ob::SpaceInformation>(space->stateSpace());
    const InstalledChecker installed = checker.install({si, space, p.scene, fcl, 1.0 / 32.0});
    expectInstalled(si, installed, checker.name);
    si->setup();
    ob::ScopedState<> start(si);
    space->setState(start.get(), p.start.data());
    installed.reset_counts();
    EXPECT_TRUE(si->isValid(start.get())) << checker.name;
    EXPECT_TRUE(si->checkMotion(start.get(), start.get())) << checker.name;
    EXPECT_GE(installed.counts().state_checks, 1u) << checker.name;
    installed.reset_counts();
    EXPECT_EQ(installed.counts().state_checks, 0u) << checker.name;
  }
}

}  // namespace
}  // namespace mddual::planning
