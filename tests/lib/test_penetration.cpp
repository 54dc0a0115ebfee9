// penetrationDepth(), width() and polyhedralPenetrationDepth() on inputs with
// known answers (hand-computed placements, closed-form widths), the
// polyhedral metric against its brute force, the facet counts of the exact
// method against the explicit M, the output-sensitivity of its Gaussian-map
// walk, the direction grid's covering angle, and the errors.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mddual/brute_force.h"
#include "mddual/constants.h"
#include "mddual/defaults.h"
#include "mddual/error.h"
#include "mddual/generators.h"
#include "mddual/penetration.h"
#include "pair.h"
#include "penetration_internal.h"
#include "test_shapes.h"

namespace mddual {
namespace {

using generators::Points;
using generators::Rng;

constexpr double kTol = 1e-9;
const PenetrationMethod kAllMethods[] = {PenetrationMethod::kExact, PenetrationMethod::kShallow,
                                         PenetrationMethod::kApprox, PenetrationMethod::kBruteForce};

Eigen::Isometry3d pose(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}

Eigen::Isometry3d at(const Eigen::Vector3d& p) {
  return pose(Eigen::Matrix3d::Identity(), p);
}

/// A random rotation, placed `radius` from the origin in a random direction.
/// The offset is drawn first: the order GCC evaluated pose()'s arguments when
/// both were drawn in the call (C++ leaves it unspecified), kept so seeded
/// poses stay as they were.
Eigen::Isometry3d randomPoseAt(Rng& rng, double radius) {
  const Eigen::Vector3d p = radius * generators::randomUnitVector(rng);
  const Eigen::Matrix3d R = generators::randomRotation(rng);
  return pose(R, p);
}

/// Axis-aligned box [lo, hi].
Points boxFromTo(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  Points out;
  for (int i = 0; i < 8; ++i) {
    out.emplace_back((i & 1) != 0 ? hi.x() : lo.x(), (i & 2) != 0 ? hi.y() : lo.y(), (i & 4) != 0 ? hi.z() : lo.z());
  }
  return out;
}

PenetrationResult pd(const ConvexPolytope& a, const Eigen::Isometry3d& X_WA, const ConvexPolytope& b,
                     const Eigen::Isometry3d& X_WB, PenetrationMethod method, double delta = 0.0) {
  PenetrationInput in{&a, X_WA, &b, X_WB, method, delta};
  return penetrationDepth(in);
}

// ---- Hand-computed placements -------------------------------------------------------

TEST(Penetration, OverlappingCubesMoveAlongTheShallowAxis) {
  // A = [0,1]^3, B = [0.7,1.7] x [0.2,1.2] x [0,1]: the overlap is 0.3 along
  // x, 0.8 along y, 1 along z; B leaves fastest by moving +x by 0.3.
  const ConvexPolytope a = ConvexPolytope::fromPoints(boxFromTo({0, 0, 0}, {1, 1, 1}));
  const ConvexPolytope b = ConvexPolytope::fromPoints(boxFromTo({0, 0, 0}, {1, 1, 1}));
  for (PenetrationMethod m : kAllMethods) {
    SCOPED_TRACE(toString(m));
    const PenetrationResult r = pd(a, at({0, 0, 0}), b, at({0.7, 0.2, 0.0}), m);
    EXPECT_EQ(r.status, PenetrationStatus::kPenetrating);
    EXPECT_NEAR(r.depth, 0.3, kTol);
    EXPECT_TRUE(r.translation_W.isApprox(Eigen::Vector3d(0.3, 0, 0), kTol)) << r.translation_W.transpose();
    EXPECT_TRUE(r.normal_W.isApprox(Eigen::Vector3d(1, 0, 0), kTol)) << r.normal_W.transpose();
  }
}

TEST(Penetration, TriangleThroughABoxLeavesThroughTheNearFace) {
  // A = [-1,1]^3 fixed; B = a triangle in the plane z = 0.2 that spans the
  // whole cross-section: sliding it sideways out of the box takes far more
  // than lifting it by 0.8 to the top face.
  const ConvexPolytope a = ConvexPolytope::fromPoints(generators::box({1, 1, 1}));
  const ConvexPolytope b = ConvexPolytope::fromPoints(generators::triangle({-5, -4, 0}, {5, -4, 0}, {0, 6, 0}));
  ASSERT_TRUE(b.isFlat());
  for (PenetrationMethod m : kAllMethods) {
    SCOPED_TRACE(toString(m));
    const PenetrationResult r = pd(a, at({0, 0, 0}), b, at({0, 0, 0.2}), m);
    EXPECT_EQ(r.status, PenetrationStatus::kPenetrating);
    EXPECT_NEAR(r.depth, 0.8, kTol);
    EXPECT_TRUE(r.translation_W.isApprox(Eigen::Vector3d(0, 0, 0.8), kTol)) << r.translation_W.transpose();
  }
  // The same with the triangle as A and the box moving: the box moves down.
  for (PenetrationMethod m : kAllMethods) {
    SCOPED_TRACE(toString(m));
    const PenetrationResult r = pd(b, at({0, 0, 0.2}), a, at({0, 0, 0}), m);
    EXPECT_NEAR(r.depth, 0.8, kTol);
    EXPECT_TRUE(r.translation_W.isApprox(Eigen::Vector3d(0, 0, -0.8), kTol)) << r.translation_W.transpose();
  }
}

TEST(Penetration, DisjointAndTouchingPairsHaveDepthZero) {
  const ConvexPolytope cube = ConvexPolytope::fromPoints(boxFromTo({0, 0, 0}, {1, 1, 1}));
  for (PenetrationMethod m : kAllMethods) {
    SCOPED_TRACE(toString(m));
    const PenetrationResult sep = pd(cube, at({0, 0, 0}), cube, at({1.5, 0.2, 0}), m);
    EXPECT_EQ(sep.status, PenetrationStatus::kSeparated);
    EXPECT_EQ(sep.depth, 0.0);
    EXPECT_EQ(sep.translation_W, Eigen::Vector3d::Zero());
    EXPECT_TRUE(sep.normal_W.hasNaN());
    EXPECT_EQ(sep.facet.kind, FaceOfM::Kind::kNone);
    for (const Eigen::Vector3d& p :
         {Eigen::Vector3d(1, 0.3, 0.2), Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(1, 1, 1)}) {
      const PenetrationResult touch = pd(cube, at({0, 0, 0}), cube, at(p), m);
      EXPECT_EQ(touch.status, PenetrationStatus::kTouching) << p.transpose();
      EXPECT_EQ(touch.depth, 0.0);
      EXPECT_EQ(touch.translation_W, Eigen::Vector3d::Zero());
    }
  }
}

TEST(Penetration, ParallelFlatPolygonsHaveNoInteriorToSeparate) {
  // Coplanar overlapping triangles: M is flat; PD is 0 (touching). Parallel
  // triangles in different planes: separated.
  const ConvexPolytope t = ConvexPolytope::fromPoints(generators::triangle({0, 0, 0}, {2, 0, 0}, {0, 2, 0}));
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (PenetrationMethod m : kAllMethods) {
    SCOPED_TRACE(toString(m));
    EXPECT_EQ(pd(t, at({0, 0, 0}), t, pose(turn, {0.3, 0.3, 0}), m).status, PenetrationStatus::kTouching);
    EXPECT_EQ(pd(t, at({0, 0, 0}), t, pose(turn, {0.3, 0.3, 0}), m).depth, 0.0);
    EXPECT_EQ(pd(t, at({0, 0, 0}), t, pose(turn, {0.3, 0.3, 0.5}), m).status, PenetrationStatus::kSeparated);
  }
  // Crossing (non-parallel) triangles: M is a solid and the depth positive.
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const PenetrationResult exact = pd(t, at({0, 0, 0}), t, pose(tilt, {0.2, 0.5, -0.5}), PenetrationMethod::kExact);
  const PenetrationResult brute = pd(t, at({0, 0, 0}), t, pose(tilt, {0.2, 0.5, -0.5}), PenetrationMethod::kBruteForce);
  EXPECT_EQ(exact.status, PenetrationStatus::kPenetrating);
  EXPECT_NEAR(exact.depth, brute.depth, kTol);
}

TEST(Penetration, ResultFieldsAreInTheWorldFrame) {
  // The overlapping cubes, the whole scene rotated and moved far away: the
  // depth is unchanged and the translation turns with the scene.
  const ConvexPolytope cube = ConvexPolytope::fromPoints(boxFromTo({0, 0, 0}, {1, 1, 1}));
  Rng rng(7);
  const Eigen::Matrix3d R = generators::randomRotation(rng);
  const Eigen::Vector3d p(1e3, -2e3, 5e2);
  for (PenetrationMethod m : kAllMethods) {
    SCOPED_TRACE(toString(m));
    const PenetrationResult r = pd(cube, pose(R, p), cube, pose(R, p + R * Eigen::Vector3d(0.7, 0.2, 0.0)), m);
    EXPECT_NEAR(r.depth, 0.3, 1e-9);
    EXPECT_TRUE(r.translation_W.isApprox(R * Eigen::Vector3d(0.3, 0, 0), 1e-9)) << r.translation_W.transpose();
  }
}

TEST(Penetration, ApproximationDeltaIsReportedAndBounded) {
  Rng rng(11);
  const ConvexPolytope a = ConvexPolytope::fromPoints(generators::blob(30, {1, 1.2, 0.8}, rng));
  const ConvexPolytope b = ConvexPolytope::fromPoints(generators::blob(30, {0.7, 1, 1.1}, rng));
  const PenetrationResult exact = pd(a, at({0, 0, 0}), b, at({0.4, 0.3, 0.1}), PenetrationMethod::kExact);
  ASSERT_EQ(exact.status, PenetrationStatus::kPenetrating);
  EXPECT_EQ(exact.delta, 0.0);
  EXPECT_EQ(pd(a, at({0, 0, 0}), b, at({0.4, 0.3, 0.1}), PenetrationMethod::kApprox).delta, defaults::kApproxPdDelta);
  EXPECT_EQ(pd(a, at({0, 0, 0}), b, at({0.4, 0.3, 0.1}), PenetrationMethod::kShallow).delta, defaults::kShallowPdDelta);
  for (double delta : {1e3, 10.0, 2.0, 0.5, 0.1, 0.01, 0.001}) {
    const PenetrationResult r = pd(a, at({0, 0, 0}), b, at({0.4, 0.3, 0.1}), PenetrationMethod::kApprox, delta);
    EXPECT_EQ(r.delta, delta);
    EXPECT_GE(r.depth, exact.depth - kTol) << delta;
    EXPECT_LE(r.depth, (1 + delta) * exact.depth + kTol) << delta;
    EXPECT_EQ(r.stats.rays, static_cast<int>(directionGrid(delta).size()));
    const PenetrationResult s = pd(a, at({0, 0, 0}), b, at({0.4, 0.3, 0.1}), PenetrationMethod::kShallow, delta);
    EXPECT_NEAR(s.depth, exact.depth, kTol) << delta;
  }
}

// ---- The exact method's enumeration ---------------------------------------------------

/// Facets of M by kind, from the vertex pairs behind each facet's vertices.
struct FacetKinds {
  int fv = 0, vf = 0, ee = 0;
};
FacetKinds facetKinds(const MinkowskiDifference& md) {
  FacetKinds k;
  const ConvexPolytope& m = md.polytope;
  for (int f = 0; f < m.numFaces(); ++f) {
    bool one_a = true;
    bool one_b = true;
    const std::pair<int, int> first = md.source[m.faceVertices(f)[0]];
    for (int v : m.faceVertices(f)) {
      one_a = one_a && md.source[v].first == first.first;
      one_b = one_b && md.source[v].second == first.second;
    }
    (one_a ? k.vf : one_b ? k.fv : k.ee)++;
  }
  return k;
}

/// The exact method's enumeration on a posed pair, with or without pruning.
PenetrationStats enumerate(const ConvexPolytope& a, const Eigen::Isometry3d& X_WA, const ConvexPolytope& b,
                           const Eigen::Isometry3d& X_WB, bool prune, double* depth) {
  const detail::PairGeometry pair(&a, X_WA, &b, X_WB, "test");
  PenetrationStats stats;
  *depth = detail::exactClosestFacet(pair, &stats, prune).h;
  return stats;
}

TEST(PenetrationExact, EnumeratesExactlyTheFacetsOfM) {
  // Generic pairs (random blobs): without pruning, every FV, VF and EE facet
  // of M once, and nothing else; with pruning, the same minimum.
  Rng rng(21);
  for (int i = 0; i < 40; ++i) {
    const ConvexPolytope a = ConvexPolytope::fromPoints(generators::blob(5 + i, {1, 1.3, 0.9}, rng));
    const ConvexPolytope b = ConvexPolytope::fromPoints(generators::blob(45 - i, {1.2, 0.8, 1}, rng));
    const Eigen::Isometry3d X_WA = pose(generators::randomRotation(rng), {0, 0, 0});
    const Eigen::Isometry3d X_WB = randomPoseAt(rng, 0.5);
    double all = 0.0;
    double pruned = 0.0;
    const PenetrationStats s = enumerate(a, X_WA, b, X_WB, false, &all);
    const PenetrationStats p = enumerate(a, X_WA, b, X_WB, true, &pruned);
    const FacetKinds k = facetKinds(MinkowskiDifference::build(a, X_WA, b, X_WB));
    EXPECT_EQ(s.fv_facets, k.fv) << i;
    EXPECT_EQ(s.vf_facets, k.vf) << i;
    EXPECT_EQ(s.ee_facets, k.ee) << i;
    EXPECT_EQ(s.walk_fallbacks, 0);
    EXPECT_EQ(s.pruned, 0);
    EXPECT_NEAR(pruned, all, 1e-12) << i;
    EXPECT_LT(p.fv_facets + p.vf_facets + p.ee_facets, k.fv + k.vf + k.ee) << i;
  }
}

TEST(PenetrationExact, GaussianMapWalkIsOutputSensitive) {
  // Two ellipsoids of 3000 vertices (~9000 edges each): the walk tests
  // (edges of A + EE facets) x (degree of B) arc pairs, not 81 million; the
  // lower bounds then leave a small fraction of that to do.
  const ConvexPolytope a = ConvexPolytope::fromPoints(generators::ellipsoid(3000));
  const ConvexPolytope b = ConvexPolytope::fromPoints(generators::ellipsoid(3000));
  Rng rng(5);
  const Eigen::Isometry3d X_WA = pose(generators::randomRotation(rng), {0, 0, 0});
  const Eigen::Isometry3d X_WB = pose(generators::randomRotation(rng), {0.5, 0.2, -0.3});
  double all = 0.0;
  double pruned = 0.0;
  const PenetrationStats s = enumerate(a, X_WA, b, X_WB, false, &all);
  const PenetrationStats p = enumerate(a, X_WA, b, X_WB, true, &pruned);
  const double all_pairs = static_cast<double>(a.numEdges()) * b.numEdges();
  std::printf(
      "[ walk     ] %d x %d edges: %lld arc pairs tested (%.4f%% of all pairs), %d EE facets, %d steps; "
      "pruned: %lld arc pairs, %d of %d candidates skipped\n",
      a.numEdges(), b.numEdges(), s.arc_pairs, 100.0 * static_cast<double>(s.arc_pairs) / all_pairs, s.ee_facets,
      s.walk_steps, p.arc_pairs, p.pruned, a.numFaces() + b.numFaces() + a.numEdges());
  EXPECT_LT(static_cast<double>(s.arc_pairs), 5e-3 * all_pairs);
  EXPECT_LE(s.arc_pairs, 20LL * (a.numEdges() + s.ee_facets));
  EXPECT_EQ(s.walk_fallbacks, 0);
  EXPECT_EQ(s.fv_facets, a.numFaces());
  EXPECT_EQ(s.vf_facets, b.numFaces());
  EXPECT_NEAR(pruned, all, 1e-12);
  EXPECT_LT(p.arc_pairs, s.arc_pairs / 4);
}

TEST(PenetrationExact, LargeEllipsoidsAgreeWithTheBruteForce) {
  const ConvexPolytope a = ConvexPolytope::fromPoints(generators::ellipsoid(300));
  Rng rng(9);
  const ConvexPolytope b = ConvexPolytope::fromPoints(generators::roundedCubeRandom(200, rng));
  int penetrating = 0;  // the depths compared are the point: every sample must penetrate
  for (int i = 0; i < 3; ++i) {
    const Eigen::Isometry3d X_WA = pose(generators::randomRotation(rng), {0, 0, 0});
    const Eigen::Isometry3d X_WB = randomPoseAt(rng, 2.0);
    const PenetrationResult brute = pd(a, X_WA, b, X_WB, PenetrationMethod::kBruteForce);
    penetrating += brute.status == PenetrationStatus::kPenetrating ? 1 : 0;
    for (PenetrationMethod m : {PenetrationMethod::kExact, PenetrationMethod::kShallow}) {
      const PenetrationResult r = pd(a, X_WA, b, X_WB, m);
      EXPECT_EQ(r.status, brute.status);
      EXPECT_NEAR(r.depth, brute.depth, 1e-9 * 10) << toString(m);
      // The exact method's own answer (not the explicit M's, which would
      // compare the brute force with itself).
      EXPECT_EQ(r.stats.brute_fallbacks, 0) << toString(m);
    }
  }
  EXPECT_EQ(penetrating, 3);
}

// ---- Width -------------------------------------------------------------------------

/// Width of a regular k-gon of circumradius r.
double polygonWidth(int k, double r) {
  return k % 2 == 0 ? 2.0 * r * std::cos(kPi / k) : r * (1.0 + std::cos(kPi / k));
}

TEST(Width, KnownSolidsInRandomPoses) {
  struct Case {
    const char* name;
    Points points;
    double width;
  };
  std::vector<Case> cases = {
      {"cube, edge 2", generators::box({1, 1, 1}), 2.0},
      {"regular tetrahedron, edge 1", testing::regularTetrahedron(1.0), 1.0 / std::sqrt(2.0)},
      {"regular tetrahedron, edge 3", testing::regularTetrahedron(3.0), 3.0 / std::sqrt(2.0)},
      {"box 0.3 x 2 x 5", generators::box({0.15, 1.0, 2.5}), 0.3},
      {"box 4 x 3 x 5", generators::box({2.0, 1.5, 2.5}), 3.0},
  };
  for (int k : {3, 4, 5, 6, 7, 12}) {
    for (double h : {0.5, 3.0}) {
      cases.push_back({"prism", generators::prism(k, 1.0, h), std::min(h, polygonWidth(k, 1.0))});
    }
  }
  Rng rng(31);
  for (const Case& c : cases) {
    const ConvexPolytope p = ConvexPolytope::fromPoints(c.points);
    for (int i = 0; i < 3; ++i) {
      const Eigen::Isometry3d X = randomPoseAt(rng, 10.0);
      for (PenetrationMethod m : kAllMethods) {
        for (double delta : {0.5, 0.1, 0.01}) {
          if (delta != 0.5 && m != PenetrationMethod::kApprox) continue;
          SCOPED_TRACE(std::string(c.name) + ", " + toString(m) + ", delta " + std::to_string(delta));
          const WidthResult w = width(WidthInput{&p, X, m, delta});
          if (m == PenetrationMethod::kApprox) {
            EXPECT_GE(w.width, c.width - kTol);
            EXPECT_LE(w.width, (1 + delta) * c.width + kTol);
          } else {
            EXPECT_NEAR(w.width, c.width, kTol);
          }
          // A's extent along the direction is the reported width.
          ASSERT_NEAR(w.direction_W.norm(), 1.0, 1e-12);
          double lo = std::numeric_limits<double>::infinity();
          double hi = -lo;
          for (const Eigen::Vector3d& v : p.vertices()) {
            lo = std::min(lo, w.direction_W.dot(X * v));
            hi = std::max(hi, w.direction_W.dot(X * v));
          }
          EXPECT_NEAR(hi - lo, w.width, kTol);
        }
      }
    }
  }
}

TEST(Width, FlatPolygonHasWidthZeroAcrossItsPlane) {
  const ConvexPolytope t = ConvexPolytope::fromPoints(generators::triangle({0, 0, 1}, {2, 0, 1}, {0, 3, 1}));
  for (PenetrationMethod m : kAllMethods) {
    const WidthResult w = width(WidthInput{&t, Eigen::Isometry3d::Identity(), m});
    EXPECT_EQ(w.width, 0.0);
    EXPECT_NEAR(std::abs(w.direction_W.z()), 1.0, 1e-12);
  }
}

// ---- Polyhedral metric --------------------------------------------------------------

TEST(PolyhedralMetric, CubeMetricOnOverlappingCubes) {
  // K = [-2,2]^3 (the L-infinity ball of radius 2). A = [0,1]^3, B offset by
  // (0.7, 0.2, 0): M = [-1.7, 0.3] x [-1.2, 0.8] x [-1, 1]. A vertex of
  // lambda K reaches x = 0.3 first: lambda = 0.15 along a vertex (2, +-2, +-2).
  const ConvexPolytope cube = ConvexPolytope::fromPoints(boxFromTo({0, 0, 0}, {1, 1, 1}));
  const PolyhedralMetric k = PolyhedralMetric::fromPoints(generators::box({2, 2, 2}));
  EXPECT_NEAR(k.norm({0.3, -0.3, 0.1}), 0.15, 1e-15);
  for (PenetrationMethod m : {PenetrationMethod::kExact, PenetrationMethod::kBruteForce}) {
    const PolyhedralResult r = polyhedralPenetrationDepth({&cube, at({0, 0, 0}), &cube, at({0.7, 0.2, 0}), &k, m});
    EXPECT_EQ(r.status, PenetrationStatus::kPenetrating);
    EXPECT_NEAR(r.depth, 0.15, kTol);
    EXPECT_NEAR(r.translation_W.x(), 0.3, kTol);
    EXPECT_NEAR(k.norm(r.translation_W), 0.15, kTol);
    EXPECT_NEAR(r.euclidean_length, r.translation_W.norm(), 1e-15);
  }
  const PolyhedralResult sep = polyhedralPenetrationDepth({&cube, at({0, 0, 0}), &cube, at({3, 0, 0}), &k});
  EXPECT_EQ(sep.status, PenetrationStatus::kSeparated);
  EXPECT_EQ(sep.depth, 0.0);
  EXPECT_EQ(sep.k_vertex, -1);
}

TEST(PolyhedralMetric, AgreesWithTheBruteForceOnRandomPairs) {
  Rng rng(41);
  std::vector<PolyhedralMetric> metrics;
  metrics.push_back(PolyhedralMetric::fromPoints(generators::box({1, 1, 1})));  // L-infinity
  metrics.push_back(
      PolyhedralMetric::fromPoints({{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}));
  Points sym;
  for (int i = 0; i < 10; ++i) {
    const Eigen::Vector3d v = generators::randomUnitVector(rng).cwiseProduct(Eigen::Vector3d(1, 2, 0.5));
    sym.push_back(v);
    sym.push_back(-v);
  }
  metrics.push_back(PolyhedralMetric::fromPoints(sym));
  int penetrating = 0;
  for (int i = 0; i < 150; ++i) {
    const ConvexPolytope a = ConvexPolytope::fromPoints(generators::blob(4 + i % 30, {1, 1.4, 0.8}, rng));
    const ConvexPolytope b = i % 3 == 0 ? ConvexPolytope::fromPoints(generators::box({0.5, 0.3, 0.8}))
                                        : ConvexPolytope::fromPoints(generators::blob(4 + i % 17, {0.8, 1, 1.1}, rng));
    const Eigen::Isometry3d X_WA = pose(generators::randomRotation(rng), {0, 0, 0});
    const Eigen::Isometry3d X_WB = randomPoseAt(rng, 1.2);
    for (const PolyhedralMetric& k : metrics) {
      const PolyhedralResult fast = polyhedralPenetrationDepth({&a, X_WA, &b, X_WB, &k});
      const PolyhedralResult brute =
          polyhedralPenetrationDepth({&a, X_WA, &b, X_WB, &k, PenetrationMethod::kBruteForce});
      ASSERT_EQ(fast.status, brute.status) << toJsonLine({&a, X_WA, &b, X_WB});
      if (brute.status != PenetrationStatus::kPenetrating) continue;
      ++penetrating;
      ASSERT_NEAR(fast.depth, brute.depth, kTol * std::max(1.0, brute.depth)) << toJsonLine({&a, X_WA, &b, X_WB});
      // The translation is on the boundary of M: B moved by it touches A,
      // and its K-norm is the depth.
      EXPECT_NEAR(k.norm(fast.translation_W), fast.depth, kTol);
      const PenetrationResult check =
          pd(a, X_WA, b, pose(X_WB.linear(), X_WB.translation() + fast.translation_W), PenetrationMethod::kExact);
      EXPECT_NE(check.status, PenetrationStatus::kPenetrating);
    }
  }
  EXPECT_GE(penetrating, 200);
}

// ---- Direction grid ------------------------------------------------------------------

TEST(DirectionGrid, CoversTheSphereWithinTheCoveringAngle) {
  Rng rng(51);
  for (double delta : {0.01, 0.1, 0.5, 1.0, 3.0, 100.0}) {
    const std::vector<Eigen::Vector3d> grid = directionGrid(delta);
    const double theta = coveringAngle(delta);
    EXPECT_LE(1.0 / std::cos(theta), 1.0 + delta + 1e-12);
    EXPECT_LE(theta, std::sqrt(delta) + 1e-15);
    // About 2 pi / theta^2 directions.
    EXPECT_LE(static_cast<double>(grid.size()), 2.0 * 2.0 * kPi / (theta * theta) + 10) << delta;
    double worst = 0.0;
    const int samples = delta < 0.05 ? 4000 : 20000;
    for (int i = 0; i < samples; ++i) {
      const Eigen::Vector3d v = generators::randomUnitVector(rng);
      double best = -1.0;
      for (const Eigen::Vector3d& u : grid) best = std::max(best, u.dot(v));
      worst = std::max(worst, std::acos(std::min(1.0, best)));
    }
    EXPECT_LE(worst, theta) << "delta " << delta << ": " << grid.size() << " directions";
    for (size_t i = 0; i < grid.size(); ++i) EXPECT_NEAR(grid[i].norm(), 1.0, 1e-15);
  }
}

// ---- Errors ----------------------------------------------------------------------

TEST(PenetrationErrors, BadInputsNameWhatIsWrong) {
  const ConvexPolytope cube = ConvexPolytope::fromPoints(generators::box({1, 1, 1}));
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  auto message = [](const auto& call) -> std::string {
    try {
      call();
    } catch (const InvalidInputError& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_NE(message([&] { penetrationDepth({nullptr, I, &cube, I}); }).find("polytope A is null"), std::string::npos);
  EXPECT_NE(message([&] { penetrationDepth({&cube, I, nullptr, I}); }).find("polytope B is null"), std::string::npos);
  Eigen::Isometry3d bad = Eigen::Isometry3d::Identity();
  bad.linear() *= 2.0;
  EXPECT_NE(message([&] { penetrationDepth({&cube, bad, &cube, I}); }).find("X_WA"), std::string::npos);
  for (double delta : {-1.0, 1e-5, 1e4, std::nan("")}) {
    for (PenetrationMethod m : {PenetrationMethod::kApprox, PenetrationMethod::kShallow}) {
      const std::string what = message([&] { penetrationDepth({&cube, I, &cube, I, m, delta}); });
      EXPECT_NE(what.find("delta"), std::string::npos) << what;
    }
    EXPECT_NE(message([&] { width({&cube, I, PenetrationMethod::kApprox, delta}); }).find("delta"), std::string::npos);
  }
  // The exact methods do not use delta, but refuse a bad one all the same (a
  // NaN or negative delta passed silently; a hostile-input hunt on the Python
  // module); 0 and in-range values are accepted.
  for (PenetrationMethod m : {PenetrationMethod::kExact, PenetrationMethod::kBruteForce}) {
    for (double delta : {-1.0, -1e-300, 1e4, std::nan("")}) {
      const std::string what = message([&] { penetrationDepth({&cube, I, &cube, I, m, delta}); });
      EXPECT_NE(what.find("penetrationDepth: delta "), std::string::npos) << what;
      EXPECT_NE(message([&] { width({&cube, I, m, delta}); }).find("width: delta "), std::string::npos);
    }
    EXPECT_EQ(message([&] { penetrationDepth({&cube, I, &cube, I, m, 0.0}); }), "(no error)");
    EXPECT_EQ(message([&] { penetrationDepth({&cube, I, &cube, I, m, 0.5}); }), "(no error)");
  }
  EXPECT_NE(message([&] {
              penetrationDepth({&cube, I, &cube, I, static_cast<PenetrationMethod>(9)});
            }).find("unknown method"),
            std::string::npos);
  EXPECT_NE(message([&] { width({nullptr}); }).find("null"), std::string::npos);
  // Metrics.
  EXPECT_NE(message([&] {
              polyhedralPenetrationDepth({&cube, I, &cube, I, nullptr});
            }).find("metric is null"),
            std::string::npos);
  EXPECT_NE(message([&] {
              PolyhedralMetric::fromPoints({{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}});
            }).find("flat"),
            std::string::npos);
  const std::string asym = message([&] { PolyhedralMetric::fromPoints(testing::regularTetrahedron(1.0)); });
  EXPECT_NE(asym.find("not centrally symmetric"), std::string::npos) << asym;
  EXPECT_NE(message([&] { PolyhedralMetric::fromPoints({}); }).find("polyhedral metric: "), std::string::npos);
  const PolyhedralMetric k = PolyhedralMetric::fromPoints(generators::box({1, 1, 1}));
  EXPECT_NE(message([&] {
              polyhedralPenetrationDepth({&cube, I, &cube, I, &k, PenetrationMethod::kApprox});
            }).find("not available"),
            std::string::npos);
}

}  // namespace
}  // namespace mddual
