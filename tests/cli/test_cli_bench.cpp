// `mddual bench` and `mddual bench-report` end to end on the tiny config
// (tests/planners/frontend/tiny_config.h): logs, database, plot, summary,
// verification in the database; shards merged by bench-report give the runs
// of one unsharded run; bad configs and flags fail with one clear line.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "tiny_config.h"

namespace mddual::cli_test {
namespace {

namespace fs = std::filesystem;

// The default checkers of a cfg: the built-in ones, and the Bullet peer's
// hull-cast when the CLI is built with Bullet.
#ifdef MDDUAL_HAVE_BULLET
const std::vector<std::string> kCheckers = {"mdd", "fcl", "fcl-continuous", "hull-cast"};
const std::string kKnownCheckers = "mdd, fcl, fcl-continuous, hull-cast";
#else
const std::vector<std::string> kCheckers = {"mdd", "fcl", "fcl-continuous"};
const std::string kKnownCheckers = "mdd, fcl, fcl-continuous";
#endif

/// Runs a shell command, returns its standard output (fails the test on a
/// non-zero status).
std::string shell(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) {
    ADD_FAILURE() << "popen failed: " << command;
    return out;
  }
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), pipe) != nullptr) out += buf.data();
  const int status = pclose(pipe);
  EXPECT_EQ(status, 0) << command << "\n" << out;
  return out;
}

/// The rows of an SQL query on a database, as lines "a|b|c" (python3's sqlite3).
std::vector<std::string> sql(const fs::path& db, const std::string& query) {
  const std::string python = MDDUAL_TEST_PYTHON;
  const std::string script =
      "import sqlite3, sys\n"
      "for row in sqlite3.connect(sys.argv[1]).execute(sys.argv[2]):\n"
      "    print('|'.join('' if v is None else str(v) for v in row))\n";
  return splitLines(shell("'" + python + "' -c \"" + script + "\" '" + db.string() + "' \"" + query + "\""));
}

std::set<std::string> runKeys(const fs::path& db) {
  const auto rows = sql(db,
                        "select e.checker, p.name, r.run_index from runs r join experiments e on "
                        "r.experimentid = e.id join plannerConfigs p on r.plannerid = p.id");
  return {rows.begin(), rows.end()};
}

// --allow-invalid-endpoints: a goal in contact (the cube's face on the
// wall's) no longer stops the command; the runs go on, the checkers that
// find the goal in collision solve none of them, and the contact is noted
// under the summary table with its message.
TEST(CliBench, AllowInvalidEndpointsRunsAndSaysSo) {
  TempDir dir;
  const fs::path cfg = testing::writeTinyConfig(fs::path(dir.path()) / "cfg");
  std::string text = readFile(cfg.string());
  text.replace(text.find("goal.x = 8\n"), 11, "goal.x = 5.26\n");
  testing::writeTextFile(cfg, text);
  const fs::path out = fs::path(dir.path()) / "out";
  const std::vector<std::string> args{"bench",      cfg.string(), "--output", out.string(), "--checkers",   "mdd,fcl",
                                      "--planners", "rrtconnect", "--runs",   "1",          "--time-limit", "0.2"};
  const CliRun refused = runCli(args);
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  std::vector<std::string> allowed_args = args;
  allowed_args.push_back("--allow-invalid-endpoints");
  const CliRun run = runCli(allowed_args);
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
  const std::string contact = "tiny.cfg: the goal state (position 5.26, 5, 5) is in collision: robot piece";
  EXPECT_NE(run.err.find("bench: warning: " + contact), std::string::npos) << run.err;
  const std::string summary = readFile((out / "summary.md").string());
  EXPECT_NE(summary.find("Endpoints in contact (run with --allow-invalid-endpoints)"), std::string::npos) << summary;
  EXPECT_NE(summary.find("- " + contact), std::string::npos) << summary;
  EXPECT_NE(run.out.find("Endpoints in contact"), std::string::npos) << run.out;
  // Both checkers find the touching goal in collision: two runs, none solved.
  const fs::path db = out / "bench.db";
  EXPECT_EQ(sql(db, "select count(*), sum(solved) from runs"), std::vector<std::string>{"2|0"});
}

