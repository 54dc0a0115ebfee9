// `mddual bench` and `mddual bench-report`: OMPL's planners on a benchmark
// config with MDD-DUAL's checker and FCL's, one OMPL benchmark log per checker,
// every solution verified (mddual::planning::runBench), then the database
// (OMPL's ompl_benchmark_statistics), plots and the summary table
// (scripts/bench_report.py). Registered only when the planning layer is built
// (MDDUAL_CLI_WITH_BENCH). Built with Bullet (MDDUAL_HAVE_BULLET), the
// Bullet peer's checker hull-cast joins the tables before anything reads them.
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>
#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bench_report.h"
#include "commands.h"
#include "mddual/error.h"
#include "mddual/planning/arm_bench.h"
#include "mddual/planning/bench_logs.h"
#include "mddual/planning/bench_runner.h"
#include "mddual/planning/checker_registry.h"
#ifdef MDDUAL_HAVE_BULLET
#include "mddual/planning/hull_cast_checkers.h"
#endif

namespace mddual::cli {
namespace {

namespace fs = std::filesystem;
namespace mp = mddual::planning;
using Clock = std::chrono::steady_clock;

struct BenchFlags {
  std::string config;
  std::string checkers;  ///< empty: every checker of the problem's kind
  std::string planners;
  std::string runs;
  std::string time_limit;
  std::string output;
  std::string shard;
  std::string seed = "1";
  std::string report;
  std::string report_timeout;
  std::string last_valid_level;
  bool allow_invalid_endpoints = false;
  // Arm problems (a MotionBenchMaker directory instead of a cfg).
  std::string robot;
  std::string srdf;
  std::string group;
  std::string problems;
  std::string save_paths;
  std::vector<std::string> package_path;
};

// ---- Small parsers (one clear line per error) --------------------------------------

long parseIntInRange(const std::string& flag, const std::string& text, long lo, long hi) {
  std::size_t used = 0;
  long v = 0;
  try {
    v = std::stol(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || v < lo || v > hi) {
    throw FatalError(flag + ": '" + clipForMessage(text) + "' is not an integer in [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "]");
  }
  return v;
}

long parsePositiveInt(const std::string& flag, const std::string& text) {
  return parseIntInRange(flag, text, 1, 1000000000L);
}

double parsePositiveReal(const std::string& flag, const std::string& text) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::out_of_range&) {
    // Beyond double's range, or a positive number below its smallest normal one.
    throw FatalError(flag + ": '" + clipForMessage(text) + "' is out of the range of double precision");
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || !(v > 0.0) || !std::isfinite(v)) {
    throw FatalError(flag + ": '" + clipForMessage(text) + "' is not a positive number");
  }
  return v;
}

std::vector<std::string> splitList(const std::string& flag, const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item.empty()) throw FatalError(flag + ": empty name in '" + clipForMessage(text) + "'");
    out.push_back(item);
  }
  if (out.empty() || text.back() == ',') throw FatalError(flag + ": empty name in '" + clipForMessage(text) + "'");
  return out;
}

std::string formatClock(double seconds) {
  const long s = static_cast<long>(seconds);
  char buf[32];
  if (s >= 3600) {
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  } else {
    std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  }
  return buf;
}

// ---- Progress -----------------------------------------------------------------------

