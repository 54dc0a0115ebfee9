// `mddual distance`: the separation distance of one pair per JSON line (the
// contract scripts call; see the help text below). A and B are the convex
// hulls of the point sets "a" and "b" at identity poses.
#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "commands.h"
#include "jsonl.h"
#include "mddual/distance.h"

namespace mddual::cli {
namespace {

struct DistanceOptions {
  std::string input;
  std::string output;
};

Json answerDistance(const Json& line) {
  const ConvexPolytope a = readPolytope(line, "a");
  const ConvexPolytope b = readPolytope(line, "b");
  DistanceInput in;
  in.a = &a;
  in.b = &b;
  const DistanceResult r = distance(in);
  Json out = Json::object();
  out["distance"] = r.distance;
  out["status"] = toString(r.status);
  out["intersecting"] = r.status != DistanceStatus::kSeparated;
  out["lower_bound"] = r.lower_bound;
  out["point_a"] = vectorOrNull(r.p_WA);
  out["point_b"] = vectorOrNull(r.p_WB);
  out["normal"] = vectorOrNull(r.normal_W);
  out["stats"] = Json{{"gjk_iterations", r.stats.gjk_iterations},
                      {"support_vertices", r.stats.support_vertices},
                      {"polished", r.stats.polished},
                      {"polish_pairs", r.stats.polish_pairs},
                      {"penetration", r.stats.penetration}};
  return out;
}

void runDistance(const DistanceOptions& options) {
  JsonLinesIo io(options.input, options.output);
  const JsonLinesSummary summary = runJsonLines(io.in(), io.out(), answerDistance, io.inputName());
  if (summary.failed > 0) throw CLI::RuntimeError(1);
}

constexpr const char* kDistanceDescription =
    "Separation distance of point-set hulls read as JSON Lines, one pair per line:\n"
    "  {\"id\": any, \"a\": [[x,y,z], ...], \"b\": [[x,y,z], ...]}\n"
    "Each line gets one output line:\n"
    "  {\"id\", \"distance\", \"status\", \"intersecting\", \"lower_bound\", \"point_a\", \"point_b\",\n"
    "   \"normal\", \"stats\"}\n"
    "separated: distance = |point_b - point_a| > 0 (closest points of A and B), normal from A toward\n"
    "B, exact to 1e-9 of the pair's size (lower_bound certifies it); touching: distance 0, a common\n"
    "point, normal null; penetrating: distance = minus the penetration depth, point_a - point_b =\n"
    "depth * normal (B moved by that touches A). A bad line gets {\"id\", \"error\"} and the run\n"
    "goes on. Exit status: 0 if every line was answered, 1 if some line failed, 2 if a file cannot\n"
    "be opened.";

}  // namespace

void registerDistanceCommand(CLI::App& app) {
  auto options = std::make_shared<DistanceOptions>();
  CLI::App* sub = app.add_subcommand("distance", "exact separation distance of convex polytopes for JSON Lines");
  sub->footer(kDistanceDescription);
  sub->add_option("--input", options->input, "read pairs from FILE (default or -: standard input)")
      ->option_text("FILE");
  sub->add_option("--output", options->output, "write answers to FILE (default or -: standard output)")
      ->option_text("FILE");
  sub->callback([options] { runDistance(*options); });
}

}  // namespace mddual::cli
