// Checks on OMPL benchmark logs before `mddual bench-report` hands them to
// OMPL's ompl_benchmark_statistics:
//   - checkBenchLog(): the log's structure as that script reads it, every
//     declared count present. The script loops forever on a log cut off
//     inside one of its "<<<| ... |>>>" blocks (its setup or CPU-info text)
//     and stops with a bare Python traceback on most other cuts; a log that
//     passes here is read to its end.
//   - findDuplicateLogs(): logs with the same content (a copied file, e.g.
//     "thin_walls-mdd (copy).log"), whose runs would be counted twice.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace mddual::planning {

/// Checks that `log` is a complete OMPL benchmark log in the format
/// ompl::tools::Benchmark::saveResultsToStream writes: header lines, the
/// setup and optional CPU-info blocks closed, the limits, the enums, and for
/// each of its planners (at least one) its declared common properties, run
/// properties ("<name> <TYPE>"; the ones scripts/bench_report.py reads as
/// numbers, such as time, of a numeric TYPE: BOOLEAN, INTEGER, REAL, ENUM,
/// DOUBLE, FLOAT or NUMERIC), runs (each with one value per run property, for
/// a numeric TYPE a number or OMPL's empty, nan or inf) and progress data,
/// ending with ".".
/// Throws InvalidInputError "<file>: line <n>: expected <what>, found <the
/// line | the end of the file> (the log is cut off or is not an OMPL
/// benchmark log)".
void checkBenchLog(const std::filesystem::path& log);

/// A log whose content is byte for byte that of another.
struct DuplicateLog {
  std::filesystem::path copy;  ///< left out
  std::filesystem::path kept;  ///< counted
};

/// The logs of `logs` that repeat another's content (compared by a 64-bit
/// FNV-1a hash of the bytes, then byte by byte). Of each set of identical
/// logs the one with the shortest file name is kept (the name mddual bench
/// gave it, not "X (copy).log"), ties by name. Throws InvalidInputError for
/// a file that cannot be read.
std::vector<DuplicateLog> findDuplicateLogs(const std::vector<std::filesystem::path>& logs);

}  // namespace mddual::planning
