// `mddual bench PROBLEM_DIR --robot URDF --srdf SRDF` end to end on two of
// arm7's problems: one log per (problem, checker), the database with one
// config for the directory, every exact solution verified, the mdd
// checker's never invalid; and the errors of a problem directory given
// without its robot, with an unknown planner, with a start or a goal in
// collision, or with a start outside its joint limits.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "cli_runner.h"

namespace mddual::cli_test {
namespace {

namespace fs = std::filesystem;

const fs::path kArm7 = fs::path(MDDUAL_CONFIGS_DIR) / "arm7";

/// Two problems of a set copied to `to` (a directory named like the set).
fs::path copyProblems(const fs::path& to, const std::string& set) {
  fs::create_directories(to);
  for (const char* f : {"scene0001.yaml", "request0001.yaml", "scene0002.yaml", "request0002.yaml"}) {
    fs::copy_file(kArm7 / "problems" / set / f, to / f);
  }
  return to;
}

std::string sqlCount(const fs::path& db, const std::string& query) {
  const std::string command = "'" + std::string(MDDUAL_TEST_PYTHON) +
                              "' -c \"import sqlite3, sys; print(sqlite3.connect(sys.argv[1]).execute(sys.argv[2])"
                              ".fetchone()[0])\" '" +
                              db.string() + "' \"" + query + "\"";
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  std::array<char, 256> buf{};
  while (pipe != nullptr && std::fgets(buf.data(), static_cast<int>(buf.size()), pipe) != nullptr) out += buf.data();
  if (pipe != nullptr) pclose(pipe);
  while (!out.empty() && (out.back() == '\n')) out.pop_back();
  return out;
}

// The default arm checkers: the built-in ones, and the Bullet peer's
// hull-cast when the CLI is built with Bullet.
#ifdef MDDUAL_HAVE_BULLET
const std::vector<std::string> kArmCheckers = {"mdd", "fcl", "fcl-fine", "hull-cast"};
#else
const std::vector<std::string> kArmCheckers = {"mdd", "fcl", "fcl-fine"};
#endif

TEST(CliBenchArms, PlansAProblemDirectoryWithEveryChecker) {
  TempDir dir;
  const fs::path problems = copyProblems(fs::path(dir.path()) / "shelf", "bookshelf_thin");
  const fs::path out = fs::path(dir.path()) / "out";
  const fs::path paths = fs::path(dir.path()) / "paths";
  // The directory as shell completion gives it, with a trailing '/'.
  const CliRun run = runCli({"bench", problems.string() + "/", "--robot", (kArm7 / "arm7.urdf").string(), "--srdf",
                             (kArm7 / "arm7.srdf").string(), "--planners", "RRTConnectkConfigDefault", "--runs", "1",
                             "--time-limit", "5", "--output", out.string(), "--save-paths", paths.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
  for (const char* problem : {"0001", "0002"}) {
    for (const std::string& checker : kArmCheckers) {
      EXPECT_TRUE(fs::is_regular_file(out / ("shelf-" + std::string(problem) + "-" + checker + ".log")))
          << problem << " " << checker;
    }
  }
  const fs::path db = out / "bench.db";
  ASSERT_TRUE(fs::is_regular_file(db));
  EXPECT_EQ(sqlCount(db, "select count(*) from runs"), std::to_string(2 * kArmCheckers.size()));
  EXPECT_EQ(sqlCount(db, "select count(distinct config) from experiments"), "1");
  EXPECT_EQ(sqlCount(db, "select count(distinct checker) from experiments"), std::to_string(kArmCheckers.size()));
  // Every exact solution is either verified or invalid; mdd's never invalid.
  EXPECT_EQ(sqlCount(db,
                     "select count(*) from runs where (solved = 1 and (approximate_solution is null or "
                     "approximate_solution = 0)) != (verified + invalid_solution = 1)"),
            "0");
  EXPECT_EQ(sqlCount(db,
                     "select count(*) from runs r join experiments e on r.experimentid = e.id where e.checker = "
                     "'mdd' and r.invalid_solution = 1"),
            "0");
  // The planner's own solve() holds every check it made and lies within
  // OMPL's time, which also holds the benchmark's thread around it.
  EXPECT_EQ(sqlCount(db,
                     "select count(*) from runs where not (solve_time > 0 and solve_time <= time and "
                     "checking_time <= solve_time)"),
            "0");
  EXPECT_NE(run.out.find("| shelf | RRTConnectkConfigDefault | mdd | 2 |"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("| shelf | RRTConnectkConfigDefault | fcl-fine | 2 |"), std::string::npos) << run.out;
  // --save-paths: one trajectory per exact solution, named by its problem,
  // checker, planner and run, "-invalid" on those the verification refused.
  int saved = 0, saved_invalid = 0;
  for (const auto& entry : fs::directory_iterator(paths)) {
    const std::string name = entry.path().filename().string();
    ++saved;
    saved_invalid += name.find("-invalid.yaml") != std::string::npos ? 1 : 0;
    EXPECT_EQ(name.rfind("shelf-000", 0), 0u) << name;
    std::ifstream in(entry.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("joint_names: [joint1, joint2, joint3, joint4, joint5, joint6, joint7]"), std::string::npos)
        << name;
  }
  EXPECT_TRUE(fs::is_regular_file(paths / "shelf-0001-mdd-RRTConnectkConfigDefault-0.yaml"));
  EXPECT_EQ(std::to_string(saved),
            sqlCount(db,
                     "select count(*) from runs where solved = 1 and (approximate_solution is null or "
                     "approximate_solution = 0)"));
  EXPECT_EQ(std::to_string(saved_invalid), sqlCount(db, "select count(*) from runs where invalid_solution = 1"));
}

TEST(CliBenchArms, BadProblemsAndFlagsFailWithOneClearLine) {
  TempDir dir;
  const fs::path problems = copyProblems(fs::path(dir.path()) / "cage", "cage");
  const std::string urdf = (kArm7 / "arm7.urdf").string();
  const std::string srdf = (kArm7 / "arm7.srdf").string();
  auto expectError = [](const CliRun& run, const std::string& part) {
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.err.find(part), std::string::npos) << run.err;
    EXPECT_EQ(splitLines(run.err).size(), 1u) << run.err;
  };
  expectError(runCli({"bench", problems.string()}), "is a problem directory: give --robot URDF and --srdf SRDF");
  expectError(runCli({"bench", problems.string(), "--robot", urdf, "--srdf", srdf, "--planners", "Dijkstra"}),
              "planner 'Dijkstra' is not an OMPL geometric planner");
  expectError(runCli({"bench", problems.string(), "--robot", urdf, "--srdf", srdf, "--checkers", "mdd,vamp"}),
              "unknown arm checker 'vamp'");
  expectError(runCli({"bench", problems.string(), "--robot", urdf, "--srdf", srdf, "--group", "legs"}),
              "has no group 'legs'");
  // Each case rewrites the second request with one bad state and expects
  // its file and the reason.
  auto expectRequestError = [&](const std::string& request, const std::string& part) {
    std::ofstream(problems / "request0002.yaml") << "group_name: arm\n" << request;
    expectError(runCli({"bench", problems.string(), "--robot", urdf, "--srdf", srdf}), "request0002.yaml: " + part);
  };
  const std::string goal_joint1 =
      "goal_constraints:\n  - joint_constraints:\n      - {joint_name: joint1, position: 0.5}\n";
  // A start state with the arm folded into the base.
  expectRequestError(
      "start_state:\n  joint_state:\n    name: [joint2, joint4]\n    position: [1.7, -3.0]\n" + goal_joint1,
      "the start state is in collision: link '");
  // The same folded arm as the goal.
  expectRequestError(
      "goal_constraints:\n  - joint_constraints:\n      - {joint_name: joint2, position: 1.7}\n"
      "      - {joint_name: joint4, position: -3.0}\n",
      "the goal state is in collision: link '");
  // A start value outside its joint's limits (joint4: [-3, -0.07]).
  expectRequestError("start_state:\n  joint_state:\n    name: [joint4]\n    position: [0.5]\n" + goal_joint1,
                     "start_state: joint 'joint4' = 0.500000 is outside its limits [-3.000000, -0.070000]");
}

}  // namespace
}  // namespace mddual::cli_test
