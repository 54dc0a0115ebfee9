// Thin RAII wrapper around qhull's reentrant C API (libqhull_r), the only place
// in mddual that talks to qhull.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace mddual::detail {

/// One facet of a 3D hull: plane normal . x = offset (unit outward normal) and
/// its vertices as indices into the input points, counter-clockwise seen from
/// outside.
struct HullFacet {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double offset = 0.0;
  std::vector<int> vertices;
};

/// Convex hull of 3D points. qhull merges coplanar facets while it builds the
/// hull (which keeps the topology valid): facets whose centrums lie within
/// `premerge` of a neighbour's plane (world units), or within qhull's own
/// round-off estimate when `premerge` is 0 ("C-0"). `what` names the caller's
/// object for error messages. Throws HullError with qhull's own message when
/// qhull fails (e.g. on a flat set).
std::vector<HullFacet> hull3d(const std::vector<Eigen::Vector3d>& points, const std::string& what,
                              double premerge = 0.0);

/// Vertices of the 2D convex hull of points, counter-clockwise, as indices into
/// points (collinear boundary points dropped). Throws HullError on failure.
std::vector<int> hull2d(const std::vector<Eigen::Vector2d>& points, const std::string& what);

}  // namespace mddual::detail
