// `mddual bench` and `mddual bench-report` on hostile input: a
// start or goal state in collision or out of bounds, planner parameters that
// OMPL checks at set-up, an output folder that cannot be written, a 10 MB
// problem name, a log cut off inside its CPU-info block
// (ompl_benchmark_statistics loops forever on it), a copied log, a report
// step that does not finish, and the shard seeding described by --help.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "tiny_config.h"

namespace mddual::cli_test {
namespace {

namespace fs = std::filesystem;

/// The tiny cfg in `dir` with one line replaced.
fs::path tinyConfigWith(const fs::path& dir, const std::string& from, const std::string& to) {
  const fs::path cfg = testing::writeTinyConfig(dir);
  std::string text = readFile(cfg.string());
  const std::size_t at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("no '" + from + "' in the tiny cfg");
  testing::writeTextFile(cfg, text.replace(at, from.size(), to));
  return cfg;
}

TEST(CliBenchHostile, InvalidStartOrGoalIsNamedBeforePlanning) {
  const TempDir dir;
  const fs::path base(dir.path());
  struct Case {
    fs::path cfg;
    std::string message;
  };
  const std::vector<Case> cases = {
      {tinyConfigWith(base / "start", "start.x = 2\n", "start.x = 5\n"),
       "mddual: tiny.cfg: the start state (position 5, 5, 5) is in collision: robot piece \"robot.urdf: link "
       "'cube_link', collision 0 (box)\" overlaps world piece \"world.urdf: link 'wall_link', collision 0 (box)\" "
       "(exact check; touching counts as collision); the deepest overlap is 0.26 (penetration depth of pair 1 of 1); "
       "FCL's collide() on the same pieces finds a contact\n"},
      {tinyConfigWith(base / "goal", "goal.x = 8\n", "goal.x = 12\n"),
       "mddual: tiny.cfg: the goal state is outside the bounds of the space: goal.x = 12 is not in [0, 10] "
       "(volume.min.x, volume.max.x)\n"},
  };
  for (const Case& c : cases) {
    const fs::path out = c.cfg.parent_path() / "out";
    const CliRun run = runCli({"bench", c.cfg.string(), "--output", out.string()});
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_EQ(run.err, c.message);
    EXPECT_EQ(run.out, "");
    EXPECT_FALSE(fs::exists(out)) << "nothing ran";
  }
}

// Parameters that OMPL checks only when the planner is set up, or that set
// the MDD validator's discarded fraction: the message names the cfg's line and
// the planner (it named neither before).
TEST(CliBenchHostile, PlannerParametersCheckedAtSetUpAreNamed) {
  const TempDir dir;
  const fs::path base(dir.path());
  struct Case {
    std::string line;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"kpiece.min_valid_path_fraction = 0",
       "planner 'kpiece': The minimum valid path fraction must be in the range (0,1] (OMPL's check at the planner's "
       "set-up)\n"},
      {"kpiece.failed_expansion_score_factor = 0",
       "planner 'kpiece': Failed expansion cell score factor must be in the range (0,1] (OMPL's check at the "
       "planner's set-up)\n"},
      {"kpiece.min_valid_path_fraction = -1",
       "planner 'kpiece': min_valid_path_fraction: MddMotionValidator: the discarded lastValid fraction must be in "
       "[0, 1], got -1.000000\n"},
  };
  int k = 0;
  for (const Case& c : cases) {
    const fs::path cfg =
        tinyConfigWith(base / std::to_string(k++), "rrtconnect =\nmdd_rrtconnect =\n", "kpiece =\n" + c.line + "\n");
    const std::string text = readFile(cfg.string());
    const std::size_t line =
        1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + text.find("kpiece ="), '\n'));
    const CliRun run = runCli({"bench", cfg.string(), "--checkers", "mdd", "--runs", "1", "--time-limit", "0.2",
                               "--output", (cfg.parent_path() / "out").string()});
    EXPECT_EQ(run.exit_code, 2) << c.line << ": " << run.err;
    const std::string expected = "mddual: tiny.cfg:" + std::to_string(line) + ": " + c.message;
    EXPECT_NE(run.err.find(expected), std::string::npos) << c.line << ": expected " << expected << "\ngot " << run.err;
  }
}