/// The progress display on standard error: a status line rewritten in place
/// on a terminal (config, checker, planner, run k of n, elapsed), and one line
/// per finished (checker, planner) with its results in any case.
class Progress {
 public:
  Progress(std::string config, int checkers) : config_(std::move(config)), checkers_(checkers) {
    tty_ = isatty(STDERR_FILENO) != 0;
    if (tty_) ticker_ = std::thread([this] { tick(); });
  }
  ~Progress() { stop(); }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void checker(const std::string& name, int index) {
    const std::lock_guard<std::mutex> lock(mutex_);
    finishPlannerLocked();
    checker_ = name;
    checker_index_ = index;
    planner_.clear();
  }
  void planner(const std::string& name, int index, int count, int runs) {
    const std::lock_guard<std::mutex> lock(mutex_);
    finishPlannerLocked();
    planner_ = name;
    planner_index_ = index;
    planners_ = count;
    runs_ = runs;
    run_ = -1;
    solved_ = verified_ = invalid_ = done_ = 0;
    planner_start_ = Clock::now();
    renderLocked();
  }
  void run(int k) {
    const std::lock_guard<std::mutex> lock(mutex_);
    run_ = k;
    renderLocked();
  }
  void finished(bool solved, bool verified, bool invalid) {
    const std::lock_guard<std::mutex> lock(mutex_);
    ++done_;
    solved_ += solved ? 1 : 0;
    verified_ += verified ? 1 : 0;
    invalid_ += invalid ? 1 : 0;
  }
  /// Ends the display (prints the last planner's line).
  void stop() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (stopped_) return;
      finishPlannerLocked();
      if (tty_) std::cerr << "\r\033[K" << std::flush;
      stopped_ = true;
    }
    wake_.notify_all();
    if (ticker_.joinable()) ticker_.join();
  }

 private:
  double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  void finishPlannerLocked() {
    if (planner_.empty()) return;
    const double took = std::chrono::duration<double>(Clock::now() - planner_start_).count();
    if (tty_) std::cerr << "\r\033[K";
    std::cerr << "bench: " << config_ << " | " << checker_ << " | " << planner_ << ": " << done_ << " runs, " << solved_
              << " solved, " << verified_ << " verified, " << invalid_ << " invalid (" << formatClock(took)
              << "; elapsed " << formatClock(elapsed()) << ")\n"
              << std::flush;
    planner_.clear();
  }

  void renderLocked() {
    if (!tty_ || stopped_ || planner_.empty()) return;
    std::cerr << "\r\033[K" << config_ << " | checker " << checker_ << " (" << checker_index_ + 1 << "/" << checkers_
              << ") | " << planner_ << " (" << planner_index_ + 1 << "/" << planners_ << ") | run "
              << std::max(run_ + 1, 1) << " of " << runs_ << " | elapsed " << formatClock(elapsed()) << std::flush;
  }

  void tick() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stopped_) {
      wake_.wait_for(lock, std::chrono::milliseconds(500));
      renderLocked();
    }
  }

  std::string config_;
  int checkers_;
  bool tty_ = false;
  bool stopped_ = false;
  Clock::time_point start_ = Clock::now();
  Clock::time_point planner_start_ = Clock::now();
  std::string checker_;
  int checker_index_ = 0;
  std::string planner_;
  int planner_index_ = 0;
  int planners_ = 0;
  int runs_ = 0;
  int run_ = -1;
  int done_ = 0;
  int solved_ = 0;
  int verified_ = 0;
  int invalid_ = 0;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread ticker_;
};

// ---- The commands -------------------------------------------------------------------

/// --report-timeout / --timeout: seconds, or the default when not given.
double reportTimeout(const std::string& flag, const std::string& text) {
  if (text.empty()) return kDefaultReportTimeout;
  return parsePositiveReal(flag, text);
}

/// `mddual bench PROBLEM_DIR --robot URDF --srdf SRDF`: the arm benchmark.
void runArmBenchCommand(const BenchFlags& f) {
  if (f.robot.empty() || f.srdf.empty()) {
    throw FatalError("bench: " + f.config + " is a problem directory: give --robot URDF and --srdf SRDF");
  }
  if (!f.last_valid_level.empty()) throw FatalError("--last-valid-level: applies to cfg problems only");
  if (f.allow_invalid_endpoints) throw FatalError("--allow-invalid-endpoints: applies to cfg problems only");
  mp::ArmBenchOptions options;
  try {
    if (!f.checkers.empty()) options.checkers = mp::parseArmCheckerList(f.checkers);
    if (!f.shard.empty()) options.shard = mp::parseShard(f.shard);
  } catch (const InvalidInputError& e) {
    throw FatalError(std::string("--checkers/--shard: ") + e.what());
  }
  if (!f.planners.empty()) options.planners = splitList("--planners", f.planners);
  if (!f.runs.empty()) options.runs = static_cast<int>(parsePositiveInt("--runs", f.runs));
  if (!f.time_limit.empty()) options.time_limit = parsePositiveReal("--time-limit", f.time_limit);
  if (!f.problems.empty()) options.problems = static_cast<int>(parsePositiveInt("--problems", f.problems));
  options.problem.group = f.group;
  options.paths_dir = f.save_paths;
  const long seed = parsePositiveInt("--seed", f.seed);
  const double timeout = reportTimeout("--report-timeout", f.report_timeout);
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  ompl::RNG::setSeed(mp::shardSeed(seed, options.shard));
  const std::string name = mp::problemDirName(f.config);
  options.output_dir = f.output.empty() ? fs::path("out") / "bench" / name : fs::path(f.output);
  std::optional<ReportTools> tools;
  if (!options.shard.sharded()) {
    tools = findReportTools();
    tools->timeout = timeout;
  }
  std::vector<mp::ArmBenchLog> logs;
  try {
    scene::RobotLoadOptions load;
    for (const std::string& p : f.package_path) load.package_path.emplace_back(p);
    const mp::ArmRobot robot = mp::loadArmRobot(f.robot, f.srdf, load);
    mp::ArmBenchObserver observer;
    observer.problem_started = [](const std::string& problem, int i, int n) {
      std::cerr << "bench: problem " << (i + 1) << " of " << n << ": " << problem << "\n";
    };
    logs = mp::runArmBench(robot, f.config, options, observer);
  } catch (const std::exception& e) {
    throw FatalError(e.what());
  }
  std::vector<fs::path> files;
  int solved = 0, verified = 0, invalid = 0;
  for (const mp::ArmBenchLog& l : logs) {
    files.push_back(l.file);
    solved += l.solved;
    verified += l.verified;
    invalid += l.invalid;
  }
  std::cerr << "bench: " << logs.size() << " logs in " << options.output_dir.string() << ": " << solved
            << " solutions, " << verified << " verified, " << invalid << " invalid\n";
  if (!tools) {
    std::cerr << "shard " << mp::toString(options.shard) << " done; when every shard is: mddual bench-report "
              << options.output_dir.string() << "\n";
    return;
  }
  checkLogs(files);
  buildReport(*tools, options.output_dir, files);
}

