// The planar Minkowski difference used for grazing lines and flat M, on
// closed-form cases.
#include <gtest/gtest.h>

#include "planar.h"

namespace mddual::detail {
namespace {

using V = Eigen::Vector3d;

TEST(Planar, SquareMinusSquareSlice) {
  // A = unit square [0,1]^2, B = square [0,2]^2 at z = 0: M = [-2, 1]^2.
  const std::vector<V> a{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<V> b{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  const PlanarDifference m(a, b, V::UnitZ());
  const PlanarSlice s = m.slice(V(0, 0.5, 0), V::UnitX(), 1e-12);
  ASSERT_TRUE(s.hit);
  EXPECT_NEAR(s.s_lo, -2.0, 1e-15);
  EXPECT_NEAR(s.s_hi, 1.0, 1e-15);
  EXPECT_TRUE(s.normal_lo.isApprox(V(-1, 0, 0)));
  EXPECT_TRUE(s.normal_hi.isApprox(V(1, 0, 0)));
  // The point of A at the +x end is on A's right edge (x = 1).
  EXPECT_NEAR(s.a_hi.x(), 1.0, 1e-15);
  // A line missing M, and one along its edge (within tolerance).
  EXPECT_FALSE(m.slice(V(0, 1.5, 0), V::UnitX(), 1e-12).hit);
  const PlanarSlice edge = m.slice(V(0, 1.0, 0), V::UnitX(), 1e-12);
  ASSERT_TRUE(edge.hit);
  EXPECT_NEAR(edge.s_lo, -2.0, 1e-15);
  EXPECT_NEAR(edge.s_hi, 1.0, 1e-15);
}

TEST(Planar, OutsideDistance) {
  const std::vector<V> a{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<V> b{{0, 0, 0}};
  const PlanarDifference m(a, b, V::UnitZ());
  V n;
  EXPECT_NEAR(m.outsideDistance(V(3, 0.5, 0), &n), 2.0, 1e-15);
  EXPECT_TRUE(n.isApprox(V(1, 0, 0)));
  EXPECT_NEAR(m.outsideDistance(V(0.5, 0.25, 0), &n), -0.25, 1e-15);
}

TEST(Planar, DegeneratePointAndSegment) {
  // Vertex minus vertex: a single point.
  const PlanarDifference point({V(1, 2, 0)}, {V(0, 0, 0)}, V::UnitZ());
  const PlanarSlice on = point.slice(V(0, 2, 0), V::UnitX(), 1e-12);
  ASSERT_TRUE(on.hit);
  EXPECT_NEAR(on.s_lo, 1.0, 1e-15);
  EXPECT_NEAR(on.s_hi, 1.0, 1e-15);
  EXPECT_FALSE(point.slice(V(0, 2.1, 0), V::UnitX(), 1e-12).hit);
  // Parallel edges: a segment along the line.
  const PlanarDifference seg({V(0, 0, 0), V(1, 0, 0)}, {V(0, 0, 0), V(2, 0, 0)}, V::UnitZ());
  const PlanarSlice along = seg.slice(V(0, 0, 0), V::UnitX(), 1e-12);
  ASSERT_TRUE(along.hit);
  EXPECT_NEAR(along.s_lo, -2.0, 1e-15);
  EXPECT_NEAR(along.s_hi, 1.0, 1e-15);
  // Crossing the segment transversally: a single point.
  const PlanarSlice across = seg.slice(V(0.5, -3, 0), V::UnitY(), 1e-12);
  ASSERT_TRUE(across.hit);
  EXPECT_NEAR(across.s_lo, 3.0, 1e-15);
  EXPECT_NEAR(across.s_hi, 3.0, 1e-15);
}

TEST(Planar, PointOfADecomposesInsideAndClampsOutside) {
  // A = unit square, B = the point (0.25, 0.25): M = A - b. Inside, a - b is
  // x itself, so a = x + b.
  const std::vector<V> a{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const PlanarDifference m(a, {V(0.25, 0.25, 0)}, V::UnitZ());
  double outside = -1.0;
  V p = m.pointOfA(V(0.5, 0.25, 0), &outside);
  EXPECT_EQ(outside, 0.0);
  EXPECT_NEAR((p - V(0.75, 0.5, 0)).norm(), 0.0, 1e-15);
  // On a diagonal of the fan and on the boundary.
  p = m.pointOfA(V(0.25, 0.25, 0), &outside);
  EXPECT_EQ(outside, 0.0);
  EXPECT_NEAR((p - V(0.5, 0.5, 0)).norm(), 0.0, 1e-15);
  p = m.pointOfA(V(0.75, -0.25, 0), &outside);
  EXPECT_NEAR(outside, 0.0, 1e-15);
  EXPECT_NEAR((p - V(1, 0, 0)).norm(), 0.0, 1e-15);
  // Outside: the nearest point of M (x = (1, 0.25) is 0.25 beyond the edge
  // x = 0.75 of M), and a is the point of A behind it.
  p = m.pointOfA(V(1, 0.25, 0), &outside);
  EXPECT_NEAR(outside, 0.25, 1e-15);
  EXPECT_NEAR((p - V(1, 0.5, 0)).norm(), 0.0, 1e-15);
  // Degenerate polygons: a point and a segment (parallel edges).
  const PlanarDifference point({V(1, 2, 0)}, {V(0, 0, 0)}, V::UnitZ());
  p = point.pointOfA(V(1, 2, 0), &outside);
  EXPECT_EQ(outside, 0.0);
  EXPECT_EQ(p, V(1, 2, 0));
  const PlanarDifference seg({V(0, 0, 0), V(1, 0, 0)}, {V(0, 0, 0), V(2, 0, 0)}, V::UnitZ());
  p = seg.pointOfA(V(-0.5, 0, 0), &outside);
  EXPECT_NEAR(outside, 0.0, 1e-15);
  EXPECT_GE(p.x(), 0.0);  // a in A, b = a - x in B
  EXPECT_LE(p.x(), 1.0);
  EXPECT_GE(p.x() + 0.5, 0.0);
  EXPECT_LE(p.x() + 0.5, 2.0);
  p = seg.pointOfA(V(0.5, 0.5, 0), &outside);
  EXPECT_NEAR(outside, 0.5, 1e-15);
  EXPECT_NEAR(p.y(), 0.0, 1e-15);
}

}  // namespace
}  // namespace mddual::detail
