// JSON writers and the --method parser shared by `mddual pd` and `mddual
// width` (header-only; the generic plumbing is in jsonl.h).
#pragma once

#include <string>

#include "jsonl.h"
#include "mddual/penetration.h"

namespace mddual::cli {

/// "exact" | "shallow" | "approx" | "brute" (CLI11 has checked the name).
inline PenetrationMethod methodFromName(const std::string& name) {
  if (name == "shallow") return PenetrationMethod::kShallow;
  if (name == "approx") return PenetrationMethod::kApprox;
  if (name == "brute") return PenetrationMethod::kBruteForce;
  return PenetrationMethod::kExact;
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