// A bad value for a planner that --planners leaves out is refused too (it
// passed unnoticed).
TEST(CliBenchHostile, PlannersLeftOutByPlannersAreCheckedToo) {
  const TempDir dir;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"kpiece.range = nan", "planner 'kpiece': parameter 'range' = 'nan': not a finite number"},
      {"kpiece.min_valid_path_fraction = -1", "planner 'kpiece': min_valid_path_fraction: "},
      {"kpiece.min_valid_path_fraction = 0", "planner 'kpiece': The minimum valid path fraction must be in"},
  };
  int k = 0;
  for (const auto& [line, message] : cases) {
    const fs::path cfg = tinyConfigWith(fs::path(dir.path()) / std::to_string(k++), "mdd_rrtconnect =\n",
                                        "mdd_rrtconnect =\nkpiece =\n" + line + "\n");
    const CliRun run = runCli({"bench", cfg.string(), "--checkers", "mdd", "--planners", "rrtconnect", "--runs", "1",
                               "--output", (cfg.parent_path() / "out").string()});
    EXPECT_EQ(run.exit_code, 2) << line << ": " << run.err;
    EXPECT_NE(run.err.find(message), std::string::npos) << line << ": " << run.err;
  }
}

// An output folder that cannot be written is refused before the runs (it was
// found when the log was written, after every run, without the reason).
// /proc: a folder that exists and takes no new file, even for root.
TEST(CliBenchHostile, AnUnwritableOutputFolderIsRefusedBeforeTheRuns) {
  if (!fs::exists("/proc/self")) GTEST_SKIP() << "no /proc (as root the command would create the folder)";
  const TempDir dir;
  const fs::path cfg = testing::writeTinyConfig(fs::path(dir.path()));
  const CliRun run = runCli({"bench", cfg.string(), "--checkers", "mdd", "--runs", "1", "--output", "/proc"});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("mddual: cannot write in the output folder /proc: "), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find("1 runs"), std::string::npos) << "no run: " << run.err;
}

TEST(CliBenchHostile, HugeNamesAreCutInMessages) {
  const TempDir dir;
  const fs::path base(dir.path());
  const std::string name(10 * 1024 * 1024, 'a');
  const fs::path cfg = tinyConfigWith(base / "long", "name = tiny\n", "name = " + name + "\n");
  const CliRun run = runCli({"bench", cfg.string(), "--output", (base / "out").string()});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err, "mddual: " + cfg.filename().string() + ": the problem name '" + std::string(200, 'a') +
                         "... (10485760 bytes)' is too long: it names the experiment and the log files; at most "
                         "128 bytes\n");
  EXPECT_FALSE(fs::exists(base / "out"));
  // A flag's value.
  const CliRun runs = runCli({"bench", cfg.string(), "--runs", std::string(100000, '9')});
  EXPECT_EQ(runs.exit_code, 2);
  EXPECT_EQ(runs.err,
            "mddual: --runs: '" + std::string(200, '9') + "... (100000 bytes)' is not an integer in [1, 1000000000]\n");
}

/// A small benchmark log as mddual bench writes them (two runs of one
/// planner, the experiment parameters bench-report groups by).
std::string smallLog() {
  return "OMPL version 1.5.2\n"
         "Experiment tiny-mdd\n"
         "3 experiment properties\n"
         "checker STRING = mdd\n"
         "config STRING = tiny\n"
         "shard STRING = 0/1\n"
         "Running on testhost\n"
         "Starting at 2024-01-01 00:00:00\n"
         "<<<|\n"
         "setup\n"
         "|>>>\n"
         "<<<|\n"
         "Architecture: x86_64\n"
         "CPU(s): 2\n"
         "|>>>\n"
         "1 is the random seed\n"
         "1 seconds per run\n"
         "1000 MB per run\n"
         "2 runs per planner\n"
         "0.5 seconds spent to collect the data\n"
         "1 planners\n"
         "geometric_rrtconnect\n"
         "1 common properties\n"
         "range = 1\n"
         "5 properties for each run\n"
         "time REAL\n"
         "solved BOOLEAN\n"
         "verified BOOLEAN\n"
         "invalid solution BOOLEAN\n"
         "run index INTEGER\n"
         "2 runs\n"
         "0.1; 1; 1; 0; 0; \n"
         "0.3; 1; 1; 0; 1; \n"
         ".\n";
}

