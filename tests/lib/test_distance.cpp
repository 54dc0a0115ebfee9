// distance() (lib/src/distance.cpp) against three oracles:
//   - the brute force: M = A - B built explicitly (MinkowskiDifference); the
//     distance is that of the origin to M, computed here from M's faces
//     (triangle fans: projection inside, else the nearest boundary segment),
//     and minus the smallest face offset when the origin is inside M;
//   - FCL's distance (fcl::distance, GJK on fcl::Convex) on the same vertices
//     and faces, when FCL is available;
//   - closed forms (unit cubes at known offsets).
// Seeded randomized families: blobs, boxes, flat triangles, touching and
// nearly touching pairs, bodies whose points lie 1e3..1e6 from the origin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "family_support.h"
#include "mddual/brute_force.h"
#include "mddual/constants.h"
#include "mddual/distance.h"
#include "mddual/error.h"
#include "mddual/generators.h"

#ifdef MDDUAL_TEST_WITH_FCL
#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/distance.h>

#include "mddual/fcl_interop.h"
#endif

namespace mddual::testing {
namespace {

using generators::Points;
using generators::Rng;

/// Required accuracy relative to the pair's length scale (the 1e-9).
constexpr double kAccuracyRel = 1e-9;

double pairScale(const ConvexPolytope& a, const Eigen::Isometry3d& X_WA, const ConvexPolytope& b,
                 const Eigen::Isometry3d& X_WB) {
  const Eigen::Vector3d ca = X_WA * a.centroid();
  const Eigen::Vector3d cb = X_WB * b.centroid();
  return std::max({a.radius(), b.radius(), (ca - cb).norm()});
}

/// Distance from the origin to segment pq.
double segmentDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  const Eigen::Vector3d d = q - p;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp(-p.dot(d) / len2, 0.0, 1.0) : 0.0;
  return (p + t * d).norm();
}

/// Distance from the origin to triangle pqr: the plane distance when the
/// foot lies inside, else the nearest edge.
double triangleDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r) {
  const Eigen::Vector3d n = (q - p).cross(r - p);
  const double nn = n.squaredNorm();
  if (nn > 0.0) {
    const Eigen::Vector3d foot = n * (p.dot(n) / nn);
    const double s0 = (q - p).cross(foot - p).dot(n);
    const double s1 = (r - q).cross(foot - q).dot(n);
    const double s2 = (p - r).cross(foot - r).dot(n);
    if (s0 >= 0.0 && s1 >= 0.0 && s2 >= 0.0) return foot.norm();
  }
  return std::min({segmentDistance(p, q), segmentDistance(q, r), segmentDistance(r, p)});
}

/// Signed distance of the origin to M (brute force): > 0 outside, minus the
/// smallest face offset inside a solid M, 0 for an origin in a flat M.
double bruteSigned(const ConvexPolytope& a, const Eigen::Isometry3d& X_WA, const ConvexPolytope& b,
                   const Eigen::Isometry3d& X_WB) {
  const ConvexPolytope m = MinkowskiDifference::build(a, X_WA, b, X_WB).polytope;
  double outside = std::numeric_limits<double>::infinity();
  for (int f = 0; f < m.numFaces(); ++f) {
    const IndexRange loop = m.faceVertices(f);
    for (int k = 1; k + 1 < loop.size(); ++k) {
      outside = std::min(outside, triangleDistance(m.vertex(loop[0]), m.vertex(loop[k]), m.vertex(loop[k + 1])));
    }
  }
  double min_offset = std::numeric_limits<double>::infinity();
  for (int f = 0; f < m.numFaces(); ++f) min_offset = std::min(min_offset, m.faceOffset(f));
  if (min_offset < 0.0 || m.isFlat()) return outside;  // origin outside (or M flat: no interior)
  return -min_offset;
}

