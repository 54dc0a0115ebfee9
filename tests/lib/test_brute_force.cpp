// The brute-force reference itself, on closed forms (so the randomized tests'
// oracle is checked independently of MDD-DUAL).
#include <gtest/gtest.h>

#include "mddual/brute_force.h"
#include "mddual/generators.h"

namespace mddual {
namespace {

Eigen::Isometry3d at(double x, double y, double z) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(x, y, z);
  return X;
}

TEST(BruteForce, MinkowskiDifferenceOfCubesIsABox) {
  const ConvexPolytope cube = ConvexPolytope::fromPoints(generators::box({0.5, 0.5, 0.5}));
  const MinkowskiDifference md = MinkowskiDifference::build(cube, at(0, 0, 0), cube, at(-3, 0, 0));
  EXPECT_EQ(md.polytope.numVertices(), 8);
  EXPECT_EQ(md.polytope.numFaces(), 6);
  for (int k = 0; k < md.polytope.numVertices(); ++k) {
    const auto [i, j] = md.source[k];
    EXPECT_EQ(md.polytope.vertex(k), cube.vertex(i) - (cube.vertex(j) + Eigen::Vector3d(-3, 0, 0)));
  }
}

TEST(BruteForce, ClosedFormCubeAnswers) {
  const ConvexPolytope cube = ConvexPolytope::fromPoints(generators::box({0.5, 0.5, 0.5}));
  const BruteForce separated(&cube, at(0, 0, 0), &cube, at(-3, 0, 0));
  const MddResult r = separated.mdd({1, 0, 0});
  EXPECT_EQ(r.status, ContactStatus::kSeparated);
  EXPECT_NEAR(r.t_lo, 2.0, 1e-12);
  EXPECT_NEAR(r.t_hi, 4.0, 1e-12);
  EXPECT_EQ(separated.toi({1, 0, 0}).status, ToiStatus::kHit);
  EXPECT_EQ(separated.toi({-1, 0, 0}).status, ToiStatus::kNever);
  EXPECT_EQ(separated.mdd({0, 0, 1}).status, ContactStatus::kNoContact);
  EXPECT_EQ(separated.intersect().status, IntersectStatus::kSeparated);

  const BruteForce overlapping(&cube, at(0, 0, 0), &cube, at(-0.5, 0.25, 0));
  const MddResult p = overlapping.mdd({0, 1, 0});
  EXPECT_EQ(p.status, ContactStatus::kPenetrating);
  EXPECT_NEAR(p.distance, -0.75, 1e-12);
  EXPECT_EQ(overlapping.intersect().status, IntersectStatus::kPenetrating);

  const BruteForce touching(&cube, at(0, 0, 0), &cube, at(1, 1, 0.2));  // edge to edge
  EXPECT_EQ(touching.intersect().status, IntersectStatus::kTouching);
  EXPECT_EQ(touching.mdd({1, 0, 0}).status, ContactStatus::kTouching);
}

TEST(BruteForce, FlatMinkowskiDifferenceUsesEdgePlanes) {
  // Two coplanar triangles: M is a hexagon in z = 0; a line crossing the plane
  // outside it must miss even though it meets both face planes.
  const ConvexPolytope tri = ConvexPolytope::fromPoints({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const BruteForce apart(&tri, at(0, 0, 0), &tri, at(5, 5, 0));
  EXPECT_TRUE(apart.minkowskiDifference().polytope.isFlat());
  EXPECT_EQ(apart.mdd({0, 0, 1}).status, ContactStatus::kNoContact);
  EXPECT_EQ(apart.intersect().status, IntersectStatus::kSeparated);
  const MddResult slide = apart.mdd({1, 1, 0});
  EXPECT_EQ(slide.status, ContactStatus::kSeparated);
  // B slides back along (1,1)/sqrt2 until its corner (5,5) meets A's
  // hypotenuse x + y = 1 at (0.5, 0.5): a distance of 4.5 * sqrt2.
  EXPECT_NEAR(slide.distance, 4.5 * std::sqrt(2.0), 1e-12);
}

}  // namespace
}  // namespace mddual
