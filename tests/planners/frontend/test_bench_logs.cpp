// The checks on benchmark logs before ompl_benchmark_statistics reads them
// (bench_logs.h): a log OMPL wrote passes, and so does one with progress
// data; every log cut short (at any line, or inside a run's line) is refused
// with the file and line, where the statistics script would loop forever or
// stop with a traceback; copies are found by content, not by name.
#include <gtest/gtest.h>
#include <unistd.h>

#include <ompl/util/Console.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "mddual/error.h"
#include "mddual/planning/bench_logs.h"
#include "mddual/planning/bench_runner.h"
#include "tiny_config.h"

namespace mddual::planning {
namespace {

namespace fs = std::filesystem;

class BenchLogs : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("mddual_bench_logs_" + std::string(info->name()) + "_" + std::to_string(static_cast<long>(::getpid())));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path file = dir_ / name;
    testing::writeTextFile(file, text);
    return file;
  }
  /// The message checkBenchLog throws for `text`, or "" if it accepts it.
  std::string check(const std::string& text) const {
    const fs::path file = write("cut.log", text);
    try {
      checkBenchLog(file);
    } catch (const InvalidInputError& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

/// A real log: one run of one planner with the mdd checker on the tiny config.
std::string omplLog(const fs::path& dir) {
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  const Problem problem = loadProblem(testing::writeTinyConfig(dir / "cfg"));
  BenchOptions options;
  options.checkers = {"mdd"};
  options.planners = {"rrtconnect"};
  options.runs = 1;
  options.time_limit = 0.05;
  options.output_dir = dir / "out";
  const std::vector<BenchLog> logs = runBench(problem, options);
  std::ifstream in(logs.at(0).file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::string join(const std::vector<std::string>& l, std::size_t count) {
  std::string text;
  for (std::size_t i = 0; i < count; ++i) text += l[i] + "\n";
  return text;
}

TEST_F(BenchLogs, EveryCutOfAnOmplLogIsRefusedWithItsLine) {
  const std::string full = omplLog(dir_);
  EXPECT_EQ(check(full), "");
  const std::vector<std::string> l = lines(full);
  ASSERT_GT(l.size(), 20u);
  const std::string file = (dir_ / "cut.log").string();
  for (std::size_t n = 0; n < l.size(); ++n) {
    const std::string message = check(join(l, n));
    ASSERT_NE(message, "") << "cut after line " << n << " accepted";
    EXPECT_EQ(message.rfind(file + ": line " + std::to_string(n + 1) + ": expected ", 0), 0u) << message;
    EXPECT_NE(message.find(", found the end of the file (the log is cut off or is not an OMPL benchmark log)"),
              std::string::npos)
        << message;
  }
  // Cut inside the CPU-info block (the statistics script's endless loop).
  std::size_t cpu = 0;
  int opened = 0;
  for (std::size_t i = 0; i < l.size() && cpu == 0; ++i) {
    if (l[i].rfind("<<<|", 0) == 0 && ++opened == 2) cpu = i;
  }
  ASSERT_GT(cpu, 0u) << "the log has a CPU-info block";
  EXPECT_EQ(check(join(l, cpu + 2)), file + ": line " + std::to_string(cpu + 3) +
                                         ": expected the line '|>>>' closing the CPU-info block opened at line " +
                                         std::to_string(cpu + 1) +
                                         ", found the end of the file (the log is cut off or is not an OMPL "
                                         "benchmark log)");
  // The last run's line cut in the middle: too few values.
  std::size_t run = 0;
  for (std::size_t i = 0; i < l.size(); ++i) {
    if (l[i] == "1 runs") run = i + 1;
  }
  ASSERT_GT(run, 0u);
  std::vector<std::string> cut = l;
  cut[run] = cut[run].substr(0, cut[run].size() / 2);
  const std::string message = check(join(cut, cut.size()));
  EXPECT_EQ(message.rfind(file + ": line " + std::to_string(run + 1) + ": expected run 1 of planner 1 (", 0), 0u)
      << message;
}

TEST_F(BenchLogs, ProgressDataAndOtherHeaders) {
  // A log with progress data (what OMPL writes for planners with progress
  // properties), no experiment properties, no CPU info, no runs-per-planner.
  const std::string log =
      "OMPL version 1.5.2\n"
      "Experiment e\n"
      "Running on host\n"
      "Starting at 2024-01-01 00:00:00\n"
      "<<<|\nsetup text\n|>>>\n"
      "7 is the random seed\n"
      "1 seconds per run\n"
      "100 MB per run\n"
      "0.5 seconds spent to collect the data\n"
      "1 planners\n"
      "geometric_RRTstar\n"
      "1 common properties\nrange = 1\n"
      "2 properties for each run\ntime REAL\nsolved BOOLEAN\n"
      "2 runs\n0.1; 1; \n0.2; 0; \n"
      "2 progress properties for each run\ntime REAL\nbest cost REAL\n"
      "2 runs\n0.1,5,;0.2,4,;\n0.1,6,;\n"
      ".\n";
  EXPECT_EQ(check(log), "");
  const std::vector<std::string> l = lines(log);
  for (std::size_t n = 0; n < l.size(); ++n) EXPECT_NE(check(join(l, n)), "") << "cut after line " << n;
  // Not a log at all.
  const std::string file = (dir_ / "cut.log").string();
  EXPECT_EQ(check("hello\n"), file +
                                  ": line 1: expected 'Experiment <name>', found 'hello' (the log is cut off or is "
                                  "not an OMPL benchmark log)");
  // A count that is not a number.
  std::string bad = log;
  bad.replace(bad.find("2 runs\n0.1; 1;"), 6, "x runs");
  EXPECT_NE(check(bad).find(": line 19: expected '<n> runs' of planner 1, found 'x runs'"), std::string::npos)
      << check(bad);
  EXPECT_THROW(checkBenchLog(dir_ / "missing.log"), InvalidInputError);
  // OMPL's "no value" (empty, nan, inf) passes in a numeric property.
  std::string none = log;
  none.replace(none.find("0.2; 0; "), 8, "nan; ; ");
  none.replace(none.find("0.1; 1; "), 8, "inf; 1; ");
  EXPECT_EQ(check(none), "");
  // Found by a hostile-input hunt, each accepted here and then a Python
  // traceback in the report: no planner (the statistics script's SQL breaks),
  // a property type sqlite takes but the report cannot (text in it), a run
  // value that is no number in a numeric property.
  std::string no_planner = log.substr(0, log.find("1 planners\n")) + "0 planners\n";
  EXPECT_NE(check(no_planner).find(": line 12: expected '<n> planners' (at least one), found '0 planners'"),
            std::string::npos)
      << check(no_planner);
  std::string blob = log;
  blob.replace(blob.find("time REAL\nsolved"), 9, "time BLOB");
  EXPECT_NE(check(blob).find(": line 17: expected run property 1 of planner 1 ('<name> <TYPE>'); the report reads "
                             "'time' as a number, so its TYPE must be BOOLEAN, INTEGER, REAL, ENUM, DOUBLE, FLOAT "
                             "or NUMERIC, found 'time BLOB'"),
            std::string::npos)
      << check(blob);
  // Other types pass (OMPL's informed trees write "best cost DOUBLE"; a
  // property the report does not read may be of any type).
  const auto edited = [](std::string text, const std::string& from, const std::string& to) {
    return text.replace(text.find(from), from.size(), to);
  };
  std::string other = edited(log, "2 properties for each run\ntime REAL\nsolved BOOLEAN\n",
                             "4 properties for each run\ntime REAL\nsolved BOOLEAN\nbest cost DOUBLE\nnote TEXT\n");
  other = edited(other, "0.1; 1; \n0.2; 0; \n", "0.1; 1; 4.5; a; \n0.2; 0; inf; b c; \n");
  EXPECT_EQ(check(other), "");
  const std::string cost = edited(other, "4.5; a;", "cheap; a;");
  EXPECT_NE(check(cost).find("value 3, 'cheap', is not a number"), std::string::npos) << check(cost);
  std::string text = log;
  text.replace(text.find("0.2; 0; "), 8, "abc; 0; ");
  EXPECT_NE(check(text).find(": line 21: expected run 2 of planner 1 (2 values, each followed by '; '); value 1, "
                             "'abc', is not a number, found 'abc; 0; '"),
            std::string::npos)
      << check(text);
}

TEST_F(BenchLogs, CopiesAreFoundByContent) {
  const fs::path a = write("thin_walls-mdd.log", "log A\n");
  const fs::path a_copy = write("thin_walls-mdd (copy).log", "log A\n");
  const fs::path b = write("thin_walls-fcl.log", "log B\n");
  const fs::path b_renamed = write("b.log", "log B\n");
  const fs::path c = write("thin_walls-fcl-continuous.log", "log C\n");
  const fs::path a_prefix = write("x.log", "log A");  // same start, not the same content
  const std::vector<DuplicateLog> d = findDuplicateLogs({a, a_copy, b, b_renamed, c, a_prefix});
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].copy, b);  // sorted by the copy's path; the shortest name is kept
  EXPECT_EQ(d[0].kept, b_renamed);
  EXPECT_EQ(d[1].copy, a_copy);
  EXPECT_EQ(d[1].kept, a);
  EXPECT_TRUE(findDuplicateLogs({a, b, c}).empty());
  EXPECT_THROW(findDuplicateLogs({dir_ / "missing.log"}), InvalidInputError);
}

}  // namespace
}  // namespace mddual::planning
