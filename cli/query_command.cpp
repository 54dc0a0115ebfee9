// `mddual query`: one directional query per JSON line (the contract scripts
// call; see the help text below). A and B are the convex hulls of the point
// sets "a" and "b" at identity poses, B moves along "direction".
#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "commands.h"
#include "jsonl.h"
#include "mddual/brute_force.h"
#include "mddual/query.h"

namespace mddual::cli {
namespace {

struct QueryOptions {
  std::string method = "dual";
  std::string input;
  std::string output;
};

/// The fields of one output line (everything but "id").
Json answerQuery(const Json& line, bool brute) {
  const ConvexPolytope a = readPolytope(line, "a");
  const ConvexPolytope b = readPolytope(line, "b");
  DirectionalInput input;
  input.a = &a;
  input.b = &b;
  input.s_W = readDirection(line);
  IntersectInput intersect_input;
  intersect_input.a = &a;
  intersect_input.b = &b;

  const MddResult m = brute ? bruteForceMdd(input) : mdd(input);
  const ToiResult t = brute ? bruteForceToi(input) : toi(input);
  const IntersectResult x = brute ? bruteForceIntersect(intersect_input) : intersect(intersect_input);

  Json out = Json::object();
  out["status"] = toString(m.status);
  out["mdd"] = numberOrNull(m.distance);
  out["toi"] = t.status == ToiStatus::kNever ? Json(nullptr) : Json(t.toi);
  out["intersecting"] = x.intersecting;
  out["normal"] = vectorOrNull(m.contact.normal_W);
  out["point"] = vectorOrNull(m.contact.point_W);
  out["t_lo"] = numberOrNull(m.t_lo);
  out["t_hi"] = numberOrNull(m.t_hi);
  out["features"] = Json{{"a", toJson(m.contact.feature_a)}, {"b", toJson(m.contact.feature_b)}};
  out["toi_status"] = toString(t.status);
  out["intersect_status"] = toString(x.status);
  out["method"] = brute ? "brute" : "dual";
  if (!brute) out["stats"] = toJson(m.stats);
  return out;
}

void runQuery(const QueryOptions& options) {
  JsonLinesIo io(options.input, options.output);
  const bool brute = options.method == "brute";
  const JsonLinesSummary summary = runJsonLines(
      io.in(), io.out(), [brute](const Json& line) { return answerQuery(line, brute); }, io.inputName());
  if (summary.failed > 0) throw CLI::RuntimeError(1);
}

constexpr const char* kQueryDescription =
    "Answer directional queries read as JSON Lines, one per line:\n"
    "  {\"id\": any, \"a\": [[x,y,z], ...], \"b\": [[x,y,z], ...], \"direction\": [x,y,z]}\n"
    "A and B are the convex hulls of the point sets (A fixed, B moving along the direction,\n"
    "which need not be unit length). Each line gets one output line, in order:\n"
    "  {\"id\", \"status\": separated|touching|penetrating|no_contact, \"mdd\", \"toi\",\n"
    "   \"intersecting\", \"normal\", \"point\", \"t_lo\", \"t_hi\", \"features\", \"method\", \"stats\"}\n"
    "or {\"id\", \"error\"} for a bad line (the run goes on). Exit status: 0 if every line was\n"
    "answered, 1 if some line failed, 2 if a file cannot be opened.";

}  // namespace

void registerQueryCommand(CLI::App& app) {
  auto options = std::make_shared<QueryOptions>();
  CLI::App* sub = app.add_subcommand("query", "MDD, time of impact and intersection for JSON Lines queries");
  sub->footer(kQueryDescription);
  sub->add_option("--method", options->method, "dual: MDD-DUAL (default); brute: explicit Minkowski difference")
      ->check(CLI::IsMember({"dual", "brute"}))
      ->capture_default_str();
  sub->add_option("--input", options->input, "read queries from FILE (default or -: standard input)")
      ->option_text("FILE");
  sub->add_option("--output", options->output, "write answers to FILE (default or -: standard output)")
      ->option_text("FILE");
  sub->callback([options] { runQuery(*options); });
}

}  // namespace mddual::cli
