// The report half of `mddual bench` and `mddual bench-report`: OMPL's
// ompl_benchmark_statistics turns the logs into a Planner Arena database,
// then scripts/bench_report.py writes the plots and the summary table. Each
// step runs as a child process with a time limit; the logs are checked
// first (ompl_benchmark_statistics loops forever on some cut-off logs).
// Errors are FatalError with one line naming what is wrong.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace mddual::cli {

/// Default bound on each step of the report (ompl_benchmark_statistics,
/// scripts/bench_report.py), seconds: both take seconds on the logs of a
/// full campaign; a step still running after 10 minutes is stuck (the
/// statistics script loops forever on some malformed logs) and is stopped.
constexpr double kDefaultReportTimeout = 600.0;

/// What the database and report steps need.
struct ReportTools {
  std::string python;                      ///< a python3 with matplotlib
  std::string statistics;                  ///< OMPL's ompl_benchmark_statistics (a python script)
  std::string script;                      ///< scripts/bench_report.py
  double timeout = kDefaultReportTimeout;  ///< seconds per step
};

/// A python3 with matplotlib (MDDUAL_PYTHON, or python3 on PATH, or
/// Debian's), ompl_benchmark_statistics and scripts/bench_report.py; throws
/// FatalError naming what is missing and how to install it.
ReportTools findReportTools();

/// Throws FatalError naming the first log that is not a complete OMPL
/// benchmark log.
void checkLogs(const std::vector<std::filesystem::path>& logs);

/// The database from `logs` (checked by checkLogs), then the report:
/// DIR/bench.db, DIR/plots/*.png, DIR/summary.md; the table goes to
/// standard output, with a note on `endpoint_contacts` when there are any.
void buildReport(const ReportTools& tools, const std::filesystem::path& dir,
                 const std::vector<std::filesystem::path>& logs,
                 const std::vector<std::string>& endpoint_contacts = {});

/// `mddual bench-report DIR`: every log of DIR (all shards; a copied log
/// counted once), checked, then buildReport.
void runBenchReport(const std::string& dir, double timeout);

/// Seconds as "%g".
std::string formatSeconds(double seconds);

}  // namespace mddual::cli
