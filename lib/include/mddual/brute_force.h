// Brute-force reference answers: build M = A - B explicitly (the convex hull
// of all m x n vertex differences, with qhull) and clip the query line with
// every face plane. O(mn log mn): slow, simple, and independent of MDD-DUAL's
// search, so tests and the CLI (--method brute) can check any answer.
#pragma once

#include <utility>
#include <vector>

#include "mddual/polytope.h"
#include "mddual/query.h"

namespace mddual {

/// M = A - B in the world frame, with the pair of vertices behind each vertex.
struct MinkowskiDifference {
  ConvexPolytope polytope;                  ///< M, frame W
  std::vector<std::pair<int, int>> source;  ///< vertex k of M = a(source[k].first) - b(source[k].second)
  /// Builds M from posed A and B (InvalidInputError on bad input).
  static MinkowskiDifference build(const ConvexPolytope& a, const Eigen::Isometry3d& X_WA, const ConvexPolytope& b,
                                   const Eigen::Isometry3d& X_WB);
};

/// Same contract as mdd(); SearchStats stay zero. Both ends t_lo and t_hi are
/// always filled when the line meets M.
MddResult bruteForceMdd(const DirectionalInput& input);
/// Same contract as toi().
ToiResult bruteForceToi(const DirectionalInput& input);
/// Same contract as intersect().
IntersectResult bruteForceIntersect(const IntersectInput& input);

}  // namespace mddual