void runBenchCommand(const BenchFlags& f) {
  if (!f.config.empty() && fs::is_directory(f.config)) {
    runArmBenchCommand(f);
    return;
  }
  if (!f.report.empty()) {
    if (!f.config.empty()) throw FatalError("bench: give either a config file or --report DIR, not both");
    runBenchReport(f.report, reportTimeout("--report-timeout", f.report_timeout));
    return;
  }
  if (f.config.empty()) throw FatalError("bench: no config file given (mddual bench CONFIG.cfg, or --report DIR)");
  if (!f.robot.empty() || !f.srdf.empty() || !f.group.empty() || !f.problems.empty() || !f.package_path.empty() ||
      !f.save_paths.empty()) {
    throw FatalError(
        "bench: --robot, --srdf, --group, --problems, --package-path and --save-paths apply to a problem "
        "directory, not to " +
        f.config);
  }

  mp::BenchOptions options;
  try {
    if (!f.checkers.empty()) options.checkers = mp::parseCheckerList(f.checkers);
  } catch (const InvalidInputError& e) {
    throw FatalError(std::string("--checkers: ") + e.what());
  }
  try {
    if (!f.shard.empty()) options.shard = mp::parseShard(f.shard);
  } catch (const InvalidInputError& e) {
    throw FatalError(e.what());
  }
  if (!f.planners.empty()) options.planners = splitList("--planners", f.planners);
  if (!f.runs.empty()) options.runs = static_cast<int>(parsePositiveInt("--runs", f.runs));
  if (!f.time_limit.empty()) options.time_limit = parsePositiveReal("--time-limit", f.time_limit);
  if (!f.last_valid_level.empty()) {
    if (std::find(options.checkers.begin(), options.checkers.end(), "mdd") == options.checkers.end()) {
      throw FatalError("--last-valid-level: it sets the mdd checker, which --checkers leaves out");
    }
    options.setup.mdd.last_valid_level =
        static_cast<int>(parseIntInRange("--last-valid-level", f.last_valid_level, 0, mp::kMaxRefinementLevels));
  }
  const long seed = parsePositiveInt("--seed", f.seed);
  const double timeout = reportTimeout("--report-timeout", f.report_timeout);

  // OMPL's random seed before anything creates a generator (a shard's own, see shardSeed).
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  ompl::RNG::setSeed(mp::shardSeed(seed, options.shard));

  options.setup.allow_invalid_endpoints = f.allow_invalid_endpoints;
  mp::Problem problem;
  std::vector<std::string> endpoint_contacts;  // with --allow-invalid-endpoints
  try {
    problem = mp::loadProblem(f.config);
    mp::selectPlanners(problem, options.planners);  // an unknown name fails now
    // A start or goal in collision too, unless --allow-invalid-endpoints.
    endpoint_contacts = mp::checkBenchProblem(problem, f.allow_invalid_endpoints);
  } catch (const std::exception& e) {
    throw FatalError(e.what());
  }
  for (const std::string& w : problem.scene->warnings) std::cerr << "bench: warning: " << w << "\n";
  for (const std::string& c : endpoint_contacts) {
    std::cerr << "bench: warning: " << c << " (--allow-invalid-endpoints: the runs go on)\n";
  }
  if (!f.output.empty()) {
    options.output_dir = f.output;
  } else if (!problem.config.output.empty()) {
    options.output_dir = scene::resolvePath(problem.config, problem.config.output);
  } else {
    options.output_dir = fs::path("out") / "bench" / problem.name;
  }

  // Before the long part: the database and report tools (unsharded runs).
  std::optional<ReportTools> tools;
  if (!options.shard.sharded()) {
    tools = findReportTools();
    tools->timeout = timeout;
  }

  Progress progress(problem.name, static_cast<int>(options.checkers.size()));
  mp::BenchObserver observer;
  // The scene summary once the runs start (after runBench has checked the
  // flags, whose errors are one line): pieces, meshes, hollow soups.
  observer.checker_started = [&](const std::string& k, int i, int) {
    if (i == 0) std::cerr << "bench: scene: " << scene::sceneSummary(*problem.scene) << "\n";
    progress.checker(k, i);
  };
  observer.planner_started = [&](const std::string&, const std::string& name, int i, int n, int runs) {
    progress.planner(name, i, n, runs);
  };
  observer.run_started = [&](const std::string&, const std::string&, int k, int, int) { progress.run(k); };
  observer.run_finished = [&](const std::string&, const std::string&, int, bool solved, bool verified, bool invalid) {
    progress.finished(solved, verified, invalid);
  };
  std::vector<mp::BenchLog> logs;
  try {
    logs = mp::runBench(problem, options, observer);
  } catch (const std::exception& e) {
    progress.stop();
    throw FatalError(e.what());
  }
  progress.stop();
  std::vector<fs::path> files;
  for (const mp::BenchLog& l : logs) {
    files.push_back(l.file);
    std::cerr << "log: " << l.file.string() << "\n";
  }
  if (!tools) {
    std::cerr << "shard " << mp::toString(options.shard) << " done; when every shard is: mddual bench-report "
              << options.output_dir.string() << "\n";
    return;
  }
  checkLogs(files);
  buildReport(*tools, options.output_dir, files, endpoint_contacts);
}

