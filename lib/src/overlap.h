// Cheap certificates that the origin lies in M (A and B overlap) or outside
// it, used before a ray search whose only job would be to prove it: a
// tetrahedron of points of M that contains the origin, or a separating
// support plane. The MDD-DUAL search stays the exact fallback.
#pragma once

#include <Eigen/Core>

#include "pair.h"

namespace mddual::detail {

/// The origin's depth in the tetrahedron (p0, p1, p2, p3): its smallest
/// distance to the four face planes, positive inside. -infinity when the
/// tetrahedron is flat.
double originDepthInTetrahedron(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                                const Eigen::Vector3d& p3);

struct OverlapTest {
  enum class Kind { kOverlap, kSeparated, kUnknown };
  Kind kind = Kind::kUnknown;
  /// kSeparated: unit n with h_M(n) < -tol (a separating plane, from A toward B).
  Eigen::Vector3d n_A = Eigen::Vector3d::Zero();
};

/// Minkowski portal refinement from the interior point v0 of M along the ray
/// through the origin (a few supports of M). kOverlap when the origin lies in
/// a tetrahedron of points of M deeper than `min_depth`; kSeparated when a
/// support value proves a separating plane; kUnknown when neither shows up
/// within a few steps (near contact): the caller then runs the exact search.
OverlapTest portalOverlapTest(const PairGeometry& pair, const Eigen::Vector3d& v0, double min_depth, WarmStart* warm,
                              SearchStats* stats);

/// Two triangles (three vertices each): the separating-axis theorem on their
/// two normals and nine edge-pair directions. kSeparated when an axis shows a
/// gap larger than twice `tol` (so that the exact search, which calls gaps up
/// to tol touching, would agree), with its unit direction from A toward B;
/// kUnknown otherwise (overlap, touching, coplanar triangles, degenerate
/// axes): the caller runs the exact test.
OverlapTest trianglesSeparated(const PairGeometry& pair, double tol);

}  // namespace mddual::detail
