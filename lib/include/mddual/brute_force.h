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

/// The reference for one posed pair: builds M once, then answers any number
/// of directional queries and the intersection test on it.
class BruteForce {
 public:
  /// Validates like the fast queries (InvalidInputError on bad input).
  BruteForce(const ConvexPolytope* a, const Eigen::Isometry3d& X_WA, const ConvexPolytope* b,
             const Eigen::Isometry3d& X_WB);

  /// Same contract as mdd() except: SearchStats stay zero, both ends t_lo and
  /// t_hi are always filled when the line meets M, and the contact's features
  /// are kNone (M is built without them).
  MddResult mdd(const Eigen::Vector3d& s_W) const;
  /// Same contract as toi().
  ToiResult toi(const Eigen::Vector3d& s_W, double max_distance = std::numeric_limits<double>::infinity()) const;
  /// Same contract as intersect().
  IntersectResult intersect() const;

  const MinkowskiDifference& minkowskiDifference() const { return md_; }
  double touchTolerance() const { return tol_; }

 private:
  struct Line;
  Line solve(const Eigen::Vector3d& s_W, const char* query) const;

  std::vector<Eigen::Vector3d> a_W_;
  MinkowskiDifference md_;
  double tol_ = 0.0;
};

/// One-shot wrappers: build the reference for input's pair and answer.
MddResult bruteForceMdd(const DirectionalInput& input);
ToiResult bruteForceToi(const DirectionalInput& input);
IntersectResult bruteForceIntersect(const IntersectInput& input);

}  // namespace mddual