#ifdef MDDUAL_TEST_WITH_FCL
/// FCL's distance (libccd GJK, tight tolerance; FCL's own GJK stops early on
/// bodies of a few cm: 7e-5 off on one blob pair); negative when FCL
/// reports a collision (its value is then not a depth).
double fclDistance(const ConvexPolytope& a, const Eigen::Isometry3d& X_WA, const ConvexPolytope& b,
                   const Eigen::Isometry3d& X_WB) {
  auto ca = toFclConvex(a);
  auto cb = toFclConvex(b);
  fcl::DistanceRequest<double> request;
  request.enable_nearest_points = true;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.distance_tolerance = 1e-14;
  fcl::DistanceResult<double> result;
  fcl::Transform3<double> ta = X_WA;
  fcl::Transform3<double> tb = X_WB;
  return fcl::distance(ca.get(), ta, cb.get(), tb, request, result);
}
#endif

/// What a family observed.
struct Tally {
  int separated = 0;
  int touching = 0;
  int penetrating = 0;
  int polished = 0;
  int polish_pairs = 0;
  int fcl_due = 0;  ///< separated pairs farther than 1e-6 L: the FCL cross-check's cases
  int fcl_compared = 0;
  double max_err_brute = 0.0;  ///< relative to the pair scale
  double max_err_fcl = 0.0;
  void print(const char* family) const {
    std::printf(
        "[ sample   ] %s: separated %d, touching %d, penetrating %d, polished %d (%d feature pairs); "
        "max |err| / L: brute %.3g, FCL %.3g (%d of %d compared)\n",
        family, separated, touching, penetrating, polished, polish_pairs, max_err_brute, max_err_fcl, fcl_compared,
        fcl_due);
#ifdef MDDUAL_TEST_WITH_FCL
    // The cross-check ran on every case it is about (it cannot vanish).
    EXPECT_EQ(fcl_compared, fcl_due);
#else
    std::printf("[ sample   ] FCL cross-check NOT BUILT (configured with MDDUAL_REQUIRE_FCL_ORACLE=OFF)\n");
#endif
  }
};

/// Checks one pair against the oracles and the result's own contract.
void checkPair(const ConvexPolytope& a, const Eigen::Isometry3d& X_WA, const ConvexPolytope& b,
               const Eigen::Isometry3d& X_WB, Tally* tally) {
  DistanceInput in;
  in.a = &a;
  in.X_WA = X_WA;
  in.b = &b;
  in.X_WB = X_WB;
  const DistanceResult r = distance(in);
  const double L = pairScale(a, X_WA, b, X_WB);
  const double tol = kAccuracyRel * L;
  const double brute = bruteSigned(a, X_WA, b, X_WB);
  SCOPED_TRACE(toJsonLine(DirectionalInput{&a, X_WA, &b, X_WB, Eigen::Vector3d::UnitX()}));
  if (r.stats.polished) ++tally->polished;
  tally->polish_pairs += r.stats.polish_pairs;
  switch (r.status) {
    case DistanceStatus::kSeparated: {
      ++tally->separated;
      EXPECT_GT(r.distance, 0.0);
      EXPECT_NEAR(r.distance, (r.p_WB - r.p_WA).norm(), tol);
      EXPECT_LE(r.lower_bound, r.distance);
      EXPECT_GE(r.lower_bound, r.distance - tol);
      // The witness points lie in their bodies (within tol of every face).
      const Eigen::Vector3d a_P = X_WA.inverse() * r.p_WA;
      const Eigen::Vector3d b_P = X_WB.inverse() * r.p_WB;
      for (int f = 0; f < a.numFaces(); ++f) EXPECT_LE(a.faceNormal(f).dot(a_P) - a.faceOffset(f), tol);
      for (int f = 0; f < b.numFaces(); ++f) EXPECT_LE(b.faceNormal(f).dot(b_P) - b.faceOffset(f), tol);
      EXPECT_NEAR(r.normal_W.norm(), 1.0, 1e-12);
      break;
    }
    case DistanceStatus::kTouching:
      ++tally->touching;
      EXPECT_EQ(r.distance, 0.0);
      EXPECT_LE(std::abs(brute), tol);
      EXPECT_LE((r.p_WA - r.p_WB).norm(), tol);
      break;
    case DistanceStatus::kPenetrating:
      ++tally->penetrating;
      EXPECT_LT(r.distance, 0.0);
      EXPECT_NEAR((r.p_WA - r.p_WB).norm(), -r.distance, tol);
      EXPECT_NEAR((r.p_WA - r.p_WB).dot(r.normal_W), -r.distance, tol);
      break;
  }
  const double err = std::abs(r.distance - (r.status == DistanceStatus::kTouching ? 0.0 : brute));
  EXPECT_LE(err, tol) << "distance " << r.distance << " brute force " << brute;
  tally->max_err_brute = std::max(tally->max_err_brute, err / L);
  if (r.status == DistanceStatus::kSeparated && r.distance > 1e-6 * L) ++tally->fcl_due;
#ifdef MDDUAL_TEST_WITH_FCL
  if (r.status == DistanceStatus::kSeparated && r.distance > 1e-6 * L) {
    const double f = fclDistance(a, X_WA, b, X_WB);
    const double ferr = std::abs(f - r.distance);
    EXPECT_LE(ferr, tol) << "FCL " << f << " ours " << r.distance;
    tally->max_err_fcl = std::max(tally->max_err_fcl, ferr / L);
    ++tally->fcl_compared;
  }
#endif
}

