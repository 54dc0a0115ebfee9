// JSON Lines plumbing shared by the per-line subcommands (see jsonl.h).
#include "jsonl.h"

#include <cmath>
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "mddual/error.h"

namespace mddual::cli {
namespace {

bool isBlank(const std::string& line) {
  return line.find_first_not_of(" \t\r\n\f\v") == std::string::npos;
}

/// nlohmann's message without its "[json.exception.parse_error.101] " prefix.
std::string jsonMessage(const nlohmann::json::exception& e) {
  const std::string what = e.what();
  const std::size_t close = what.find("] ");
  return !what.empty() && what.front() == '[' && close != std::string::npos ? what.substr(close + 2) : what;
}

/// A short rendering of a JSON value for error messages.
std::string shortDump(const Json& value) {
  constexpr std::size_t kMaxChars = 60;
  std::string text = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (text.size() > kMaxChars) text = text.substr(0, kMaxChars) + "...";
  return text;
}

/// The output line for an input line, or its error.
Json answerLine(const std::string& text, const LineHandler& handler, bool* failed) {
  Json id = nullptr;
  try {
    Json line;
    try {
      line = Json::parse(text);
    } catch (const nlohmann::json::exception& e) {
      throw LineError("invalid JSON: " + jsonMessage(e));
    }
    if (!line.is_object()) throw LineError("expected a JSON object, got " + shortDump(line));
    const auto it = line.find("id");
    if (it != line.end()) id = *it;
    Json out = Json::object();
    out["id"] = id;
    Json fields = handler(line);
    for (auto& item : fields.items()) out[item.key()] = std::move(item.value());
    *failed = false;
    return out;
  } catch (const LineError& e) {
    *failed = true;
    return Json{{"id", id}, {"error", e.what()}};
  } catch (const Error& e) {
    *failed = true;
    return Json{{"id", id}, {"error", e.what()}};
  }
}

}  // namespace

JsonLinesIo::JsonLinesIo(const std::string& input_path, const std::string& output_path)
    : in_(&std::cin), out_(&std::cout) {
  if (!input_path.empty() && input_path != "-") {
    file_in_.open(input_path);
    if (!file_in_.is_open()) throw FatalError("cannot open input file '" + input_path + "'");
    in_ = &file_in_;
  }
  if (!output_path.empty() && output_path != "-") {
    std::error_code ignored;
    if (file_in_.is_open() && std::filesystem::equivalent(input_path, output_path, ignored)) {
      throw FatalError("the input and output files are the same file '" + output_path + "'");
    }
    file_out_.open(output_path, std::ios::out | std::ios::trunc);
    if (!file_out_.is_open()) throw FatalError("cannot open output file '" + output_path + "'");
    out_ = &file_out_;
  }
}

JsonLinesSummary runJsonLines(std::istream& in, std::ostream& out, const LineHandler& handler) {
  JsonLinesSummary summary;
  std::string text;
  long line_number = 0;
  while (std::getline(in, text)) {
    ++line_number;
    if (isBlank(text)) continue;
    bool failed = false;
    const Json result = answerLine(text, handler, &failed);
    ++(failed ? summary.failed : summary.answered);
    out << result.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
    out.flush();
    if (!out) throw FatalError("cannot write the output (line " + std::to_string(line_number) + ")");
  }
  if (in.bad()) throw FatalError("error reading the input after line " + std::to_string(line_number));
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
