// Shared by the hierarchy's construction (bvh_build.cpp) and its volume
// tests and traversals (bvh.cpp): the volumes' padding and the magnitude of
// a node's coordinates, which scales the slack of the tests on it.
#pragma once

#include <Eigen/Core>
#include <algorithm>

#include "mddual/bvh.h"

namespace mddual::detail {

/// Volumes are grown by this fraction of their coordinates' magnitude so that
/// round-off in fitting them never leaves a point (or a child's volume)
/// outside. Dimensionless; far below any tolerance of the queries (1e-10).
inline constexpr double kPadRel = 1e-13;

/// A bound on the coordinates' absolute values of a box (or a point set)
/// about c with half extents h.
inline double magnitude(const Eigen::Vector3d& c, const Eigen::Vector3d& h) {
  return c.cwiseAbs().maxCoeff() + h.sum();
}

/// The magnitude of a node's coordinates (its volumes'), which scales the
/// slack of the tests on it.
inline double nodeScale(const Obb& obb, const Eigen::Vector3d& centre, double radius) {
  return std::max(magnitude(obb.centre_F, obb.half), centre.cwiseAbs().maxCoeff() + radius);
}

}  // namespace mddual::detail
