// JSON Lines plumbing shared by the per-line subcommands (see jsonl.h).
#include "jsonl.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <new>
#include <optional>

#include "commands.h"
#include "mddual/error.h"

namespace mddual::cli {
namespace {

bool isBlank(const std::string& line) {
  return line.find_first_not_of(" \t\r\n\f\v") == std::string::npos;
}

bool isJsonSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

/// nlohmann's message without its "[json.exception.parse_error.101] " prefix,
/// clipped (its "last read: '...'" can quote a whole line).
std::string jsonMessage(const nlohmann::json::exception& e) {
  const std::string what = e.what();
  const std::size_t close = what.find("] ");
  return clipForMessage(!what.empty() && what.front() == '[' && close != std::string::npos ? what.substr(close + 2)
                                                                                           : what);
}

/// A short rendering of a JSON value for error messages.
std::string shortDump(const Json& value) {
  constexpr std::size_t kMaxChars = 60;
  std::string text = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (text.size() > kMaxChars) text = text.substr(0, kMaxChars) + "...";
  return text;
}

/// Index of the quote closing the JSON string that opens at text[open], or
/// text.size() if it is not closed.
std::size_t stringEnd(const std::string& text, std::size_t open) {
  for (std::size_t i = open + 1; i < text.size(); ++i) {
    if (text[i] == '\\') {
      ++i;
    } else if (text[i] == '"') {
      return i;
    }
  }
  return text.size();
}

/// Byte offset at which `text` opens its (kMaxJsonDepth + 1)-th nested array
/// or object (brackets inside strings do not count), or npos. Linear, no
/// recursion: it runs before the parser sees the line.
std::size_t tooDeepAt(const std::string& text) {
  int depth = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"') {
      i = stringEnd(text, i);
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) return i;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return std::string::npos;
}

/// Whether the raw JSON string `raw` (quotes included) spells "id".
bool isIdKey(const std::string& raw) {
  if (raw == "\"id\"") return true;
  if (raw.find('\\') == std::string::npos) return false;
  try {
    return Json::parse(raw) == "id";
  } catch (const nlohmann::json::exception&) {
    return false;
  }
}

/// The JSON text of the top-level "id" member of the object `text` (which
/// parsed), as given; the last one when repeated, as the parser keeps.
std::optional<std::string> rawIdText(const std::string& text) {
  enum class Expect : std::uint8_t { kKey, kColon, kValue, kInValue };
  std::optional<std::string> found;
  Expect expect = Expect::kKey;
  bool key_is_id = false;
  std::size_t value_start = 0;
  int depth = 0;
  const auto endValue = [&](std::size_t end) {
    if (expect == Expect::kInValue && key_is_id) {
      std::size_t last = end;
      while (last > value_start && isJsonSpace(text[last - 1])) --last;
      found = text.substr(value_start, last - value_start);
    }
    expect = Expect::kKey;
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (isJsonSpace(c)) continue;
    const bool top = depth == 1;
    if (top && expect == Expect::kValue) {
      value_start = i;
      expect = Expect::kInValue;
    }
    if (c == '"') {
      const std::size_t end = stringEnd(text, i);
      if (top && expect == Expect::kKey) {
        key_is_id = isIdKey(text.substr(i, end + 1 - i));
        expect = Expect::kColon;
      }
      i = end;
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if (c == ']' || c == '}') {
      if (top) endValue(i);
      --depth;
    } else if (top && c == ':') {
      expect = Expect::kValue;
    } else if (top && c == ',') {
      endValue(i);
    }
  }
  return found;
}

/// The id to echo: its JSON text as given (so that integers beyond 64 bits
/// and numbers such as 1.0 or 1e2 come back unchanged), or the parsed value
/// written out should the text not read back as the same value.
std::string idText(const std::string& text, const Json& id) {
  const std::optional<std::string> raw = rawIdText(text);
  if (raw) {
    try {
      if (Json::parse(*raw) == id) return *raw;
    } catch (const nlohmann::json::exception&) {
    }
  }
  return id.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

/// One output line: its id (JSON text) and the other fields, or the error.
struct Answer {
  std::string id = "null";
  Json fields;
  bool failed = false;
};

Answer failedAnswer(std::string id, const std::string& message) {
  Answer a;
  a.id = std::move(id);
  a.fields = Json{{"error", message}};
  a.failed = true;
  return a;
}

/// The output line for an input line, or its error. Every exception ends
/// here: a line that fails (even by running out of memory) is that line's
/// error, and the run goes on.
Answer answerLine(const std::string& text, const LineHandler& handler) {
  std::string id = "null";
  try {
    const std::size_t deep = tooDeepAt(text);
    if (deep != std::string::npos) {
      throw LineError("invalid JSON: arrays and objects nested deeper than " + std::to_string(kMaxJsonDepth) +
                      " levels (at byte " + std::to_string(deep + 1) + ")");
    }
    Json line;
    try {
      line = Json::parse(text);
    } catch (const nlohmann::json::exception& e) {
      throw LineError("invalid JSON: " + jsonMessage(e));
    }
    if (!line.is_object()) throw LineError("expected a JSON object, got " + shortDump(line));
    const auto it = line.find("id");
    if (it != line.end()) id = idText(text, *it);
    Answer a;
    a.id = id;
    a.fields = handler(line);
    return a;
  } catch (const LineError& e) {
    return failedAnswer(id, e.what());
  } catch (const Error& e) {
    return failedAnswer(id, e.what());
  } catch (const std::bad_alloc&) {
    return failedAnswer(id, "out of memory while answering this line (std::bad_alloc)");
  } catch (const std::exception& e) {
    return failedAnswer(id, "unexpected error: " + clipForMessage(e.what()));
  } catch (...) {
    return failedAnswer(id, "unexpected error (unknown exception)");
  }
}

/// {"id":<id>, <fields>} on one line, compact.
std::string outputLine(const Answer& a) {
  std::string line = "{\"id\":" + a.id;
  const std::string fields = a.fields.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  // fields is "{...}" or "{}" (or "null" for a handler that returned nothing).
  if (a.fields.is_object() && fields.size() > 2)
    line += "," + fields.substr(1);
  else
    line += "}";
  return line;
}

}  // namespace

JsonLinesIo::JsonLinesIo(const std::string& input_path, const std::string& output_path)
    : in_(&std::cin), out_(&std::cout) {
  if (!input_path.empty() && input_path != "-") {
    input_name_ = "input file '" + clipForMessage(input_path) + "'";
    std::error_code ignored;
    // A directory opens as a stream on Linux and only fails when read.
    if (std::filesystem::is_directory(input_path, ignored)) {
      throw FatalError("--input '" + clipForMessage(input_path) + "' is a directory, not a file");
    }
    file_in_.open(input_path);
    if (!file_in_.is_open()) throw FatalError("cannot open input file '" + clipForMessage(input_path) + "'");
    in_ = &file_in_;
  }
  if (!output_path.empty() && output_path != "-") {
    std::error_code ignored;
    if (file_in_.is_open() && std::filesystem::equivalent(input_path, output_path, ignored)) {
      throw FatalError("the input and output files are the same file '" + clipForMessage(output_path) + "'");
    }
    if (std::filesystem::is_directory(output_path, ignored)) {
      throw FatalError("--output '" + clipForMessage(output_path) + "' is a directory, not a file");
    }
    file_out_.open(output_path, std::ios::out | std::ios::trunc);
    if (!file_out_.is_open()) throw FatalError("cannot open output file '" + clipForMessage(output_path) + "'");
    out_ = &file_out_;
  }
}

JsonLinesSummary runJsonLines(std::istream& in, std::ostream& out, const LineHandler& handler,
                              const std::string& input_name) {
  JsonLinesSummary summary;
  std::string text;
  long line_number = 0;
  while (std::getline(in, text)) {
    ++line_number;
    if (isBlank(text)) continue;
    const Answer answer = answerLine(text, handler);
    ++(answer.failed ? summary.failed : summary.answered);
    out << outputLine(answer) << '\n';
    out.flush();
    if (!out) throw FatalError("cannot write the output (line " + std::to_string(line_number) + ")");
  }
  if (in.bad()) {
    throw FatalError("error reading " + input_name + " after line " + std::to_string(line_number));
  }
  return summary;
}

const Json& requireField(const Json& line, const std::string& name) {
  const auto it = line.find(name);
  if (it == line.end()) throw LineError(name + ": missing field");
  return *it;
}

Eigen::Vector3d readVector3(const Json& value, const std::string& where) {
  if (!value.is_array() || value.size() != 3) {
    throw LineError(where + ": expected 3 numbers, got " + shortDump(value));
  }
  Eigen::Vector3d v;
  for (int k = 0; k < 3; ++k) {
    const Json& x = value[static_cast<std::size_t>(k)];
    if (!x.is_number()) throw LineError(where + ": expected 3 numbers, got " + shortDump(value));
    v[k] = x.get<double>();
    if (!std::isfinite(v[k])) throw LineError(where + ": coordinate " + std::to_string(k) + " is not finite");
  }
  return v;
}

std::vector<Eigen::Vector3d> readPoints(const Json& value, const std::string& where) {
  if (!value.is_array()) throw LineError(where + ": expected an array of points, got " + shortDump(value));
  if (value.empty()) throw LineError(where + ": expected at least one point, got []");
  std::vector<Eigen::Vector3d> points;
  points.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i) {
    points.push_back(readVector3(value[i], where + "[" + std::to_string(i) + "]"));
  }
  return points;
}

ConvexPolytope readPolytope(const Json& line, const std::string& name) {
  const std::vector<Eigen::Vector3d> points = readPoints(requireField(line, name), name);
  try {
    return ConvexPolytope::fromPoints(points);
  } catch (const Error& e) {
    throw LineError(name + ": " + e.what());
  }
}

Eigen::Vector3d readDirection(const Json& line, const std::string& name) {
  const Eigen::Vector3d s = readVector3(requireField(line, name), name);
  // Only the direction matters: rescaling by the largest coordinate keeps
  // |s| representable for tiny or huge inputs such as [1e-200, 0, 0].
  const double largest = s.cwiseAbs().maxCoeff();
  if (!(largest > 0.0) || !std::isfinite(largest)) throw LineError(name + ": must be finite and nonzero");
  return s / largest;
}

Json numberOrNull(double x) {
  return std::isfinite(x) ? Json(x) : Json(nullptr);
}

Json vectorOrNull(const Eigen::Vector3d& v) {
  if (!v.allFinite()) return nullptr;
  return Json::array({v.x(), v.y(), v.z()});
}

Json toJson(const Feature& feature) {
  return Json{{"type", toString(feature.type)}, {"index", feature.index}};
}

Json toJson(const SearchStats& stats) {
  return Json{{"centre_iterations", stats.centre_iterations},
              {"fv_faces", stats.fv_faces},
              {"vf_faces", stats.vf_faces},
              {"ee_faces", stats.ee_faces},
              {"ee_edge_faces", stats.ee_edge_faces},
              {"steps", stats.steps},
              {"rays", stats.rays},
              {"support_vertices", stats.support_vertices},
              {"planar", stats.planar}};
}

}  // namespace mddual::cli
