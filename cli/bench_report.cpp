// The benchmark report (bench_report.h).
#include "bench_report.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "commands.h"
#include "mddual/error.h"
#include "mddual/planning/bench_logs.h"
#include "mddual/planning/bench_runner.h"

extern char** environ;

namespace mddual::cli {
namespace {

namespace fs = std::filesystem;
namespace mp = mddual::planning;
using Clock = std::chrono::steady_clock;

/// Longer time limits are taken as this one (about 115 days): the deadline
/// must stay within the steady clock's range.
constexpr double kMaxReportTimeout = 1e7;
/// How often a running step is polled, milliseconds.
constexpr int kReportPollMs = 20;
/// runProgram's status for a program stopped at its time limit.
constexpr int kTimedOut = -2;

/// Runs argv[0] (searched on PATH) with argv; stdout and stderr go to `log`
/// when given (appended), else to ours. Returns the exit status (-1: could
/// not start or killed; kTimedOut: still running after `timeout` seconds,
/// then killed).
int runProgram(const std::vector<std::string>& argv, const std::string& log = "",
               double timeout = kDefaultReportTimeout) {
  std::vector<std::string> args = argv;
  std::vector<char*> cargv;
  for (std::string& a : args) cargv.push_back(a.data());
  cargv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!log.empty()) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  }
  std::cout.flush();
  std::cerr.flush();
  pid_t pid = -1;
  const int rc = posix_spawnp(&pid, cargv[0], &actions, nullptr, cargv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) return -1;
  const Clock::time_point deadline =
      Clock::now() +
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(std::min(timeout, kMaxReportTimeout)));
  int status = 0;
  for (;;) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) return -1;
    if (Clock::now() >= deadline) {
      kill(pid, SIGKILL);  // the child we started, by its id
      while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      return kTimedOut;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(kReportPollMs));
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool isExecutable(const fs::path& p) {
  return !p.empty() && access(p.c_str(), X_OK) == 0 && !fs::is_directory(p);
}

/// `name` on PATH (or as given when it holds a '/'), or empty.
fs::path findOnPath(const std::string& name) {
  if (name.find('/') != std::string::npos) return isExecutable(name) ? fs::path(name) : fs::path();
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const fs::path candidate = fs::path(dir.empty() ? "." : dir) / name;
    if (isExecutable(candidate)) return candidate;
  }
  return {};
}

std::string findReportScript() {
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv("MDDUAL_BENCH_REPORT")) candidates.emplace_back(env);
#ifdef MDDUAL_BENCH_REPORT_SOURCE
  candidates.emplace_back(MDDUAL_BENCH_REPORT_SOURCE);
#endif
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back(exe.parent_path().parent_path() / "share" / "mddual" / "bench_report.py");
#ifdef MDDUAL_BENCH_REPORT_INSTALLED
  candidates.emplace_back(MDDUAL_BENCH_REPORT_INSTALLED);
#endif
  std::string tried;
  for (const fs::path& c : candidates) {
    if (fs::is_regular_file(c)) return c.string();
    tried += (tried.empty() ? "" : ", ") + c.string();
  }
  throw FatalError("scripts/bench_report.py not found (tried " + tried + "; set MDDUAL_BENCH_REPORT)");
}

/// The note under the summary table of a run with --allow-invalid-endpoints
/// whose start or goal is in collision, on standard output and in `summary`.
void appendEndpointNote(const fs::path& summary, const std::vector<std::string>& contacts) {
  std::string note =
      "\nEndpoints in contact (run with --allow-invalid-endpoints): a checker that finds the start or "
      "the goal in collision solves no run, and every solution of the others ends in contact, so "
      "its path verification fails.\n\n";
  for (const std::string& c : contacts) note += "- " + c + "\n";
  std::cout << note << std::flush;
  std::ofstream out(summary, std::ios::app);
  out << note;
  if (!out) throw FatalError("cannot append to " + summary.string());
}

std::vector<fs::path> logsIn(const fs::path& dir) {
  if (!fs::is_directory(dir)) throw FatalError("bench-report: no folder " + dir.string());
  std::vector<fs::path> logs;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.is_regular_file() && e.path().extension() == ".log") logs.push_back(e.path());
  }
  std::sort(logs.begin(), logs.end());
  if (logs.empty()) throw FatalError("bench-report: no benchmark logs (*.log) in " + dir.string());
  return logs;
}

}  // namespace

std::string formatSeconds(double seconds) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", seconds);
  return buf;
}

