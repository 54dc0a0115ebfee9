// The benchmark runner in-process on the tiny config: one OMPL log per
// checker with the experiment parameters and the extra run properties, every
// run kept, verification counted, shards that partition the runs, option
// errors. (`mddual bench` end to end, with the database and the report, is
// tested in tests/cli.)
#include <gtest/gtest.h>
#include <unistd.h>

#include <ompl/util/Console.h>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "mddual/error.h"
#include "mddual/planning/bench_runner.h"
#include "planner_budget.h"
#include "tiny_config.h"

namespace mddual::planning {
namespace {

namespace fs = std::filesystem;

/// An OMPL benchmark log, read back (the parts the tests look at).
struct ParsedLog {
  std::string experiment;
  std::map<std::string, std::string> parameters;  ///< "checker STRING" -> "mdd"
  int runs_per_planner = -1;
  /// planner -> runs, each run property name -> value.
  std::map<std::string, std::vector<std::map<std::string, std::string>>> planners;
};

ParsedLog parseLog(const fs::path& file) {
  std::ifstream in(file);
  EXPECT_TRUE(in.good()) << file;
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ParsedLog log;
  std::size_t i = 0;
  auto next = [&]() -> const std::string& {
    if (i >= lines.size()) throw std::runtime_error("log ends early: " + file.string());
    return lines[i++];
  };
  auto count = [](const std::string& line) { return std::stoi(line.substr(0, line.find(' '))); };
  next();  // OMPL version
  log.experiment = next().substr(std::string("Experiment ").size());
  for (int k = count(next()); k > 0; --k) {
    const std::string& p = next();
    const std::size_t eq = p.find(" = ");
    log.parameters[p.substr(0, eq)] = p.substr(eq + 3);
  }
  while (next().find(" runs per planner") == std::string::npos) {
  }
  log.runs_per_planner = count(lines[i - 1]);
  while (lines[i].find(" planners") == std::string::npos || lines[i].find(' ') != lines[i].rfind(' ')) next();
  for (int planners = count(next()); planners > 0; --planners) {
    const std::string name = next();
    for (int k = count(next()); k > 0; --k) next();  // common properties
    std::vector<std::string> names;
    for (int k = count(next()); k > 0; --k) names.push_back(next());
    auto& runs = log.planners[name];
    for (int k = count(next()); k > 0; --k) {
      std::stringstream values(next());
      std::map<std::string, std::string> run;
      for (const std::string& n : names) {
        std::string v;
        std::getline(values, v, ';');
        if (!v.empty() && v[0] == ' ') v.erase(0, 1);
        run[n] = v;
      }
      runs.push_back(run);
    }
    std::string end = next();
    if (end != ".") {  // progress properties
      for (int k = count(end); k > 0; --k) next();
      for (int k = count(next()); k > 0; --k) next();
      end = next();
    }
    EXPECT_EQ(end, ".");
  }
  return log;
}

class BenchRunner : public ::testing::Test {
 protected:
  void SetUp() override {
    ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("mddual_bench_runner_" + std::string(info->name()) + "_" + std::to_string(static_cast<long>(::getpid())));
    fs::remove_all(dir_);
    problem_ = loadProblem(testing::writeTinyConfig(dir_ / "cfg"));
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
  Problem problem_;
};

const std::vector<std::string> kExtraProperties = {
    "run index INTEGER",        "state checks INTEGER",   "motion checks INTEGER",  "pair queries INTEGER",
    "sub edges INTEGER",        "checking time REAL",     "solve time REAL",        "verified BOOLEAN",
    "invalid solution BOOLEAN", "invalid by mdd BOOLEAN", "invalid by fcl BOOLEAN", "invalid raw solution BOOLEAN",
    "verification time REAL",
};

TEST_F(BenchRunner, WritesOneLogPerCheckerWithVerifiedRuns) {
  BenchOptions options;
  options.output_dir = dir_ / "out";
  // Not the config's 0.2 s: every run must solve, so the limit is only a
  // safety net (RRT-Connect stops at its first solution, seeded by the main).
  options.time_limit = testing::kPlannerSafetyNetSeconds;
  int started = 0;
  int finished = 0;
  BenchObserver observer;
  observer.run_started = [&](const std::string&, const std::string&, int, int runs, int) {
    ++started;
    EXPECT_EQ(runs, 2);
  };
  observer.run_finished = [&](const std::string&, const std::string&, int, bool, bool, bool) { ++finished; };
  const std::vector<BenchLog> logs = runBench(problem_, options, observer);
  ASSERT_EQ(logs.size(), 3u);
  EXPECT_EQ(started, 12);
  EXPECT_EQ(finished, 12);
  for (const BenchLog& l : logs) {
    EXPECT_EQ(l.file, dir_ / "out" / ("tiny-" + l.checker + ".log"));
    const ParsedLog log = parseLog(l.file);
    EXPECT_EQ(log.experiment, "tiny-" + l.checker);
    EXPECT_EQ(log.parameters.at("config STRING"), "tiny");
    EXPECT_EQ(log.parameters.at("checker STRING"), l.checker);
    EXPECT_EQ(log.parameters.at("shard STRING"), "0/1");
    EXPECT_EQ(log.runs_per_planner, 2);
    ASSERT_EQ(log.planners.size(), 2u);
    int solved = 0;
    int verified = 0;
    int invalid = 0;
    for (const auto& [name, runs] : log.planners) {
      EXPECT_TRUE(name == "geometric_rrtconnect" || name == "geometric_mdd_rrtconnect") << name;
      ASSERT_EQ(runs.size(), 2u);
      for (std::size_t k = 0; k < runs.size(); ++k) {
        const auto& run = runs[k];
        for (const std::string& p : kExtraProperties) EXPECT_EQ(run.count(p), 1u) << p;
        EXPECT_EQ(run.at("run index INTEGER"), std::to_string(k));
        const bool exact = run.at("solved BOOLEAN") == "1" && run.at("approximate solution BOOLEAN") != "1";
        const bool v = run.at("verified BOOLEAN") == "1";
        const bool inv = run.at("invalid solution BOOLEAN") == "1";
        EXPECT_FALSE(v && inv);
        EXPECT_EQ(exact, v || inv);  // every solution verified one way or the other, nothing else
        EXPECT_EQ(inv, run.at("invalid by mdd BOOLEAN") == "1" || run.at("invalid by fcl BOOLEAN") == "1");
        EXPECT_GT(std::stoll(run.at("motion checks INTEGER")), 0);
        // The planner's own solve() holds its checks and lies within OMPL's time.
        const double solve = std::stod(run.at("solve time REAL"));
        EXPECT_GT(solve, 0.0);
        EXPECT_LE(solve, std::stod(run.at("time REAL")));
        EXPECT_LE(std::stod(run.at("checking time REAL")), solve);
        solved += exact ? 1 : 0;
        verified += v ? 1 : 0;
        invalid += inv ? 1 : 0;
      }
    }
    EXPECT_EQ(l.solved, solved);
    EXPECT_EQ(l.verified, verified);
    EXPECT_EQ(l.invalid, invalid);
    if (l.checker == "mdd") {
      EXPECT_EQ(invalid, 0) << "our checker's solutions are never invalid";
      EXPECT_EQ(verified, 4) << "the tiny problem is easy";
    }
  }
}

TEST_F(BenchRunner, ShardsPartitionTheRuns) {
  using Key = std::tuple<std::string, std::string, std::string>;  // checker, planner, run index
  auto keys = [&](const BenchShard& shard, const std::string& sub) {
    BenchOptions options;
    options.output_dir = dir_ / sub;
    options.runs = 3;
    options.time_limit = 0.1;
    options.checkers = {"mdd", "fcl"};
    options.planners = {"mdd_rrtconnect"};
    options.shard = shard;
    std::multiset<Key> out;
    for (const BenchLog& l : runBench(problem_, options)) {
      EXPECT_EQ(l.file.filename().string(), logFileName("tiny", l.checker, shard));
      const ParsedLog log = parseLog(l.file);
      EXPECT_EQ(log.parameters.at("shard STRING"), toString(shard));
      for (const auto& [name, runs] : log.planners) {
        for (const auto& run : runs) out.insert({l.checker, name, run.at("run index INTEGER")});
      }
    }
    return out;
  };
  const std::multiset<Key> all = keys(BenchShard{}, "all");
  EXPECT_EQ(all.size(), 6u);
  const std::multiset<Key> s0 = keys(BenchShard{0, 2}, "shards");
  const std::multiset<Key> s1 = keys(BenchShard{1, 2}, "shards");
  EXPECT_EQ(s0.size(), 4u);  // runs 0 and 2
  EXPECT_EQ(s1.size(), 2u);  // run 1
  std::multiset<Key> merged = s0;
  merged.insert(s1.begin(), s1.end());
  EXPECT_EQ(merged, all);
  EXPECT_TRUE(fs::exists(dir_ / "shards" / "tiny-mdd.shard0of2.log"));
  EXPECT_TRUE(fs::exists(dir_ / "shards" / "tiny-fcl.shard1of2.log"));
}

TEST(BenchShards, SeedsAreTheCampaignsOwnWhenUnshardedAndDistinctPerShard) {
  EXPECT_EQ(shardSeed(7, BenchShard{}), 7u);
  std::set<std::uint32_t> seen;
  for (long seed : {1L, 2L, 3L, 1000000000L}) {
    for (int n : {2, 3, 10}) {
      for (int i = 0; i < n; ++i) {
        const std::uint32_t s = shardSeed(seed, BenchShard{i, n});
        EXPECT_GE(s, 1u);
        EXPECT_TRUE(seen.insert(s).second) << "seed " << seed << " shard " << i << "/" << n << " repeats " << s;
      }
    }
  }
  // seed + I would make "--seed 1 --shard 1/2" and "--seed 2 --shard 0/2" the same stream.
  EXPECT_NE(shardSeed(1, BenchShard{1, 2}), shardSeed(2, BenchShard{0, 2}));
  EXPECT_EQ(shardSeed(5, BenchShard{1, 4}), shardSeed(5, BenchShard{1, 4}));
}

TEST(BenchShards, ReportNeedsCompleteShardSets) {
  auto error = [](const std::vector<fs::path>& logs) -> std::string {
    try {
      checkShardSets(logs);
    } catch (const InvalidInputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(error({"d/tiny-mdd.log", "d/tiny-fcl.log"}), "");
  EXPECT_EQ(error({"d/tiny-mdd.shard0of2.log", "d/tiny-mdd.shard1of2.log", "d/tiny-fcl.log"}), "");
  EXPECT_EQ(error({"d/other.log", "d/tiny-mdd.shardXof2.log", "d/tiny-mdd.shard1of.log"}), "");  // not shard names
  EXPECT_NE(error({"d/tiny-mdd.log", "d/tiny-mdd.shard0of2.log", "d/tiny-mdd.shard1of2.log"})
                .find("tiny-mdd: both an unsharded log and shard logs"),
            std::string::npos);
  EXPECT_NE(error({"d/tiny-mdd.shard0of2.log", "d/tiny-mdd.shard1of2.log", "d/tiny-mdd.shard0of3.log",
                   "d/tiny-mdd.shard1of3.log", "d/tiny-mdd.shard2of3.log"})
                .find("tiny-mdd: shard logs of different shard counts (2, 3)"),
            std::string::npos);
  EXPECT_NE(error({"d/tiny-fcl.shard0of3.log", "d/tiny-fcl.shard2of3.log"}).find("tiny-fcl: shard logs missing: 1/3"),
            std::string::npos);
}

TEST_F(BenchRunner, OptionErrors) {
  auto expectError = [&](const std::function<void(BenchOptions&)>& edit, const std::string& needle) {
    BenchOptions options;
    options.output_dir = dir_ / "err";
    edit(options);
    try {
      runBench(problem_, options);
      ADD_FAILURE() << "no error (expected '" << needle << "')";
    } catch (const InvalidInputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expectError([](BenchOptions& o) { o.runs = 0; }, "--runs must be at least 1");
  expectError([](BenchOptions& o) { o.time_limit = 0.0; }, "time limit must be a positive");
  // Limits OMPL would overflow (the deadline, the byte count): every run would end at once, unsolved.
  expectError([](BenchOptions& o) { o.time_limit = 1e18; }, "time limit must be a positive number of seconds, at most");
  expectError([](BenchOptions& o) { o.mem_limit = 1e300; }, "memory limit must be a positive number of MB, at most");
  expectError([](BenchOptions& o) { o.checkers.clear(); }, "no checker");
  expectError([](BenchOptions& o) { o.shard = BenchShard{2, 3}; }, "only 2 runs per planner, so at most 2 shards");
  expectError([](BenchOptions& o) { o.planners = {"rrtt"}; }, "unknown planner 'rrtt': not in tiny.cfg");
  // A start in collision: refused before anything runs (OMPL would report
  // every run unsolved, "Invalid start"); the message is checkStartAndGoal's.
  Eigen::Isometry3d start = problem_.scene->start;
  start.translation().x() = 5.0;
  scene::ProblemScene moved = *problem_.scene;
  moved.start = start;
  problem_ = makeProblem(problem_.config, moved);
  expectError([](BenchOptions&) {}, "tiny.cfg: the start state (position 5, 5, 5) is in collision: robot piece");
  // A name too long for the log files' names.
  scene::ProblemConfig long_name = problem_.config;
  long_name.name = std::string(kMaxProblemNameBytes + 1, 'n');
  problem_ = makeProblem(long_name, *problem_.scene);
  expectError([](BenchOptions&) {}, "tiny.cfg: the problem name '" + std::string(kMaxProblemNameBytes + 1, 'n') +
                                        "' is too long: it names the experiment and the log files; at most 128 bytes");
  EXPECT_FALSE(fs::exists(dir_ / "err" / "tiny-mdd.log"));
  EXPECT_FALSE(fs::exists(dir_ / "err"));
}

}  // namespace
}  // namespace mddual::planning