Eigen::Isometry3d randomPose(Rng& rng, double spread) {
  // The translation before the rotation: the order GCC evaluated pose()'s
  // arguments (C++ leaves it unspecified), kept so seeded poses stay as they were.
  const Eigen::Vector3d p = generators::drawVector(std::uniform_real_distribution<double>(-spread, spread), rng);
  const Eigen::Matrix3d R = generators::randomRotation(rng);
  return pose(R, p);
}

Points randomBlob(Rng& rng, double scale) {
  const Eigen::Vector3d axes = generators::drawVector(std::uniform_real_distribution<double>(0.3, 2.0), rng);
  return generators::blob(uniformInt(rng, 4, 60), axes * scale, rng);
}

Points shifted(Points p, const Eigen::Vector3d& offset) {
  for (auto& x : p) x += offset;
  return p;
}

int samples(int n) {
  return n * static_cast<int>(envLong("MDDUAL_SWEEP_SCALE", 1));
}
std::uint64_t seed(std::uint64_t s) {
  return s + static_cast<std::uint64_t>(envLong("MDDUAL_SWEEP_SEED", 0));
}

TEST(Distance, ClosedFormUnitCubes) {
  const ConvexPolytope cube = ConvexPolytope::fromPoints(generators::box(Eigen::Vector3d::Constant(0.5)));
  auto at = [](const Eigen::Vector3d& p) { return pose(Eigen::Matrix3d::Identity(), p); };
  struct Case {
    Eigen::Vector3d offset;
    double expected;
  };
  const Case cases[] = {
      {{3.0, 0.0, 0.0}, 2.0},                         // face to face
      {{1.5, 1.5, 0.0}, std::sqrt(0.5)},              // edge to edge
      {{2.0, 3.0, 4.0}, std::sqrt(1.0 + 4.0 + 9.0)},  // vertex to vertex
      {{1.25, 0.3, -0.2}, 0.25},                      // face to face, shifted
      {{1.0, 0.0, 0.0}, 0.0},                         // touching
      {{0.75, 0.1, 0.0}, -0.25},                      // overlap 0.25 along x
      {{0.0, 0.0, 0.0}, -1.0},                        // coincident
  };
  for (const Case& c : cases) {
    for (double far : {0.0, 1e3, 1e6}) {
      DistanceInput in;
      in.a = &cube;
      in.X_WA = at(Eigen::Vector3d::Constant(far));
      in.b = &cube;
      in.X_WB = at(Eigen::Vector3d::Constant(far) + c.offset);
      const DistanceResult r = distance(in);
      EXPECT_NEAR(r.distance, c.expected, 1e-9) << c.offset.transpose() << " at " << far;
      if (c.expected > 0.0) {
        EXPECT_EQ(r.status, DistanceStatus::kSeparated);
        EXPECT_NEAR((r.p_WB - r.p_WA).norm(), c.expected, 1e-9);
      } else if (c.expected == 0.0) {
        EXPECT_EQ(r.status, DistanceStatus::kTouching);
      } else {
        EXPECT_EQ(r.status, DistanceStatus::kPenetrating);
      }
    }
  }
  // Rotated: a cube turned 45 degrees about z, its edge facing the other's face.
  DistanceInput in;
  in.a = &cube;
  in.b = &cube;
  in.X_WB =
      pose(Eigen::AngleAxisd(kPi / 4.0, Eigen::Vector3d::UnitZ()).toRotationMatrix(), Eigen::Vector3d(2.0, 0.0, 0.0));
  const DistanceResult r = distance(in);
  EXPECT_NEAR(r.distance, 1.5 - std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(r.p_WA.x(), 0.5, 1e-12);
  EXPECT_NEAR(r.p_WB.x(), 2.0 - std::sqrt(0.5), 1e-12);
}

TEST(Distance, RandomBlobs) {
  Rng rng(seed(101));
  Tally t;
  for (int i = 0; i < samples(300) && !HasFailure(); ++i) {
    const double s = std::pow(10.0, uniform(rng, -2.0, 2.0));
    const ConvexPolytope a = ConvexPolytope::fromPoints(randomBlob(rng, s));
    const ConvexPolytope b = ConvexPolytope::fromPoints(randomBlob(rng, s));
    // B's pose first: the order GCC evaluated checkPair()'s arguments (C++
    // leaves it unspecified), kept so the seeded scenes stay as they were.
    const Eigen::Isometry3d X_WB = randomPose(rng, 2.5 * s);
    const Eigen::Isometry3d X_WA = randomPose(rng, 1.0 * s);
    checkPair(a, X_WA, b, X_WB, &t);
  }
  t.print("blobs");
  EXPECT_GE(t.separated, samples(300) / 3);
  EXPECT_GE(t.penetrating, samples(300) / 10);
}

// separationLowerBound: never above the distance, within GJK's certified gap
// of it on separated pairs, 0 on overlapping ones; with `enough`, at least
// `enough` (or the distance, when that is smaller) and still never above it.
TEST(Distance, SeparationLowerBoundBracketsTheDistance) {
  Rng rng(seed(808));
  int separated = 0, overlapping = 0, stopped_early = 0, rough_early = 0;
  for (int i = 0; i < samples(300) && !HasFailure(); ++i) {
    const double s = std::pow(10.0, uniform(rng, -2.0, 2.0));
    const ConvexPolytope a = ConvexPolytope::fromPoints(randomBlob(rng, s));
    const ConvexPolytope b = ConvexPolytope::fromPoints(randomBlob(rng, s));
    DistanceInput in;
    in.a = &a;
    in.b = &b;
    in.X_WB = randomPose(rng, 2.5 * s);
    in.X_WA = randomPose(rng, 1.0 * s);
    const double d = distance(in).distance;
    const double slack = 1e-9 * (a.radius() + b.radius() + std::abs(d));
    const double lb = separationLowerBound(in);
    EXPECT_LE(lb, std::max(d, 0.0) + slack) << i;
    if (d > slack) {
      ++separated;
      EXPECT_GE(lb, d - 1e-6 * (a.radius() + b.radius() + d)) << i;
      const double half = separationLowerBound(in, nullptr, 0.5 * d);
      EXPECT_GE(half, 0.5 * d) << i;
      EXPECT_LE(half, d + slack) << i;
      stopped_early += half < lb ? 1 : 0;
      const double rough = separationLowerBound(in, nullptr, std::numeric_limits<double>::infinity(), 0.25);
      EXPECT_GE(rough, 0.75 * d - slack) << i;
      EXPECT_LE(rough, d + slack) << i;
      rough_early += rough < lb - slack ? 1 : 0;
    } else if (d < -slack) {
      ++overlapping;
      EXPECT_EQ(lb, 0.0) << i;
      EXPECT_EQ(separationLowerBound(in, nullptr, 1.0), 0.0) << i;
    }
  }
  EXPECT_GE(separated, samples(300) / 3);
  EXPECT_GE(overlapping, samples(300) / 10);
  EXPECT_GE(stopped_early, separated / 10);  // `enough` does cut GJK short
  EXPECT_GE(rough_early, separated / 10);    // and so does rel_gap
  DistanceInput in;
  const ConvexPolytope cube = ConvexPolytope::fromPoints(generators::box(Eigen::Vector3d::Constant(0.5)));
  in.a = &cube;
  in.b = &cube;
  EXPECT_THROW(separationLowerBound(in, nullptr, std::numeric_limits<double>::quiet_NaN()), InvalidInputError);
  EXPECT_THROW(separationLowerBound(in, nullptr, 1.0, 1.0), InvalidInputError);
  EXPECT_THROW(separationLowerBound(in, nullptr, 1.0, -0.1), InvalidInputError);
  EXPECT_THROW(separationLowerBound(in, nullptr, 1.0, std::numeric_limits<double>::quiet_NaN()), InvalidInputError);
}

TEST(Distance, RandomBoxes) {
  Rng rng(seed(202));
  Tally t;
  for (int i = 0; i < samples(300) && !HasFailure(); ++i) {
    auto extents = [&] { return generators::drawVector(std::uniform_real_distribution<double>(0.1, 2.0), rng); };
    const ConvexPolytope a = ConvexPolytope::fromPoints(generators::box(extents()));
    const ConvexPolytope b = ConvexPolytope::fromPoints(generators::box(extents()));
    // Half the scenes keep both boxes axis-aligned (parallel faces: face-face
    // closest features, degenerate for GJK).
    const bool aligned = i % 2 == 0;
    const Eigen::Isometry3d X_WA =
        aligned ? pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()) : randomPose(rng, 1.0);
    Eigen::Isometry3d X_WB = randomPose(rng, 5.0);
    if (aligned) X_WB.linear().setIdentity();
    checkPair(a, X_WA, b, X_WB, &t);
  }
  t.print("boxes");
  EXPECT_GE(t.separated, samples(300) / 3);
  EXPECT_GE(t.penetrating, samples(300) / 20);
}