ReportTools findReportTools() {
  ReportTools t;
  std::vector<std::string> candidates;
  const char* env = std::getenv("MDDUAL_PYTHON");
  const bool from_env = env != nullptr && *env != '\0';
  if (from_env) {
    if (findOnPath(env).empty()) {
      throw FatalError("MDDUAL_PYTHON='" + clipForMessage(env) +
                       "' is not an executable file (nor a program on PATH): set it to a python3 with matplotlib, "
                       "or unset it to use python3 from PATH");
    }
    candidates.emplace_back(env);  // only that one
  } else {
    candidates.emplace_back("python3");
    candidates.emplace_back("/usr/bin/python3");  // Debian's, when PATH's python3 is another (pyenv, venv)
  }
  std::vector<std::string> found;
  for (const std::string& c : candidates) {
    const fs::path p = findOnPath(c);
    if (p.empty() || std::find(found.begin(), found.end(), p.string()) != found.end()) continue;
    found.push_back(p.string());
    if (runProgram({p.string(), "-c", "import sqlite3, matplotlib"}, "/dev/null") == 0) {
      t.python = p.string();
      break;
    }
  }
  if (t.python.empty()) {
    if (found.empty()) {
      throw FatalError(
          "python3 not found: the database and plots need python3 and matplotlib "
          "(Debian: python3 python3-matplotlib; scripts/install-deps.sh installs them)");
    }
    std::string list;
    for (const std::string& f : found) list += (list.empty() ? "" : ", ") + clipForMessage(f);
    if (from_env) {
      throw FatalError("no python3 with matplotlib (tried " + list +
                       ", from MDDUAL_PYTHON): it cannot import sqlite3 and matplotlib; point MDDUAL_PYTHON at "
                       "a python3 that can, or unset it to use python3 from PATH");
    }
    throw FatalError("no python3 with matplotlib (tried " + list +
                     "): install python3-matplotlib (scripts/install-deps.sh) or set MDDUAL_PYTHON");
  }
  fs::path stats = findOnPath("ompl_benchmark_statistics");
  if (stats.empty() && fs::is_regular_file("/usr/bin/ompl_benchmark_statistics")) {
    stats = "/usr/bin/ompl_benchmark_statistics";
  }
  if (stats.empty()) {
    throw FatalError("ompl_benchmark_statistics not found: install Debian's ompl-demos (scripts/install-deps.sh)");
  }
  t.statistics = stats.string();
  t.script = findReportScript();
  return t;
}

// ompl_benchmark_statistics loops forever on a log cut off inside a block
// and fails with a bare traceback on most other cuts: the logs are checked
// before it runs.
void checkLogs(const std::vector<fs::path>& logs) {
  for (const fs::path& l : logs) {
    try {
      mp::checkBenchLog(l);
    } catch (const InvalidInputError& e) {
      throw FatalError(std::string("bench-report: ") + e.what());
    }
  }
}

void buildReport(const ReportTools& tools, const fs::path& dir, const std::vector<fs::path>& logs,
                 const std::vector<std::string>& endpoint_contacts) {
  const fs::path db = dir / "bench.db";
  const fs::path stats_log = dir / "ompl_benchmark_statistics.out";
  std::error_code ec;
  fs::remove(db, ec);
  fs::remove(stats_log, ec);
  std::vector<std::string> argv{tools.python, tools.statistics};
  for (const fs::path& l : logs) argv.push_back(l.string());
  argv.insert(argv.end(), {"-d", db.string()});
  const int stats_rc = runProgram(argv, stats_log.string(), tools.timeout);
  if (stats_rc == kTimedOut) {
    throw FatalError("ompl_benchmark_statistics did not finish within " + formatSeconds(tools.timeout) +
                     " s on the logs in " + dir.string() + " and was stopped (its output: " + stats_log.string() +
                     "; a larger limit: --report-timeout / bench-report --timeout)");
  }
  if (stats_rc != 0 || !fs::is_regular_file(db)) {
    std::ifstream in(stats_log);
    std::string line;
    std::string last;
    while (std::getline(in, line)) {
      if (!line.empty()) last = line;
    }
    throw FatalError("ompl_benchmark_statistics failed on the logs in " + dir.string() + (last.empty() ? "" : ": ") +
                     last + " (full output: " + stats_log.string() + ")");
  }
  std::cout << "## " << dir.string() << "\n\n" << std::flush;
  const int rc = runProgram({tools.python, "-B", tools.script, "--db", db.string(), "--plots", (dir / "plots").string(),
                             "--markdown", (dir / "summary.md").string()},
                            "", tools.timeout);
  if (rc == kTimedOut) {
    throw FatalError("scripts/bench_report.py did not finish within " + formatSeconds(tools.timeout) +
                     " s and was stopped (a larger limit: --report-timeout / bench-report --timeout)");
  }
  if (rc != 0) throw FatalError("scripts/bench_report.py failed (exit status " + std::to_string(rc) + ")");
  if (!endpoint_contacts.empty()) appendEndpointNote(dir / "summary.md", endpoint_contacts);
  std::cout << "\ndatabase: " << db.string() << " (opens in Planner Arena)\n" << std::flush;
}

void runBenchReport(const std::string& dir, double timeout) {
  std::vector<fs::path> logs = logsIn(dir);
  // A copied log holds the same runs: count them once.
  std::vector<mp::DuplicateLog> copies;
  try {
    copies = mp::findDuplicateLogs(logs);
  } catch (const InvalidInputError& e) {
    throw FatalError(std::string("bench-report: ") + e.what());
  }
  for (const mp::DuplicateLog& d : copies) {
    std::cerr << "bench-report: " << d.copy.filename().string() << " has the same content as "
              << d.kept.filename().string() << ": counted once\n";
    logs.erase(std::remove(logs.begin(), logs.end(), d.copy), logs.end());
  }
  try {
    mp::checkShardSets(logs);
  } catch (const InvalidInputError& e) {
    throw FatalError("bench-report: " + dir + ": " + e.what());
  }
  checkLogs(logs);
  ReportTools tools = findReportTools();
  tools.timeout = timeout;
  std::cerr << "bench-report: " << logs.size() << " logs in " << dir << "\n";
  buildReport(tools, dir, logs);
}

}  // namespace mddual::cli
