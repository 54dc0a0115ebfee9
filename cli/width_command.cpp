// `mddual width`: the width of one polytope per JSON line (the contract
// scripts call; see the help text below): width(A) = PD(A, A), the smallest
// distance between two parallel planes enclosing the hull of "a".
#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "commands.h"
#include "jsonl.h"
#include "mddual/defaults.h"
#include "mddual/penetration.h"
#include "pd_json.h"

namespace mddual::cli {
namespace {

struct WidthOptions {
  std::string method = "exact";
  std::string delta;  ///< as given (empty: the method's default)
  bool delta_given = false;
  std::string input;
  std::string output;
};

Json answerWidth(const Json& line, PenetrationMethod method, double delta) {
  const ConvexPolytope a = readPolytope(line, "a");
  WidthInput in;
  in.a = &a;
  in.method = method;
  in.delta = delta;
  const WidthResult r = width(in);
  Json out = Json::object();
  out["width"] = r.width;
  out["direction"] = vectorOrNull(r.direction_W);
  out["facet"] = toJson(r.facet);
  out["features"] = Json{{"a", toJson(r.feature_a)}, {"b", toJson(r.feature_b)}};
  out["method"] = toString(method);
  out["delta"] = r.delta > 0.0 ? Json(r.delta) : Json(nullptr);
  if (method != PenetrationMethod::kBruteForce) out["stats"] = toJson(r.stats);
  return out;
}

void runWidth(const WidthOptions& options) {
  // Options first: a usage error must not truncate the output file.
  const PenetrationMethod method = methodFromName(options.method);
  const double delta = deltaOption(options.delta, options.delta_given, method, options.method);
  JsonLinesIo io(options.input, options.output);
  const JsonLinesSummary summary = runJsonLines(
      io.in(), io.out(), [method, delta](const Json& line) { return answerWidth(line, method, delta); },
      io.inputName());
  if (summary.failed > 0) throw CLI::RuntimeError(1);
}

constexpr const char* kWidthDescription =
    "Width of polytopes read as JSON Lines, one per line:\n"
    "  {\"id\": any, \"a\": [[x,y,z], ...]}\n"
    "The width of the convex hull of the points is the smallest distance between two parallel\n"
    "planes enclosing it (= its penetration depth with itself). Each line gets one output line:\n"
    "  {\"id\", \"width\", \"direction\": [x,y,z] (unit normal of the two planes), \"facet\",\n"
    "   \"features\" (of A on the upper / lower plane), \"method\", \"delta\", \"stats\"}\n"
    "approx: width <= reported <= (1 + delta) width, and the hull's extent along \"direction\" is\n"
    "the reported value. A flat polygon has width 0 (direction: its normal). A bad line gets\n"
    "{\"id\", \"error\"} and the run goes on. Exit status: 0 if every line was answered, 1 if some\n"
    "line failed, 2 if a file cannot be opened.";

}  // namespace

void registerWidthCommand(CLI::App& app) {
  auto options = std::make_shared<WidthOptions>();
  CLI::App* sub = app.add_subcommand("width", "width of convex polytopes (exact or approximate) for JSON Lines");
  sub->footer(kWidthDescription);
  sub->add_option("--method", options->method,
                  "exact: every facet of A - A (default); approx: (1 + delta)-approximation by ray shots; "
                  "brute: explicit A - A")
      ->check(CLI::IsMember({"exact", "approx", "brute"}))
      ->capture_default_str();
  sub->add_option("--delta", options->delta,
                  "accuracy of approx: default " + formatNumber(defaults::kApproxPdDelta) + ", range " +
                      deltaRange(PenetrationMethod::kApprox) + " (exact, brute: ignored)")
      ->option_text("D");
  sub->add_option("--input", options->input, "read polytopes from FILE (default or -: standard input)")
      ->option_text("FILE");
  sub->add_option("--output", options->output, "write answers to FILE (default or -: standard output)")
      ->option_text("FILE");
  sub->callback([options, sub] {
    options->delta_given = sub->count("--delta") > 0;
    runWidth(*options);
  });
}

}  // namespace mddual::cli
