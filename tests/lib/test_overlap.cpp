// lib/src/overlap.cpp: the triangle pair's separating-axis certificate
// (trianglesSeparated) against the brute-force reference, and intersect() on
// triangle pairs, which uses it first.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>

#include "mddual/brute_force.h"
#include "mddual/generators.h"
#include "mddual/query.h"
#include "overlap.h"
#include "pair.h"
#include "query_oracle.h"

namespace mddual {
namespace {

using generators::Points;
using generators::Rng;

double uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

Eigen::Vector3d randomPoint(Rng& rng, double r) {
  return generators::drawVector(std::uniform_real_distribution<double>(-r, r), rng);
}

/// A triangle of random points in [-r, r]^3, the last vertex drawn first: the
/// order GCC evaluated triangle()'s arguments when they were drawn in the call
/// (C++ leaves it unspecified), kept so the seeded triangles stay as they were.
Points randomTriangle(Rng& rng, double r) {
  const Eigen::Vector3d v2 = randomPoint(rng, r);
  const Eigen::Vector3d v1 = randomPoint(rng, r);
  const Eigen::Vector3d v0 = randomPoint(rng, r);
  return generators::triangle(v0, v1, v2);
}

Eigen::Isometry3d randomPose(Rng& rng, double r) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = generators::randomRotation(rng);
  X.translation() = randomPoint(rng, r);
  return X;
}

TEST(Overlap, TrianglesSeparatedOnlyWhereTheBruteForceSeparates) {
  Rng rng(11);
  int separated = 0, certified = 0, overlapping = 0, touching = 0;
  for (int q = 0; q < 3000; ++q) {
    const Points ta = randomTriangle(rng, 1);
    Points tb = randomTriangle(rng, 1);
    const ConvexPolytope a = ConvexPolytope::fromPoints(ta);
    const Eigen::Isometry3d X_WA = randomPose(rng, 0.5);
    Eigen::Isometry3d X_WB = randomPose(rng, 0.6);
    if (q % 5 == 0) {
      // Touching: B's vertex 0 placed on A's plane, inside A (a barycentric
      // combination), B on one side of the plane.
      const Eigen::Vector3d n_A = (ta[1] - ta[0]).cross(ta[2] - ta[0]).normalized();
      const double w0 = uniform(rng, 0.1, 0.8), w1 = uniform(rng, 0.1, 1.0 - w0 - 0.05);
      const Eigen::Vector3d p_A = w0 * ta[0] + w1 * ta[1] + (1.0 - w0 - w1) * ta[2];
      // The last vertex first, as GCC evaluated triangle()'s arguments.
      const Eigen::Vector3d v2 = p_A + n_A + randomPoint(rng, 0.5);
      const Eigen::Vector3d v1 = p_A + n_A + randomPoint(rng, 0.5).cross(n_A);
      tb = generators::triangle(p_A, v1, v2);
      X_WB = X_WA;  // B's points are given in A's body frame
    }
    const ConvexPolytope b = ConvexPolytope::fromPoints(tb);
    ASSERT_EQ(a.numVertices(), 3);
    if (b.numVertices() != 3) continue;  // the touching construction can fold into a segment: not this test's case
    const IntersectInput in{&a, X_WA, &b, X_WB};
    const IntersectResult reference = bruteForceIntersect(in);
    const detail::PairGeometry pair(&a, X_WA, &b, X_WB, "test");
    const detail::OverlapTest sat = detail::trianglesSeparated(pair, pair.touchTolerance());
    if (sat.kind == detail::OverlapTest::Kind::kSeparated) {
      ++certified;
      EXPECT_FALSE(reference.intersecting) << testing::describeFrames(a, X_WA, b, X_WB);
      // The certificate is a proof: A below and B above the plane along n.
      const Eigen::Vector3d n_W = pair.vectorToWorld(sat.n_A);
      double hi_a = -1e300, lo_b = 1e300;
      for (int v = 0; v < 3; ++v) {
        hi_a = std::max(hi_a, n_W.dot(X_WA * a.vertex(v)));
        lo_b = std::min(lo_b, n_W.dot(X_WB * b.vertex(v)));
      }
      EXPECT_GT(lo_b - hi_a, pair.touchTolerance()) << testing::describeFrames(a, X_WA, b, X_WB);
    }
    const IntersectResult r = intersect(in);
    EXPECT_EQ(r.intersecting, reference.intersecting) << testing::describeFrames(a, X_WA, b, X_WB);
    if (!reference.intersecting) ++separated;
    if (reference.status == IntersectStatus::kPenetrating) ++overlapping;
    if (reference.status == IntersectStatus::kTouching) ++touching;
  }
  std::printf("separated %d (certified %d), penetrating %d, touching %d\n", separated, certified, overlapping,
              touching);
  // Guards: every outcome occurs, and the certificate settles most separated pairs.
  EXPECT_GT(overlapping, 300);
  EXPECT_GT(touching, 300);
  EXPECT_GT(separated, 900);
  EXPECT_GT(certified, separated * 8 / 10);
}

TEST(Overlap, CoplanarTrianglesAreLeftToTheExactTest) {
  // Same plane, disjoint in it: every one of the 11 axes sees overlapping
  // projections (the normals are parallel, the edge pairs' directions are the
  // normal), so the certificate must say "unknown" and the exact test decides.
  const ConvexPolytope a = ConvexPolytope::fromPoints(generators::triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
  const ConvexPolytope b = ConvexPolytope::fromPoints(generators::triangle({2, 2, 0}, {3, 2, 0}, {2, 3, 0}));
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  const detail::PairGeometry pair(&a, I, &b, I, "test");
  EXPECT_EQ(detail::trianglesSeparated(pair, pair.touchTolerance()).kind, detail::OverlapTest::Kind::kUnknown);
  const IntersectResult r = intersect(IntersectInput{&a, I, &b, I});
  EXPECT_FALSE(r.intersecting);
  // Lifted by a gap just above and just below twice the tolerance: the
  // certificate answers only above it.
  const double tol = pair.touchTolerance();
  for (const double gap : {3.0 * tol, 1.5 * tol}) {
    Eigen::Isometry3d up = I;
    up.translation().z() = gap;
    const ConvexPolytope c = ConvexPolytope::fromPoints(generators::triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
    const detail::PairGeometry lifted(&a, I, &c, up, "test");
    const detail::OverlapTest sat = detail::trianglesSeparated(lifted, lifted.touchTolerance());
    EXPECT_EQ(sat.kind == detail::OverlapTest::Kind::kSeparated, gap > 2.0 * lifted.touchTolerance()) << gap;
  }
}

}  // namespace
}  // namespace mddual
