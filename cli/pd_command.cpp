// `mddual pd`: penetration depth of one pair per JSON line (the contract
// scripts call; see the help text below). A and B are the convex hulls of
// the point sets "a" and "b" at identity poses; an optional "metric" point set
// (a centrally symmetric solid K) asks for the depth under |.|_K instead.
#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "commands.h"
#include "jsonl.h"
#include "mddual/defaults.h"
#include "mddual/error.h"
#include "mddual/penetration.h"
#include "pd_json.h"

namespace mddual::cli {
namespace {

struct PdOptions {
  std::string method = "exact";
  std::string delta;  ///< as given (empty: the method's default)
  bool delta_given = false;
  std::string input;
  std::string output;
};

/// Common fields of a penetration answer.
void putCommon(PenetrationStatus status, double depth, const Eigen::Vector3d& translation,
               const Eigen::Vector3d& normal, const FaceOfM& facet, const Feature& fa, const Feature& fb, Json* out) {
  (*out)["pd"] = depth;
  (*out)["translation"] = vectorOrNull(translation);
  (*out)["intersecting"] = status != PenetrationStatus::kSeparated;
  (*out)["status"] = toString(status);
  (*out)["normal"] = vectorOrNull(normal);
  (*out)["facet"] = toJson(facet);
  (*out)["features"] = Json{{"a", toJson(fa)}, {"b", toJson(fb)}};
}

Json answerPd(const Json& line, PenetrationMethod method, double delta) {
  const ConvexPolytope a = readPolytope(line, "a");
  const ConvexPolytope b = readPolytope(line, "b");
  Json out = Json::object();
  const auto metric_field = line.find("metric");
  if (metric_field != line.end()) {
    // PD under the polyhedral metric K: k ray shots, exact (brute: explicit M).
    const std::vector<Eigen::Vector3d> k_points = readPoints(*metric_field, "metric");
    const PolyhedralMetric metric = [&] {
      try {
        return PolyhedralMetric::fromPoints(k_points);
      } catch (const Error& e) {
        // "metric: <what is wrong>" (the library's message names K itself).
        std::string what = e.what();
        const std::string prefix = "polyhedral metric: ";
        if (what.compare(0, prefix.size(), prefix) == 0) what = what.substr(prefix.size());
        throw LineError("metric: " + what);
      }
    }();
    PolyhedralInput in;
    in.a = &a;
    in.b = &b;
    in.metric = &metric;
    in.method = method == PenetrationMethod::kBruteForce ? method : PenetrationMethod::kExact;
    const PolyhedralResult r = polyhedralPenetrationDepth(in);
    putCommon(r.status, r.depth, r.translation_W, r.normal_W, r.facet, r.feature_a, r.feature_b, &out);
    out["euclidean_length"] = r.euclidean_length;
    out["metric_vertex"] = r.k_vertex >= 0 ? Json(r.k_vertex) : Json(nullptr);
    out["method"] = toString(in.method);
    out["metric"] = true;
    if (in.method != PenetrationMethod::kBruteForce) out["stats"] = toJson(r.stats);
    return out;
  }
  PenetrationInput in;
  in.a = &a;
  in.b = &b;
  in.method = method;
  in.delta = delta;
  const PenetrationResult r = penetrationDepth(in);
  putCommon(r.status, r.depth, r.translation_W, r.normal_W, r.facet, r.feature_a, r.feature_b, &out);
  out["method"] = toString(method);
  out["delta"] = r.delta > 0.0 ? Json(r.delta) : Json(nullptr);
  if (method != PenetrationMethod::kBruteForce) out["stats"] = toJson(r.stats);
  return out;
}

void runPd(const PdOptions& options) {
  // Options first: a usage error must not truncate the output file.
  const PenetrationMethod method = methodFromName(options.method);
  const double delta = deltaOption(options.delta, options.delta_given, method, options.method);
  JsonLinesIo io(options.input, options.output);
  const JsonLinesSummary summary = runJsonLines(
      io.in(), io.out(), [method, delta](const Json& line) { return answerPd(line, method, delta); }, io.inputName());
  if (summary.failed > 0) throw CLI::RuntimeError(1);
}

constexpr const char* kPdDescription =
    "Penetration depth of pairs read as JSON Lines, one per line (the input of `mddual query`;\n"
    "a \"direction\" field is ignored):\n"
    "  {\"id\": any, \"a\": [[x,y,z], ...], \"b\": [[x,y,z], ...], \"metric\": [[x,y,z], ...] (optional)}\n"
    "A and B are the convex hulls of the point sets (A fixed, B moving). PD is the length of the\n"
    "shortest translation of B that makes the interiors disjoint (0 if they already are); the\n"
    "translation is PD times the normal of the closest facet of M = A - B (from A toward B).\n"
    "Each line gets one output line, in order:\n"
    "  {\"id\", \"pd\", \"translation\": [x,y,z], \"intersecting\", \"status\": separated|touching|\n"
    "   penetrating, \"normal\", \"facet\": {\"kind\": fv|vf|ee|none, \"a\", \"b\"}, \"features\",\n"
    "   \"method\", \"delta\", \"stats\"}\n"
    "approx: PD <= pd <= (1 + delta) PD; exact, shallow, brute: pd = PD. With \"metric\" (a centrally\n"
    "symmetric solid K): pd = min |t|_K over separating translations t (one ray per vertex of K,\n"
    "exact; brute: explicit M), plus \"euclidean_length\" and \"metric_vertex\".\n"
    "A bad line gets {\"id\", \"error\"} and the run goes on. Exit status: 0 if every line was\n"
    "answered, 1 if some line failed, 2 if a file cannot be opened.";

}  // namespace

void registerPdCommand(CLI::App& app) {
  auto options = std::make_shared<PdOptions>();
  CLI::App* sub = app.add_subcommand("pd", "penetration depth (exact, shallow, approximate) for JSON Lines pairs");
  sub->footer(kPdDescription);
  sub->add_option("--method", options->method,
                  "exact: every facet of M that matters (default); shallow: approximation + search near it; "
                  "approx: (1 + delta)-approximation by ray shots; brute: explicit Minkowski difference")
      ->check(CLI::IsMember({"exact", "shallow", "approx", "brute"}))
      ->capture_default_str();
  sub->add_option("--delta", options->delta,
                  "accuracy of approx / shallow: default " + formatNumber(defaults::kApproxPdDelta) + " / " +
                      formatNumber(defaults::kShallowPdDelta) + ", range " + deltaRange(PenetrationMethod::kApprox) +
                      " / " + deltaRange(PenetrationMethod::kShallow) + " (exact, brute: ignored)")
      ->option_text("D");
  sub->add_option("--input", options->input, "read pairs from FILE (default or -: standard input)")
      ->option_text("FILE");
  sub->add_option("--output", options->output, "write answers to FILE (default or -: standard output)")
      ->option_text("FILE");
  sub->callback([options, sub] {
    options->delta_given = sub->count("--delta") > 0;
    runPd(*options);
  });
}

}  // namespace mddual::cli