TEST(CliBench, EndToEnd) {
  TempDir dir;
  const fs::path cfg = testing::writeTinyConfig(fs::path(dir.path()) / "cfg");
  const fs::path out = fs::path(dir.path()) / "out";
  // A time limit far above the runs' (RRT-Connect stops at its first
  // solution): only a safety net, so every run solves on any machine.
  const CliRun run = runCli({"bench", cfg.string(), "--output", out.string(), "--time-limit", "300"});
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;

  // Logs, database, plot, summary.
  for (const std::string& checker : kCheckers) {
    EXPECT_TRUE(fs::is_regular_file(out / ("tiny-" + checker + ".log"))) << checker;
  }
  const fs::path db = out / "bench.db";
  ASSERT_TRUE(fs::is_regular_file(db));
  const fs::path png = out / "plots" / "tiny.png";
  ASSERT_TRUE(fs::is_regular_file(png));
  EXPECT_EQ(readFile(png.string()).substr(1, 3), "PNG");
  const std::string summary = readFile((out / "summary.md").string());
  EXPECT_NE(summary.find("| config | planner | checker | runs | success |"), std::string::npos) << summary;
  EXPECT_NE(run.out.find(summary), std::string::npos) << "the summary table is printed";
  EXPECT_NE(run.out.find("| tiny | mdd_rrtconnect | mdd | 2 |"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("| tiny | rrtconnect | fcl-continuous | 2 |"), std::string::npos) << run.out;

  // Progress: one line per (checker, planner) when standard error is not a terminal.
  EXPECT_NE(run.err.find("bench: tiny | mdd | rrtconnect: 2 runs,"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("bench: scene: robot '"), std::string::npos) << run.err;  // the scene summary
  EXPECT_NE(run.err.find("bench: tiny | fcl-continuous | mdd_rrtconnect: 2 runs,"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find('\r'), std::string::npos);

  // The database: one experiment per checker with its parameters, 4 runs
  // each, the verification properties on every run and consistent.
  std::vector<std::string> experiments;
  for (const std::string& c : kCheckers) experiments.push_back("tiny-" + c + "|tiny|" + c + "|0/1");
  std::sort(experiments.begin(), experiments.end(), [](const std::string& a, const std::string& b) {
    return a.substr(0, a.find('|')) < b.substr(0, b.find('|'));  // by name, as the query
  });
  EXPECT_EQ(sql(db, "select name, config, checker, shard from experiments order by name"), experiments);
  EXPECT_EQ(sql(db, "select count(*) from runs"), std::vector<std::string>{std::to_string(4 * kCheckers.size())});
  EXPECT_EQ(sql(db,
                "select count(*) from runs where verified is null or invalid_solution is null or "
                "verification_time is null or state_checks is null or checking_time is null or run_index is null "
                "or solve_time is null"),
            std::vector<std::string>{"0"});
  // The planner's own solve() holds every check it made and lies within
  // OMPL's time, which also holds the benchmark's thread around it.
  EXPECT_EQ(sql(db,
                "select count(*) from runs where not (solve_time > 0 and solve_time <= time and "
                "checking_time <= solve_time)"),
            std::vector<std::string>{"0"});
  EXPECT_EQ(sql(db,
                "select count(*) from runs where (solved = 1 and (approximate_solution is null or "
                "approximate_solution = 0)) != (verified + invalid_solution = 1)"),
            std::vector<std::string>{"0"});
  EXPECT_EQ(sql(db,
                "select sum(r.invalid_solution) from runs r join experiments e on r.experimentid = e.id "
                "where e.checker = 'mdd'"),
            std::vector<std::string>{"0"});
  // The tiny problem is easy: our checker's 4 runs all solve and verify.
  EXPECT_EQ(sql(db,
                "select sum(r.verified) from runs r join experiments e on r.experimentid = e.id "
                "where e.checker = 'mdd'"),
            std::vector<std::string>{"4"});
  // The summary counts what the database holds: its invalid column per
  // (planner, checker) and its success rate.
  const auto groups = sql(db,
                          "select p.name, e.checker, sum(r.invalid_solution), sum(r.verified), count(*) from runs r "
                          "join experiments e on r.experimentid = e.id join plannerConfigs p on r.plannerid = p.id "
                          "group by p.name, e.checker");
  ASSERT_EQ(groups.size(), 2 * kCheckers.size());
  for (const std::string& g : groups) {
    std::vector<std::string> f;
    std::string cell;
    for (char c : g + "|") {
      if (c == '|') {
        f.push_back(cell);
        cell.clear();
      } else {
        cell += c;
      }
    }
    const std::string planner = f[0].substr(std::string("geometric_").size());
    const int success = 100 * std::stoi(f[3]) / std::stoi(f[4]);
    const std::string prefix =
        "| tiny | " + planner + " | " + f[1] + " | " + f[4] + " | " + std::to_string(success) + "% |";
    const std::size_t at = summary.find(prefix);
    ASSERT_NE(at, std::string::npos) << prefix << "\n" << summary;
    const std::string line = summary.substr(at, summary.find('\n', at) - at);
    // ... | invalid | invalid raw |
    const std::size_t last = line.rfind(" | ", line.size() - 3);
    const std::size_t before = line.rfind(" | ", last - 1);
    EXPECT_EQ(line.substr(before + 3, last - before - 3), f[2]) << line;
  }
}

#ifdef MDDUAL_HAVE_BULLET
// The Bullet peer by name, beside mdd and fcl: a log, runs in the database,
// a summary row, and the help lists it.
TEST(CliBench, RunsTheHullCastPeer) {
  TempDir dir;
  const fs::path cfg = testing::writeTinyConfig(fs::path(dir.path()) / "cfg");
  const fs::path out = fs::path(dir.path()) / "out";
  const CliRun run = runCli({"bench", cfg.string(), "--output", out.string(), "--checkers", "mdd,fcl,hull-cast",
                             "--planners", "rrtconnect", "--runs", "1", "--time-limit", "300"});
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
  EXPECT_TRUE(fs::is_regular_file(out / "tiny-hull-cast.log"));
  EXPECT_EQ(sql(out / "bench.db", "select count(*) from runs"), std::vector<std::string>{"3"});
  // Translation only: the cast is exact, its solution verifies.
  EXPECT_EQ(sql(out / "bench.db",
                "select r.verified from runs r join experiments e on r.experimentid = e.id "
                "where e.checker = 'hull-cast'"),
            std::vector<std::string>{"1"});
  EXPECT_NE(run.out.find("| tiny | rrtconnect | hull-cast | 1 | 100% |"), std::string::npos) << run.out;
  const CliRun help = runCli({"bench", "--help"});
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("hull-cast"), std::string::npos) << help.out;
}
#endif

TEST(CliBench, ShardsMergeToTheUnshardedRuns) {
  TempDir dir;
  const fs::path cfg = testing::writeTinyConfig(fs::path(dir.path()) / "cfg");
  const fs::path all = fs::path(dir.path()) / "all";
  const fs::path shards = fs::path(dir.path()) / "shards";
  const std::vector<std::string> common{"--runs",     "3",       "--time-limit", "0.1",
                                        "--checkers", "mdd,fcl", "--planners",   "mdd_rrtconnect"};
  auto bench = [&](const fs::path& out, const std::string& shard) {
    std::vector<std::string> args{"bench", cfg.string(), "--output", out.string()};
    args.insert(args.end(), common.begin(), common.end());
    if (!shard.empty()) args.insert(args.end(), {"--shard", shard, "--seed", "7"});
    return runCli(args);
  };
  const CliRun unsharded = bench(all, "");
  ASSERT_EQ(unsharded.exit_code, 0) << unsharded.err;
  for (const char* s : {"0/2", "1/2"}) {
    const CliRun r = bench(shards, s);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("mddual bench-report " + shards.string()), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  EXPECT_FALSE(fs::exists(shards / "bench.db")) << "a shard builds no database";
  for (const char* f :
       {"tiny-mdd.shard0of2.log", "tiny-mdd.shard1of2.log", "tiny-fcl.shard0of2.log", "tiny-fcl.shard1of2.log"}) {
    EXPECT_TRUE(fs::is_regular_file(shards / f)) << f;
  }
  // Each shard has a seed of its own (a hash of 7, I, N; exact values in test_bench_runner), in its log.
  auto seedOf = [&](const char* log) {
    const std::string text = readFile((shards / log).string());
    const std::size_t at = text.find(" is the random seed");
    const std::size_t start = text.rfind('\n', at);
    return at == std::string::npos || start == std::string::npos ? "" : text.substr(start + 1, at - start - 1);
  };
  const std::string seed0 = seedOf("tiny-mdd.shard0of2.log");
  const std::string seed1 = seedOf("tiny-mdd.shard1of2.log");
  EXPECT_FALSE(seed0.empty());
  EXPECT_NE(seed0, seed1);
  EXPECT_NE(seed0, "7");
  EXPECT_EQ(seed0, seedOf("tiny-fcl.shard0of2.log")) << "one seed per shard, every checker";

  const CliRun report = runCli({"bench-report", shards.string()});
  ASSERT_EQ(report.exit_code, 0) << report.err;
  EXPECT_NE(report.out.find("| tiny | mdd_rrtconnect | mdd | 3 |"), std::string::npos) << report.out;
  EXPECT_TRUE(fs::is_regular_file(shards / "plots" / "tiny.png"));
  const std::set<std::string> merged = runKeys(shards / "bench.db");
  EXPECT_EQ(merged.size(), 6u);
  EXPECT_EQ(merged, runKeys(all / "bench.db"));
  EXPECT_EQ(sql(shards / "bench.db", "select shard from experiments order by shard, checker"),
            (std::vector<std::string>{"0/2", "0/2", "1/2", "1/2"}));
  // bench --report DIR is the same step.
  const CliRun again = runCli({"bench", "--report", shards.string()});
  EXPECT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(runKeys(shards / "bench.db"), merged) << "the database is rebuilt, not appended to";
}

struct BadCase {
  std::vector<std::string> args;  ///< after "bench" (CFG: the tiny cfg)
  std::string needle;
};

TEST(CliBench, BadConfigsAndFlagsFailWithOneClearLine) {
  TempDir dir;
  const fs::path base = fs::path(dir.path());
  const std::string cfg = testing::writeTinyConfig(base / "good").string();
  testing::TinyConfigText malformed;
  malformed.problem_extra = "this line has no equals sign\n";
  const std::string bad_line = testing::writeTinyConfig(base / "malformed", malformed).string();
  testing::TinyConfigText unknown;
  unknown.planners = "rrtconnect =\nfoo =\n";
  const std::string bad_planner = testing::writeTinyConfig(base / "unknown", unknown).string();
  const std::string out = (base / "out").string();
  const std::vector<BadCase> cases = {
      {{(base / "missing.cfg").string()}, "missing.cfg"},
      {{bad_line}, "tiny.cfg:26"},
      {{bad_planner}, "tiny.cfg:34: unknown planner 'foo'"},
      {{cfg, "--checkers", "foo"}, "--checkers: unknown checker 'foo' (known: " + kKnownCheckers + ")"},
      {{cfg, "--checkers", "mdd,,fcl"}, "--checkers: empty checker name"},
      {{cfg, "--shard", "3/2"}, "--shard '3/2': expected I/N with 0 <= I < N"},
      {{cfg, "--shard", "x"}, "--shard 'x'"},
      {{cfg, "--runs", "0"}, "--runs: '0' is not an integer in [1, 1000000000]"},
      {{cfg, "--runs", "two"}, "--runs: 'two' is not an integer in [1, 1000000000]"},
      {{cfg, "--time-limit=-1"}, "--time-limit: '-1' is not a positive number"},
      {{cfg, "--time-limit", "1e-320"}, "--time-limit: '1e-320' is out of the range of double precision"},
      {{cfg, "--output", ""}, "--output: an empty value (leave the option out for its default)"},
      {{cfg, "--planners", ""}, "--planners: an empty value (leave the option out for its default)"},
      {{cfg, "--runs", ""}, "--runs: an empty value (leave the option out for its default)"},
      {{cfg, "--seed", ""}, "--seed: an empty value (leave the option out for its default)"},
      {{cfg, "--time-limit", "1e18", "--output", out}, "the time limit must be a positive number of seconds, at most"},
      {{cfg, "--seed", "0"}, "--seed: '0' is not an integer in [1, 1000000000]"},
      {{cfg, "--last-valid-level", "9"}, "--last-valid-level: '9' is not an integer in [0, 8]"},
      {{cfg, "--last-valid-level", "-1"}, "--last-valid-level: '-1' is not an integer in [0, 8]"},
      {{cfg, "--last-valid-level", "1.5"}, "--last-valid-level: '1.5' is not an integer in [0, 8]"},
      {{cfg, "--checkers", "fcl", "--last-valid-level", "2"},
       "--last-valid-level: it sets the mdd checker, which --checkers leaves out"},
      {{cfg, "--planners", "prn"}, "unknown planner 'prn': not in tiny.cfg (its planners: rrtconnect, mdd_rrtconnect)"},
      {{cfg, "--shard", "2/3", "--output", out}, "--shard 2/3: only 2 runs per planner, so at most 2 shards"},
      {{}, "no config file given"},
      {{cfg, "--report", out}, "either a config file or --report DIR"},
  };
  for (const BadCase& c : cases) {
    std::vector<std::string> args{"bench"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const CliRun r = runCli(args);
    std::string shown;
    for (const auto& a : args) shown += a + " ";
    EXPECT_EQ(r.exit_code, 2) << shown << r.err;
    EXPECT_EQ(countLines(r.err), 1) << shown << r.err;
    EXPECT_EQ(r.err.rfind("mddual: ", 0), 0u) << shown << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << shown << "\nexpected: " << c.needle << "\ngot: " << r.err;
    EXPECT_TRUE(r.out.empty()) << shown << r.out;
  }
  EXPECT_FALSE(fs::exists(base / "out" / "tiny-mdd.log"));

  // bench-report on logs that do not form complete shard sets: nothing is built.
  TempDir mixed;
  for (const char* f : {"tiny-mdd.log", "tiny-mdd.shard0of2.log", "tiny-fcl.shard1of2.log"}) {
    std::ofstream(fs::path(mixed.path()) / f) << f << "\n";  // distinct: copies would be counted once
  }
  const CliRun bad_set = runCli({"bench-report", mixed.path()});
  EXPECT_EQ(bad_set.exit_code, 2);
  EXPECT_EQ(countLines(bad_set.err), 1) << bad_set.err;
  EXPECT_NE(bad_set.err.find("tiny-fcl: shard logs missing: 0/2"), std::string::npos) << bad_set.err;
  EXPECT_FALSE(fs::exists(fs::path(mixed.path()) / "bench.db"));

  // bench-report on a folder without logs, or no folder.
  const CliRun empty = runCli({"bench-report", dir.path()});
  EXPECT_EQ(empty.exit_code, 2);
  EXPECT_NE(empty.err.find("no benchmark logs (*.log) in"), std::string::npos) << empty.err;
  const CliRun none = runCli({"bench-report", (base / "nowhere").string()});
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("no folder"), std::string::npos) << none.err;

  // No usable python3 (MDDUAL_PYTHON names the only one to try): fails before running.
  ::setenv("MDDUAL_PYTHON", "/bin/false", 1);
  const CliRun no_mpl = runCli({"bench", cfg, "--output", out});
  ::setenv("MDDUAL_PYTHON", (base / "no-python3").c_str(), 1);
  const CliRun no_python = runCli({"bench", cfg, "--output", out});
  ::unsetenv("MDDUAL_PYTHON");
  EXPECT_EQ(no_mpl.exit_code, 2);
  EXPECT_NE(no_mpl.err.find("no python3 with matplotlib (tried /bin/false, from MDDUAL_PYTHON)"), std::string::npos)
      << no_mpl.err;
  EXPECT_EQ(no_python.exit_code, 2);
  EXPECT_NE(no_python.err.find("MDDUAL_PYTHON='" + (base / "no-python3").string() + "' is not an executable file"),
            std::string::npos)
      << no_python.err;
  EXPECT_FALSE(fs::exists(base / "out" / "tiny-mdd.log")) << "nothing ran";
}

}  // namespace
}  // namespace mddual::cli_test
