// Planar pieces of M: when the query line lies in a supporting plane of M
// (a grazing line), or when A and B are parallel flat polygons (M is flat),
// what matters is a convex polygon in one plane: conv{a_i - b_j} for the
// vertices of A and B on that plane. This module builds that polygon and
// answers the two questions the queries ask of it: where a line in the plane
// enters and leaves it (with the points of A and B that meet there), and how
// far a point of the plane lies outside it.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace mddual::detail {

/// The part of a line {o + s d} inside the polygon: s in [s_lo, s_hi].
struct PlanarSlice {
  bool hit = false;
  double s_lo = 0.0;
  double s_hi = 0.0;
  /// At each end, a point of A (the caller's frame) that B meets there, and
  /// the unit outward normal (in the plane) of the polygon edge at that end.
  Eigen::Vector3d a_lo = Eigen::Vector3d::Zero();
  Eigen::Vector3d a_hi = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal_lo = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal_hi = Eigen::Vector3d::Zero();
};

class PlanarDifference {
 public:
  /// pa, pb: points of A and of B lying (within tolerance) in one plane with
  /// unit normal `normal`. Builds the 2D convex hull of all differences.
  PlanarDifference(const std::vector<Eigen::Vector3d>& pa, const std::vector<Eigen::Vector3d>& pb,
                   const Eigen::Vector3d& normal);

  /// Intersection with the line {o + s d}, d a unit vector in the plane; a
  /// hull vertex within `tol` of the line counts as on it.
  PlanarSlice slice(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double tol) const;

  /// Signed distance from the in-plane projection of x to the polygon's
  /// boundary lines, maximised over edges (> 0: outside), with that edge's
  /// outward unit normal. A degenerate polygon (point or segment) counts its
  /// extent along its own line too.
  double outsideDistance(const Eigen::Vector3d& x, Eigen::Vector3d* edge_normal) const;

  /// Decomposes the in-plane projection of x as a - b over the polygon: a
  /// and b are convex combinations of the points of A and of B given, and
  /// a - b is x's projection when that lies in the polygon, else the
  /// polygon's point nearest to it. Returns a; *outside is how far x's
  /// projection lies outside the polygon (0 inside).
  Eigen::Vector3d pointOfA(const Eigen::Vector3d& x, double* outside) const;

 private:
  struct Vertex {
    Eigen::Vector2d q;  // in-plane coordinates
    int i;              // index into pa
    int j;              // index into pb
  };
  Eigen::Vector2d toPlane(const Eigen::Vector3d& x) const { return {x.dot(e1_), x.dot(e2_)}; }
  Eigen::Vector3d fromPlane(const Eigen::Vector2d& v) const { return v.x() * e1_ + v.y() * e2_; }
  Eigen::Vector2d edgeNormal(int k) const;

  std::vector<Eigen::Vector3d> pa_;
  Eigen::Vector3d e1_;
  Eigen::Vector3d e2_;
  std::vector<Vertex> hull_;  // counter-clockwise
};

}  // namespace mddual::detail
