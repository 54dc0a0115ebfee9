// The arm benchmark in process (runArmBench): MotionBenchMaker planner_ids
// mapped to OMPL's planners, the name a problem directory gives its logs,
// --problems and --shard on a problem directory (which problems each shard
// plans), and the solution paths it saves.
#include <gtest/gtest.h>

#include <ompl/util/Console.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "mddual/planning/arm_bench.h"
#include "mddual/planning/planner_factory.h"
#include "scene_test_util.h"

namespace mddual::planning {
namespace {

namespace fs = std::filesystem;

const fs::path kArm7 = fs::path(MDDUAL_CONFIGS_DIR) / "arm7";

TEST(ArmBench, MapsMotionBenchMakerPlannerIdsToOmplPlanners) {
  EXPECT_EQ(plannerFromPlannerId("RRTConnectkConfigDefault"), "rrtconnect");
  EXPECT_EQ(plannerFromPlannerId("BKPIECEkConfigDefault"), "bkpiece");
  EXPECT_EQ(plannerFromPlannerId("LBKPIECEkConfigDefault"), "lbkpiece");
  EXPECT_EQ(plannerFromPlannerId("KPIECEkConfigDefault"), "kpiece");
  EXPECT_EQ(plannerFromPlannerId("RRTstarkConfigDefault"), "rrtstar");
  EXPECT_EQ(plannerFromPlannerId("PRMkConfigDefault"), "prm");
  // Variants named with a trailing word, and plain OMPL names.
  EXPECT_EQ(plannerFromPlannerId("BKPIECEGood"), "bkpiece");
  EXPECT_EQ(plannerFromPlannerId("RRTConnectFastShortcut"), "rrtconnect");
  EXPECT_EQ(plannerFromPlannerId("KPIECE1"), "kpiece");
  EXPECT_EQ(plannerFromPlannerId("rrtconnect"), "rrtconnect");
  // No planner: nothing left once the trailing words are dropped.
  EXPECT_EQ(plannerFromPlannerId("Dijkstra"), "");
  EXPECT_EQ(plannerFromPlannerId("kConfigDefault"), "");
  EXPECT_EQ(plannerFromPlannerId(""), "");
  EXPECT_EQ(plannerFromPlannerId("GoodPlanner"), "");
}

TEST(ArmBench, NamesAProblemDirectoryByItsLastComponent) {
  EXPECT_EQ(problemDirName("problems/cage"), "cage");
  EXPECT_EQ(problemDirName("problems/cage/"), "cage");
  EXPECT_EQ(problemDirName("problems/cage/."), "cage");
  EXPECT_EQ(problemDirName("problems/cage/../box/"), "box");
}

/// The problems whose logs a run wrote, as "NNNN".
std::set<std::string> problemsLogged(const std::vector<ArmBenchLog>& logs) {
  std::set<std::string> out;
  for (const ArmBenchLog& log : logs) {
    EXPECT_EQ(log.checker, "mdd");
    EXPECT_TRUE(fs::is_regular_file(log.file)) << log.file;
    out.insert(log.problem.substr(log.problem.size() - 4));
  }
  return out;
}

/// One RRT-Connect run with mdd on each of the first `problems` problems.
ArmBenchOptions oneRunOptions(int problems) {
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  ArmBenchOptions options;
  options.checkers = {"mdd"};
  options.planners = {"RRTConnect"};
  options.runs = 1;
  options.time_limit = 10.0;  // a safety net: table_pick's problems take milliseconds
  options.problems = problems;
  return options;
}

TEST(ArmBench, ShardsSplitTheFirstProblemsOfADirectory) {
  const ArmRobot robot = loadArmRobot(kArm7 / "arm7.urdf", kArm7 / "arm7.srdf");
  scene::testing::TempDir dir;
  ArmBenchOptions options = oneRunOptions(3);
  std::set<std::string> all;
  for (int index = 0; index < 2; ++index) {
    options.shard = {index, 2};
    options.output_dir = dir.path() / ("logs" + std::to_string(index));
    options.paths_dir = dir.path() / ("paths" + std::to_string(index));
    const std::vector<ArmBenchLog> logs = runArmBench(robot, kArm7 / "problems" / "table_pick", options);
    const std::set<std::string> mine = problemsLogged(logs);
    // Problem k (0-based, by number) belongs to shard k mod 2.
    const std::set<std::string> expected =
        index == 0 ? std::set<std::string>{"0001", "0003"} : std::set<std::string>{"0002"};
    EXPECT_EQ(mine, expected);
    all.insert(mine.begin(), mine.end());
    int saved = 0;
    for (const ArmBenchLog& log : logs) {
      saved += log.solved;
      EXPECT_EQ(log.solved, 1) << log.problem << ": table_pick's problems take milliseconds";
      EXPECT_EQ(log.invalid, 0) << log.problem;
    }
    int files = 0;
    for (const auto& entry : fs::directory_iterator(options.paths_dir)) {
      ++files;
      EXPECT_EQ(entry.path().filename().string().rfind("table_pick-000", 0), 0u) << entry.path();
    }
    EXPECT_EQ(files, saved);
  }
  EXPECT_EQ(all.size(), 3u);
}

TEST(ArmBench, APathThatCannotBeWrittenFailsTheBenchmark) {
  const ArmRobot robot = loadArmRobot(kArm7 / "arm7.urdf", kArm7 / "arm7.srdf");
  scene::testing::TempDir dir;
  ArmBenchOptions options = oneRunOptions(1);
  options.output_dir = dir.path() / "logs";
  options.paths_dir = dir.path() / "paths";
  // A folder where the path's file would go: it cannot be written there.
  fs::create_directories(options.paths_dir / "table_pick-0001-mdd-RRTConnect-0.yaml");
  try {
    runArmBench(robot, kArm7 / "problems" / "table_pick", options);
    ADD_FAILURE() << "no error for a path that cannot be written";
  } catch (const scene::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("table_pick-0001-mdd-RRTConnect-0.yaml: cannot be written ("),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mddual::planning