/// The checker tables (checker_registry.h) as the footer lists them: one
/// "  NAME  DESCRIPTION" line each.
template <class Entry>
std::string checkerLines(const std::vector<Entry>& table) {
  std::string out;
  for (const Entry& e : table) {
    std::string name = e.name;
    name.resize(std::max<std::size_t>(name.size() + 2, 16), ' ');
    out += "  " + name + e.description + "\n";
  }
  return out;
}

std::string benchFooter() {
  return "For each checker, the cfg's problem and planners in ompl::tools::Benchmark with the cfg's limits (flags\n"
         "override them). Writes one OMPL benchmark log per checker (experiment <config>-<checker>) to DIR (default\n"
         "out/bench/<config>/), verifies every solution path (exact MDD edge check with a 1e-6 rotation tolerance\n"
         "+ dense FCL check), then builds DIR/bench.db (ompl_benchmark_statistics), DIR/plots/*.png and\n"
         "DIR/summary.md and prints the summary table. Checkers of a cfg (--checkers; default all, in this order):\n" +
         checkerLines(mp::rigidCheckers()) +
         "--shard I/N runs runs r with r mod N = I only, seeds OMPL with a splitmix64 hash of (seed, I, N) and\n"
         "skips the report: run `mddual bench-report DIR` when every shard is done. Before planning, the start and\n"
         "goal states are checked (within the bounds, free of the world by the exact test and by each checker).\n"
         "A MotionBenchMaker problem directory (sceneNNNN.yaml, requestNNNN.yaml) with --robot URDF --srdf SRDF\n"
         "runs each problem with each arm checker, the requests' planner_id unless --planners says otherwise;\n"
         "--shard I/N splits the problems. Arm checkers (--checkers; default all, in this order):\n" +
         checkerLines(mp::armCheckers()) + "Exit status 2 for bad input.";
}

/// A text option whose value is kept as given for the command to parse. Given
/// with an empty value it is an error, not its default (a hostile-input hunt:
/// `--output ''` wrote to out/bench/<config>/).
void textOption(CLI::App* app, const std::string& flag, std::string* to, const std::string& help,
                const std::string& text) {
  app->add_option_function<std::string>(
         flag,
         [flag, to](const std::string& value) {
           if (value.empty()) throw FatalError(flag + ": an empty value (leave the option out for its default)");
           *to = value;
         },
         help)
      ->option_text(text);
}

