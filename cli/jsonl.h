// JSON Lines plumbing shared by the subcommands that answer one query per
// input line (query today; pd and width later):
//   - JsonLinesIo opens the input and output (standard streams by default);
//   - runJsonLines() streams the input line by line, calls a handler per
//     line, writes one output line per input line, in order, flushed, and
//     turns a bad line into {"id": ..., "error": "..."} without stopping;
//   - readers for the common fields, whose errors name the field;
//   - writers for the library's result types (NaN -> null).
#pragma once

#include "mddual/error.h"

#include <Eigen/Core>
#include <cstddef>
#include <fstream>
#include <functional>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "mddual/polytope.h"
#include "mddual/query.h"

namespace mddual::cli {

/// Key order is kept as inserted, so output lines read id first.
using Json = nlohmann::ordered_json;

/// A problem with one input line. runJsonLines() reports it as the line's
/// error and goes on; what() should start with the field it is about.
class LineError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The command's input and output: a file when a path is given, otherwise
/// standard input / standard output. Throws FatalError ("cannot open input
/// file 'X'") when a file cannot be opened; the input is opened first, so a
/// bad input never truncates the output file.
class JsonLinesIo {
 public:
  JsonLinesIo(const std::string& input_path, const std::string& output_path);
  JsonLinesIo(const JsonLinesIo&) = delete;
  JsonLinesIo& operator=(const JsonLinesIo&) = delete;

  std::istream& in() { return *in_; }
  std::ostream& out() { return *out_; }
  /// "'<path>'" of the input file, or "standard input" (for messages).
  const std::string& inputName() const { return input_name_; }

 private:
  std::string input_name_ = "standard input";
  std::ifstream file_in_;
  std::ofstream file_out_;
  std::istream* in_;
  std::ostream* out_;
};

/// Turns one input object into the fields of its output line (without "id",
/// which runJsonLines() writes first). Throw LineError or any mddual::Error for
/// a bad line; any other exception (std::bad_alloc included) also becomes that
/// line's error.
using LineHandler = std::function<Json(const Json& line)>;

struct JsonLinesSummary {
  long answered = 0;  ///< lines with a result
  long failed = 0;    ///< lines answered with an error
};

/// Deepest nesting of arrays and objects accepted in an input line. Real
/// inputs nest 3 deep (an array of points); writing back a deeply nested id
/// recurses once per level, so a line nested some 70,000 deep would overflow
/// the stack. Such a line is refused before it is parsed.
inline constexpr int kMaxJsonDepth = 64;

// clipForMessage (a user's string in a message): mddual/error.h.

/// Reads `in` to the end, one JSON object per line, in constant memory. Blank
/// lines are skipped; every other line gets exactly one output line on `out`,
/// flushed at once. A line's "id" is echoed as its JSON text, exactly as
/// given. Throws FatalError if writing or reading fails (`input_name` names
/// the input in that message).
JsonLinesSummary runJsonLines(std::istream& in, std::ostream& out, const LineHandler& handler,
                              const std::string& input_name = "standard input");

// ---- Readers (errors are LineErrors naming the field) --------------------------

/// line[name]; "name: missing field" if absent.
const Json& requireField(const Json& line, const std::string& name);
/// Three finite numbers; "<where>: expected 3 numbers" otherwise.
Eigen::Vector3d readVector3(const Json& value, const std::string& where);
/// A non-empty array of points; errors name the point, e.g. "a[3]: ...".
std::vector<Eigen::Vector3d> readPoints(const Json& value, const std::string& where);
/// The convex hull of the point set line[name]; the library's errors come back
/// as "name: <library message>".
ConvexPolytope readPolytope(const Json& line, const std::string& name);
/// line[name] as a direction: "name: must be finite and nonzero" otherwise.
Eigen::Vector3d readDirection(const Json& line, const std::string& name = "direction");

// ---- Writers ---------------------------------------------------------------------

/// The number, or null when it is NaN or infinite.
Json numberOrNull(double x);
/// [x, y, z], or null when any coordinate is NaN or infinite.
Json vectorOrNull(const Eigen::Vector3d& v);
/// {"type": "face"|"edge"|"vertex"|"none", "index": n}.
Json toJson(const Feature& feature);
/// The SearchStats fields by name.
Json toJson(const SearchStats& stats);

}  // namespace mddual::cli