TEST(Distance, FlatTriangles) {
  Rng rng(seed(303));
  Tally t;
  for (int i = 0; i < samples(300) && !HasFailure(); ++i) {
    const ConvexPolytope a = ConvexPolytope::fromPoints(randomTriangle(rng, 1.0));
    const ConvexPolytope b = ConvexPolytope::fromPoints(i % 2 == 0 ? randomTriangle(rng, 1.0) : randomBlob(rng, 1.0));
    // B's pose first, as GCC evaluated checkPair()'s arguments.
    const Eigen::Isometry3d X_WB = randomPose(rng, 3.0);
    const Eigen::Isometry3d X_WA = randomPose(rng, 1.0);
    checkPair(a, X_WA, b, X_WB, &t);
  }
  t.print("flat triangles");
  EXPECT_GE(t.separated, samples(300) / 3);
}

TEST(Distance, TouchingAndNearlyTouching) {
  // B moved by the brute force's closest point c of M: B + c touches A
  // (distance 0); B + (1 - eps) c is separated by eps |c|.
  Rng rng(seed(404));
  Tally t;
  int near = 0;
  for (int i = 0; i < samples(200) && !HasFailure(); ++i) {
    const ConvexPolytope a =
        ConvexPolytope::fromPoints(i % 3 == 0 ? generators::box(Eigen::Vector3d(1.0, 0.5, 0.3)) : randomBlob(rng, 1.0));
    const ConvexPolytope b = ConvexPolytope::fromPoints(randomBlob(rng, 1.0));
    const Eigen::Isometry3d X_WA = randomPose(rng, 1.0);
    Eigen::Isometry3d X_WB = randomPose(rng, 1.0);
    X_WB.translation() += 8.0 * generators::randomUnitVector(rng);
    DistanceInput in{&a, X_WA, &b, X_WB};
    const DistanceResult r = distance(in);
    ASSERT_EQ(r.status, DistanceStatus::kSeparated);
    // c = p_WA - p_WB (the closest point of M); the brute force checks it.
    const Eigen::Vector3d c = r.p_WA - r.p_WB;
    const double eps = i % 2 == 0 ? 0.0 : std::pow(10.0, uniform(rng, -8.0, -3.0));
    Eigen::Isometry3d X_WB2 = X_WB;
    X_WB2.translation() += (1.0 - eps) * c;
    checkPair(a, X_WA, b, X_WB2, &t);
    if (eps > 0.0) {
      const DistanceResult r2 = distance(DistanceInput{&a, X_WA, &b, X_WB2});
      EXPECT_NEAR(r2.distance, eps * c.norm(), kAccuracyRel * pairScale(a, X_WA, b, X_WB2));
      ++near;
    }
  }
  t.print("touching / nearly touching");
  EXPECT_GE(t.touching, samples(200) / 4);
  EXPECT_GE(near, samples(200) / 3);
}