TEST(CliBenchHostile, LogCutInsideItsCpuInfoIsRefusedAtOnce) {
  const TempDir dir;
  const std::string log = smallLog();
  const std::string cut = log.substr(0, log.find("CPU(s)"));  // lines 1 to 13
  dir.write("tiny-mdd.log", cut);
  const CliRun run = runCli({"bench-report", dir.path()});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err, "mddual: bench-report: " + dir.path() +
                         "/tiny-mdd.log: line 14: expected the line '|>>>' closing the CPU-info block opened at line "
                         "12, found the end of the file (the log is cut off or is not an OMPL benchmark log)\n");
  EXPECT_FALSE(fs::exists(fs::path(dir.path()) / "bench.db"));
}

/// An ompl_benchmark_statistics of our own (a python script, run as OMPL's
/// is), first on PATH while this object lives.
class FakeStatistics {
 public:
  FakeStatistics(const fs::path& dir, const std::string& script) {
    const fs::path fake = dir / "ompl_benchmark_statistics";
    testing::writeTextFile(fake, script);
    if (::chmod(fake.c_str(), 0755) != 0) throw std::runtime_error("chmod failed");
    const char* path = std::getenv("PATH");
    saved_ = path ? path : "";
    ::setenv("PATH", (dir.string() + ":" + saved_).c_str(), 1);
  }
  ~FakeStatistics() { ::setenv("PATH", saved_.c_str(), 1); }
  FakeStatistics(const FakeStatistics&) = delete;
  FakeStatistics& operator=(const FakeStatistics&) = delete;

 private:
  std::string saved_;
};

TEST(CliBenchHostile, CopiedLogIsCountedOnce) {
  // The statistics step records the logs it is handed (one line each).
  const TempDir dir;
  const fs::path logs = fs::path(dir.path()) / "logs";
  testing::writeTextFile(logs / "tiny-mdd.log", smallLog());
  testing::writeTextFile(logs / "tiny-mdd (copy).log", smallLog());
  testing::writeTextFile(logs / "tiny-fcl.log", smallLog() + "\n");  // another content
  const fs::path handed = fs::path(dir.path()) / "handed.txt";
  const FakeStatistics fake(
      fs::path(dir.path()) / "bin",
      "import sys\nwith open('" + handed.string() +
          "', 'w') as f:\n    f.write(''.join(a + '\\n' for a in sys.argv[1:] if a.endswith('.log')))\n"
          "sys.exit(3)\n");
  const CliRun run = runCli({"bench-report", logs.string()});
  EXPECT_EQ(run.exit_code, 2);  // the fake fails: no database
  EXPECT_NE(run.err.find("bench-report: tiny-mdd (copy).log has the same content as tiny-mdd.log: counted once\n"),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("bench-report: 2 logs in " + logs.string()), std::string::npos) << run.err;
  EXPECT_EQ(readFile(handed.string()),
            (logs / "tiny-fcl.log").string() + "\n" + (logs / "tiny-mdd.log").string() + "\n");
}

TEST(CliBenchHostile, ReportStepsAreStoppedAtTheirTimeLimit) {
  // An ompl_benchmark_statistics that never finishes.
  const TempDir dir;
  const fs::path logs = fs::path(dir.path()) / "logs";
  testing::writeTextFile(logs / "tiny-mdd.log", smallLog());
  CliRun run;
  CliRun bad;
  {
    const FakeStatistics fake(fs::path(dir.path()) / "bin", "import time\ntime.sleep(60)\n");
    run = runCli({"bench-report", logs.string(), "--timeout", "0.5"});
    bad = runCli({"bench-report", logs.string(), "--timeout", "nan"});
  }
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(countLines(run.err), 2) << run.err;  // "bench-report: 1 logs in DIR", then the error
  EXPECT_NE(
      run.err.find("mddual: ompl_benchmark_statistics did not finish within 0.5 s on the logs in " + logs.string() +
                   " and was stopped (its output: " + (logs / "ompl_benchmark_statistics.out").string() +
                   "; a larger limit: --report-timeout / bench-report --timeout)\n"),
      std::string::npos)
      << run.err;
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.err, "mddual: --timeout: 'nan' is not a positive number\n");
}

TEST(CliBenchHostile, HelpDescribesTheShardSeeds) {
  const CliRun run = runCli({"bench", "--help"});
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_EQ(run.out.find("seed + I"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("seeds OMPL with a splitmix64 hash of (seed, I, N)"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("shard I of N: a splitmix64 hash of K, I and N"), std::string::npos) << run.out;
}

}  // namespace
}  // namespace mddual::cli_test
