// JSON writers and the --method parser shared by `mddual pd` and `mddual
// width` (header-only; the generic plumbing is in jsonl.h).
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "jsonl.h"
#include "mddual/defaults.h"
#include "mddual/penetration.h"

namespace mddual::cli {

/// "exact" | "shallow" | "approx" | "brute" (CLI11 has checked the name).
inline PenetrationMethod methodFromName(const std::string& name) {
  if (name == "shallow") return PenetrationMethod::kShallow;
  if (name == "approx") return PenetrationMethod::kApprox;
  if (name == "brute") return PenetrationMethod::kBruteForce;
  return PenetrationMethod::kExact;
}

/// The shallow method runs the approximation with delta / 4 first
/// (penetration.h), which must itself be at least defaults::kMinPdDelta: the
/// smallest --delta shallow accepts is kMinPdDelta / kShallowDeltaShare.
inline constexpr double kShallowDeltaShare = 0.25;

/// x with %g.
inline std::string formatNumber(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

/// "[lo, hi]": the --delta range of `method` (see deltaOption).
inline std::string deltaRange(PenetrationMethod method) {
  const double lo =
      method == PenetrationMethod::kShallow ? defaults::kMinPdDelta / kShallowDeltaShare : defaults::kMinPdDelta;
  return "[" + formatNumber(lo) + ", " + formatNumber(defaults::kMaxPdDelta) + "]";
}

/// The --delta value a method runs with: 0 (the library's default) when the
/// option is absent, else `text` as a number within the method's range
/// (approx: [kMinPdDelta, kMaxPdDelta]; shallow: [kMinPdDelta / 0.25,
/// kMaxPdDelta]; exact and brute ignore delta, but it must still be a number
/// in [kMinPdDelta, kMaxPdDelta]). Throws CLI::ValidationError naming
/// --delta, the value as given and the range.
inline double deltaOption(const std::string& text, bool given, PenetrationMethod method,
                          const std::string& method_name) {
  if (!given) return 0.0;
  const std::string shown = "'" + clipForMessage(text) + "'";
  char* end = nullptr;
  const double delta = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(delta)) {
    throw CLI::ValidationError("--delta", shown + " is not a finite number");
  }
  const double lo =
      method == PenetrationMethod::kShallow ? defaults::kMinPdDelta / kShallowDeltaShare : defaults::kMinPdDelta;
  if (!(delta >= lo && delta <= defaults::kMaxPdDelta)) {
    std::string why;
    if (method == PenetrationMethod::kShallow) why = " (shallow first approximates with delta / 4)";
    throw CLI::ValidationError(
        "--delta", shown + " is outside " + deltaRange(method) + ", the range of --method " + method_name + why);
  }
  return delta;
}

/// {"kind": "fv"|"vf"|"ee"|"none", "a": index, "b": index}, indices as in FaceOfM.
inline Json toJson(const FaceOfM& facet) {
  const char* kind = "none";
  if (facet.kind == FaceOfM::Kind::kFV) kind = "fv";
  if (facet.kind == FaceOfM::Kind::kVF) kind = "vf";
  if (facet.kind == FaceOfM::Kind::kEE) kind = "ee";
  return Json{{"kind", kind}, {"a", facet.a}, {"b", facet.b}};
}

/// The PenetrationStats fields by name, the ray searches' SearchStats under "search".
inline Json toJson(const PenetrationStats& s) {
  return Json{{"fv_facets", s.fv_facets},
              {"vf_facets", s.vf_facets},
              {"ee_facets", s.ee_facets},
              {"arc_pairs", s.arc_pairs},
              {"walk_steps", s.walk_steps},
              {"walk_fallbacks", s.walk_fallbacks},
              {"brute_fallbacks", s.brute_fallbacks},
              {"pruned", s.pruned},
              {"support_vertices", s.support_vertices},
              {"grid_directions", s.grid_directions},
              {"rays", s.rays},
              {"shallow_directions", s.shallow_directions},
              {"shallow_facets", s.shallow_facets},
              {"search", toJson(s.search)}};
}

}  // namespace mddual::cli
