#include "mddual/planning/bench_logs.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <utility>

#include "mddual/error.h"

namespace mddual::planning {

namespace {

// Largest count a log line may declare (planners, properties, runs, enum
// types): far above any real campaign, and small enough that a corrupted
// count is reported rather than trusted.
constexpr long kMaxDeclaredCount = 100000000;
// Characters of an offending line quoted in a message.
constexpr std::size_t kMaxQuotedLine = 80;
/// Property types whose values are numbers (OMPL's, and what sqlite gives
/// numeric affinity among the words OMPL's planners use).
constexpr const char* kNumericTypes[] = {"BOOLEAN", "INTEGER", "REAL", "ENUM", "DOUBLE", "FLOAT", "NUMERIC"};
/// Run properties scripts/bench_report.py reads as numbers.
constexpr const char* kReportedNumbers[] = {"time",          "solved",           "approximate solution",
                                            "verified",      "invalid solution", "invalid raw solution",
                                            "checking time", "state checks",     "motion checks"};

std::vector<std::string> tokens(const std::string& line) {
  std::istringstream in(line);
  return {std::istream_iterator<std::string>(in), std::istream_iterator<std::string>()};
}

/// Whether the last tokens of `line` are `suffix` (and there is at least one
/// token before them when `with_value`).
bool endsWith(const std::vector<std::string>& t, const std::vector<std::string>& suffix, bool with_value) {
  const std::size_t need = suffix.size() + (with_value ? 1 : 0);
  if (t.size() < need) return false;
  return std::equal(suffix.begin(), suffix.end(), t.end() - static_cast<std::ptrdiff_t>(suffix.size()));
}

bool isCount(const std::string& text, long* value) {
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos) return false;
  *value = std::strtol(text.c_str(), nullptr, 10);
  return *value <= kMaxDeclaredCount;
}

bool isNumber(const std::string& text) {
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size();
}

/// The log's lines, read as ompl_benchmark_statistics reads them (one
/// readline() at a time), with what each step expects.
class LogReader {
 public:
  explicit LogReader(const std::filesystem::path& file) : file_(file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw InvalidInputError(file.string() + ": cannot read the benchmark log");
    std::string line;
    while (std::getline(in, line)) lines_.push_back(line);
    if (in.bad()) throw InvalidInputError(file.string() + ": cannot read the benchmark log");
  }

  bool atEnd() const { return next_ >= lines_.size(); }
  const std::string& peek() const { return lines_[next_]; }

  /// The next line; `what` names it in the error when the file ends.
  const std::string& line(const std::string& what) {
    if (atEnd()) fail(what);
    return lines_[next_++];
  }

  /// "<value> suffix..." (value a number).
  void value(const std::vector<std::string>& suffix, const std::string& what) {
    const std::vector<std::string> t = tokens(line(what));
    if (!endsWith(t, suffix, true) || !isNumber(t[0])) failAt(what);
  }

  /// "<n> suffix..." (n a count); returns n.
  long count(const std::vector<std::string>& suffix, const std::string& what) {
    const std::vector<std::string> t = tokens(line(what));
    long n = 0;
    if (!endsWith(t, suffix, true) || !isCount(t[0], &n)) failAt(what);
    return n;
  }

  /// As count() when the next line matches, else 0 without reading it
  /// (ompl_benchmark_statistics' optional values).
  long optionalCount(const std::vector<std::string>& suffix, const std::string& what) {
    if (atEnd()) return 0;
    const std::vector<std::string> t = tokens(peek());
    if (!endsWith(t, suffix, false)) return 0;
    return count(suffix, what);
  }

  /// A "<<<|" ... "|>>>" block (optional: only when the next line opens one).
  void block(const std::string& what, bool optional) {
    if (optional && (atEnd() || peek().rfind("<<<|", 0) != 0)) return;
    if (line(what + " (a line '<<<|')").rfind("<<<|", 0) != 0) failAt(what + " (a line '<<<|')");
    const std::size_t opened = next_;
    while (!atEnd() && peek().rfind("|>>>", 0) != 0) ++next_;
    if (atEnd()) {
      fail("the line '|>>>' closing the " + what + " opened at line " + std::to_string(opened));
    }
    ++next_;
  }

  /// Reports the line just read as not being `what`.
  [[noreturn]] void failAt(const std::string& what) const {
    --next_;
    fail(what);
  }