std::string reportTimeoutHelp() {
  return "stop a report step (ompl_benchmark_statistics, bench_report.py) after S seconds (default " +
         formatSeconds(kDefaultReportTimeout) + ")";
}

}  // namespace

void registerBenchCommand(CLI::App& app) {
#ifdef MDDUAL_HAVE_BULLET
  mp::registerHullCastCheckers();  // before the help text lists the tables
#endif
  auto flags = std::make_shared<BenchFlags>();
  CLI::App* sub =
      app.add_subcommand("bench", "OMPL benchmark of a config with MDD-DUAL and FCL checkers, verified solutions");
  sub->footer(benchFooter());
  sub->add_option("config", flags->config,
                  "benchmark config (OMPL.app .cfg), or a MotionBenchMaker problem directory (with --robot, --srdf)")
      ->option_text("CONFIG.cfg|PROBLEM_DIR");
  textOption(sub, "--checkers", &flags->checkers,
             "comma-separated checker names, of a cfg's or of an arm's (see below; default: all)", "LIST");
  textOption(sub, "--planners", &flags->planners,
             "comma-separated planner names: the cfg's, or any OMPL planner with its default parameters (default: "
             "the cfg's)",
             "LIST");
  textOption(sub, "--runs", &flags->runs, "runs per planner (default: the cfg's run_count)", "N");
  textOption(sub, "--time-limit", &flags->time_limit, "seconds per run (default: the cfg's time_limit)", "S");
  textOption(sub, "--output", &flags->output, "output folder (default: out/bench/<config>/)", "DIR");
  textOption(sub, "--shard", &flags->shard, "run only slice I of N of the runs (0 <= I < N)", "I/N");
  textOption(sub, "--seed", &flags->seed,
             "OMPL's random seed (default 1; shard I of N: a splitmix64 hash of K, I and N)", "K");
  textOption(sub, "--report", &flags->report, "only build the database and report from the logs in DIR", "DIR");
  textOption(sub, "--report-timeout", &flags->report_timeout, reportTimeoutHelp(), "S");
  textOption(sub, "--last-valid-level", &flags->last_valid_level,
             "mdd checker: the coarsest enlargement level whose contact may end a rotating edge's lastValid search, "
             "0 (any level: fastest, keeps least of an invalid edge) to 8; levels from the scene's refinement levels "
             "(3) up mean the finest (default " +
                 std::to_string(mp::kDefaultLastValidLevel) + ", MddSceneOptions::last_valid_level)",
             "K");
  sub->add_flag("--allow-invalid-endpoints", flags->allow_invalid_endpoints,
                "cfg problems: run even when the start or goal is in collision (by the exact test or a checker); "
                "the contacts are printed and noted under the summary table, every path is still verified");
  textOption(sub, "--robot", &flags->robot, "problem directories: the robot's URDF", "URDF");
  textOption(sub, "--srdf", &flags->srdf, "problem directories: the robot's SRDF", "SRDF");
  textOption(sub, "--group", &flags->group, "problem directories: the planning group (default: each request's)",
             "NAME");
  textOption(sub, "--problems", &flags->problems, "problem directories: only the first N problems", "N");
  textOption(sub, "--save-paths", &flags->save_paths,
             "problem directories: write every exact solution there as a MoveIt trajectory (YAML)", "DIR");
  sub->add_option("--package-path", flags->package_path,
                  "problem directories: a folder searched for the URDF's package:// meshes (repeatable)")
      ->option_text("DIR");
  sub->callback([flags] { runBenchCommand(*flags); });

  auto dir = std::make_shared<std::string>();
  auto timeout = std::make_shared<std::string>();
  CLI::App* report = app.add_subcommand(
      "bench-report", "database, plots and summary table from the benchmark logs in DIR (merges shards)");
  report->footer(
      "Every *.log in DIR is checked first: complete OMPL benchmark logs (a log cut off is named with its line),\n"
      "complete shard sets; a log with the same content as another (a copy) is reported and counted once.");
  report->add_option("dir", *dir, "folder with the logs of mddual bench (all shards)")->required()->option_text("DIR");
  textOption(report, "--timeout", timeout.get(), reportTimeoutHelp(), "S");
  report->callback([dir, timeout] { runBenchReport(*dir, reportTimeout("--timeout", *timeout)); });
}

}  // namespace mddual::cli