TEST(Distance, PolishedAnswersAreExact) {
  // Gaps of 1e-9 .. 1e-6 of the pair's size: GJK's direction is then poor
  // and it often stalls; the polish must give the exact distance and a
  // lower_bound equal to it (regression: lower_bound was left at GJK's
  // bound, 2e-9 L below the distance, on a 10x sweep). Large blobs check that
  // the polish stays local (its feature pairs are reported).
  Rng rng(seed(707));
  Tally t;
  int polished = 0;
  for (int i = 0; i < samples(120) && !HasFailure(); ++i) {
    const int n = i % 4 == 0 ? 150 : 30;
    const ConvexPolytope a = ConvexPolytope::fromPoints(generators::blob(n, Eigen::Vector3d(1.0, 0.7, 0.5), rng));
    const ConvexPolytope b = ConvexPolytope::fromPoints(generators::blob(n, Eigen::Vector3d(0.6, 1.0, 0.8), rng));
    const Eigen::Isometry3d X_WA = randomPose(rng, 1.0);
    Eigen::Isometry3d X_WB = randomPose(rng, 1.0);
    X_WB.translation() += 6.0 * generators::randomUnitVector(rng);
    const DistanceResult r = distance(DistanceInput{&a, X_WA, &b, X_WB});
    ASSERT_EQ(r.status, DistanceStatus::kSeparated);
    const Eigen::Vector3d c = r.p_WA - r.p_WB;
    const double gap = std::pow(10.0, uniform(rng, -9.0, -6.0)) * pairScale(a, X_WA, b, X_WB);
    X_WB.translation() += c - gap * c.normalized();
    const DistanceResult r2 = distance(DistanceInput{&a, X_WA, &b, X_WB});
    polished += r2.stats.polished ? 1 : 0;
    checkPair(a, X_WA, b, X_WB, &t);
  }
  t.print("gaps of 1e-9 .. 1e-6");
  EXPECT_GE(polished, samples(120) / 20);
  EXPECT_GE(t.separated, samples(120) / 2);
}