  /// Reports that the next line is not `what`.
  [[noreturn]] void fail(const std::string& what) const {
    std::string found = "the end of the file";
    if (!atEnd()) {
      std::string text = lines_[next_];
      if (text.size() > kMaxQuotedLine) text = text.substr(0, kMaxQuotedLine) + "...";
      found = "'" + text + "'";
    }
    throw InvalidInputError(file_.string() + ": line " + std::to_string(next_ + 1) + ": expected " + what + ", found " +
                            found + " (the log is cut off or is not an OMPL benchmark log)");
  }

 private:
  std::filesystem::path file_;
  std::vector<std::string> lines_;
  mutable std::size_t next_ = 0;
};

/// One planner's section.
void checkPlanner(LogReader& r, long index) {
  const std::string planner = "planner " + std::to_string(index + 1);
  if (r.line(planner + "'s name").empty()) r.failAt(planner + "'s name");
  const long common = r.count({"common", "properties"}, "'<n> common properties' of " + planner);
  for (long k = 0; k < common; ++k) r.line("common property " + std::to_string(k + 1) + " of " + planner);
  const long properties = r.count({"properties", "for", "each", "run"}, "'<n> properties for each run' of " + planner);
  // Whether each property's values must be numbers. The statistics script
  // makes the last word a column's type (any word: OMPL's informed trees
  // write "best cost DOUBLE"), and sqlite keeps text in a column of any
  // type, which the report's medians cannot sort: the properties the report
  // reads need a numeric type, and a numeric type needs numbers.
  std::vector<bool> numeric;
  for (long k = 0; k < properties; ++k) {
    const std::string what = "run property " + std::to_string(k + 1) + " of " + planner + " ('<name> <TYPE>')";
    const std::vector<std::string> t = tokens(r.line(what));
    if (t.size() < 2) r.failAt(what);
    const std::string& type = t.back();
    numeric.push_back(std::find(std::begin(kNumericTypes), std::end(kNumericTypes), type) != std::end(kNumericTypes));
    std::string name = t.front();
    for (std::size_t w = 1; w + 1 < t.size(); ++w) name += " " + t[w];
    const bool read =
        std::find(std::begin(kReportedNumbers), std::end(kReportedNumbers), name) != std::end(kReportedNumbers);
    if (read && !numeric.back()) {
      r.failAt(what + "; the report reads '" + name +
               "' as a number, so its TYPE must be BOOLEAN, INTEGER, REAL, ENUM, DOUBLE, FLOAT or NUMERIC");
    }
  }
  const long runs = r.count({"runs"}, "'<n> runs' of " + planner);
  for (long k = 0; k < runs; ++k) {
    const std::string what = "run " + std::to_string(k + 1) + " of " + planner + " (" + std::to_string(properties) +
                             " values, each followed by '; ')";
    // ompl_benchmark_statistics: line.split('; ')[:-1], one value per property.
    const std::string& text = r.line(what);
    long values = 0;
    std::size_t from = 0;
    for (std::size_t at = text.find("; "); at != std::string::npos; at = text.find("; ", from)) {
      // Empty, nan and inf are OMPL's "no value"; other text in a numeric
      // property is no value at all.
      const std::string value = text.substr(from, at - from);
      if (values < properties && numeric[static_cast<std::size_t>(values)] && !value.empty() && !isNumber(value)) {
        r.failAt(what + "; value " + std::to_string(values + 1) + ", '" + value.substr(0, kMaxQuotedLine) +
                 "', is not a number");
      }
      ++values;
      from = at + 2;
    }
    if (values != properties) r.failAt(what);
  }
  // Then "." or the progress data: its properties, runs, and ".".
  if (!r.atEnd() && tokens(r.peek()) == std::vector<std::string>{"."}) {
    r.line(".");
    return;
  }
  const long progress = r.count({"progress", "properties", "for", "each", "run"},
                                "'.' or '<n> progress properties for each run' ending " + planner);
  for (long k = 0; k < progress; ++k) r.line("progress property " + std::to_string(k + 1) + " of " + planner);
  const long progress_runs = r.count({"runs"}, "'<n> runs' of the progress data of " + planner);
  for (long k = 0; k < progress_runs; ++k) {
    r.line("progress data of run " + std::to_string(k + 1) + " of " + planner);
  }
  if (tokens(r.line("'.' ending " + planner)) != std::vector<std::string>{"."}) r.failAt("'.' ending " + planner);
}

std::uint64_t fnv1a(const std::string& bytes) {
  constexpr std::uint64_t kOffsetBasis = 14695981039346656037ULL;
  constexpr std::uint64_t kPrime = 1099511628211ULL;
  std::uint64_t h = kOffsetBasis;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= kPrime;
  }
  return h;
}