TEST(Distance, ParallelFlatPolygons) {
  // Two triangles in parallel planes: M is flat. Coplanar and overlapping:
  // touching (no interior to penetrate); offset along the normal by h: h.
  const ConvexPolytope tri = ConvexPolytope::fromPoints(
      generators::triangle(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(0, 2, 0)));
  for (double h : {0.0, 0.5, 3.0}) {
    for (double shift : {0.3, 5.0}) {
      const Eigen::Isometry3d X_WB = pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(shift, 0.2, h));
      const DistanceResult r = distance(DistanceInput{&tri, Eigen::Isometry3d::Identity(), &tri, X_WB});
      // In the plane: overlapping for shift 0.3; for shift 5, B's corner
      // (5, 0.2) is nearest to A's corner (2, 0).
      const double in_plane = shift < 2.0 ? 0.0 : std::hypot(shift - 2.0, 0.2);
      const double expected = std::hypot(h, in_plane);
      EXPECT_NEAR(r.distance, expected, 1e-12) << "h " << h << " shift " << shift;
      EXPECT_EQ(r.status, expected > 0.0 ? DistanceStatus::kSeparated : DistanceStatus::kTouching);
    }
  }
}

TEST(Distance, FarFromOrigin) {
  // Points (not poses) 1e3 .. 1e6 from the origin: the body's own frame is
  // far away, as in a world mesh.
  Rng rng(seed(505));
  Tally t;
  for (int i = 0; i < samples(200) && !HasFailure(); ++i) {
    // The direction before the distance: the order GCC evaluated the operands
    // of the product (C++ leaves them unsequenced), kept so the samples stay.
    const Eigen::Vector3d direction = generators::randomUnitVector(rng);
    const Eigen::Vector3d far = std::pow(10.0, uniform(rng, 3.0, 6.0)) * direction;
    const Eigen::Vector3d rel = generators::drawVector(std::uniform_real_distribution<double>(-4.0, 4.0), rng);
    const ConvexPolytope a = ConvexPolytope::fromPoints(shifted(randomBlob(rng, 1.0), far));
    const ConvexPolytope b = ConvexPolytope::fromPoints(shifted(randomBlob(rng, 1.0), far + rel));
    const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
    checkPair(a, I, b, I, &t);
  }
  t.print("far from origin");
  EXPECT_GE(t.separated, samples(200) / 3);
  EXPECT_GE(t.penetrating, samples(200) / 20);
}

TEST(Distance, WarmStartGivesTheSameAnswer) {
  Rng rng(seed(606));
  const ConvexPolytope a = ConvexPolytope::fromPoints(randomBlob(rng, 1.0));
  const ConvexPolytope b = ConvexPolytope::fromPoints(randomBlob(rng, 1.0));
  DistanceWarmStart warm;
  for (int i = 0; i < 200; ++i) {
    DistanceInput in{&a, Eigen::Isometry3d::Identity(), &b,
                     pose(Eigen::AngleAxisd(0.01 * i, Eigen::Vector3d::UnitZ()).toRotationMatrix(),
                          Eigen::Vector3d(4.0 * std::cos(0.05 * i), 4.0 * std::sin(0.05 * i), 0.3))};
    const DistanceResult cold = distance(in);
    const DistanceResult hot = distance(in, &warm);
    EXPECT_EQ(cold.status, hot.status);
    EXPECT_NEAR(cold.distance, hot.distance, 1e-9 * 5.0);
  }
}

TEST(Distance, BadInputIsReported) {
  const ConvexPolytope cube = ConvexPolytope::fromPoints(generators::box(Eigen::Vector3d::Constant(0.5)));
  DistanceInput in;
  in.a = &cube;
  EXPECT_THROW(distance(in), InvalidInputError);
  in.b = &cube;
  in.X_WB.translation().x() = std::numeric_limits<double>::quiet_NaN();
  try {
    distance(in);
    FAIL() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("X_WB"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mddual::testing