std::string readAll(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in || in.bad()) throw InvalidInputError(file.string() + ": cannot read the benchmark log");
  return text.str();
}

}  // namespace

void checkBenchLog(const std::filesystem::path& log) {
  LogReader r(log);
  // "<library> version <x>" (optional), "Experiment <name>", experiment
  // properties (optional), host, date.
  if (!r.atEnd() && tokens(r.peek()).size() >= 2 && tokens(r.peek())[1] == "version") r.line("version");
  {
    const std::vector<std::string> t = tokens(r.line("'Experiment <name>'"));
    if (t.empty() || t[0] != "Experiment") r.failAt("'Experiment <name>'");
  }
  const long properties = r.optionalCount({"experiment", "properties"}, "'<n> experiment properties'");
  for (long k = 0; k < properties; ++k) {
    const std::string what = "experiment property " + std::to_string(k + 1) + " ('<name> <TYPE> = <value>')";
    if (r.line(what).find(" = ") == std::string::npos) r.failAt(what);
  }
  {
    const std::vector<std::string> t = tokens(r.line("'Running on <host>'"));
    if (t.empty() || t[0] != "Running") r.failAt("'Running on <host>'");
  }
  if (r.line("'Starting at <date>'").rfind("Starting", 0) != 0) r.failAt("'Starting at <date>'");
  r.block("setup block", false);
  r.block("CPU-info block", true);
  // Seed, limits, runs, time, enums.
  {
    const std::vector<std::string> t = tokens(r.line("'<seed> is the random seed'"));
    if (!endsWith(t, {"random", "seed"}, true)) r.failAt("'<seed> is the random seed'");
  }
  r.value({"seconds", "per", "run"}, "'<t> seconds per run'");
  r.value({"MB", "per", "run"}, "'<m> MB per run'");
  r.optionalCount({"runs", "per", "planner"}, "'<n> runs per planner'");
  r.value({"collect", "the", "data"}, "'<t> seconds spent to collect the data'");
  if (!r.atEnd()) {
    const std::vector<std::string> t = tokens(r.peek());
    if (t.size() >= 2 && t[t.size() - 2] == "enum") {
      long enums = 0;
      r.line("'<n> enum types'");
      if (!isCount(t[0], &enums)) r.failAt("'<n> enum types'");
      for (long k = 0; k < enums; ++k) r.line("enum type " + std::to_string(k + 1));
    }
  }
  const long planners = r.count({"planners"}, "'<n> planners' (at least one)");
  if (planners == 0) r.failAt("'<n> planners' (at least one)");
  for (long p = 0; p < planners; ++p) checkPlanner(r, p);
}

std::vector<DuplicateLog> findDuplicateLogs(const std::vector<std::filesystem::path>& logs) {
  // Identical files, grouped by size and hash, then compared byte by byte.
  std::map<std::pair<std::size_t, std::uint64_t>, std::vector<std::pair<std::filesystem::path, std::string>>> groups;
  for (const std::filesystem::path& log : logs) {
    std::string bytes = readAll(log);
    const auto key = std::make_pair(bytes.size(), fnv1a(bytes));
    groups[key].emplace_back(log, std::move(bytes));
  }
  std::vector<DuplicateLog> out;
  for (auto& [key, files] : groups) {
    std::sort(files.begin(), files.end(), [](const auto& x, const auto& y) {
      const std::string a = x.first.filename().string();
      const std::string b = y.first.filename().string();
      return a.size() != b.size() ? a.size() < b.size() : a < b;
    });
    std::vector<bool> done(files.size(), false);
    for (std::size_t i = 0; i < files.size(); ++i) {
      if (done[i]) continue;
      for (std::size_t j = i + 1; j < files.size(); ++j) {
        if (!done[j] && files[j].second == files[i].second) {
          out.push_back({files[j].first, files[i].first});
          done[j] = true;
        }
      }
    }
  }
  std::sort(out.begin(), out.end(), [](const DuplicateLog& a, const DuplicateLog& b) { return a.copy < b.copy; });
  return out;
}

}  // namespace mddual::planning
