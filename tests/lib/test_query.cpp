// mdd(), toi() and intersect() on hand-computed configurations with exact
// expected values, plus errors, warm starts and concurrent use.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <thread>

#include "mddual/brute_force.h"
#include "mddual/constants.h"
#include "mddual/error.h"
#include "mddual/generators.h"
#include "mddual/query.h"

namespace mddual {
namespace {

const ConvexPolytope& unitCube() {
  static const ConvexPolytope cube = ConvexPolytope::fromPoints(generators::box({0.5, 0.5, 0.5}));
  return cube;
}

Eigen::Isometry3d at(double x, double y, double z) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(x, y, z);
  return X;
}

MddResult mddOf(const ConvexPolytope& a, const Eigen::Isometry3d& X_WA, const ConvexPolytope& b,
                const Eigen::Isometry3d& X_WB, const Eigen::Vector3d& s) {
  return mdd(DirectionalInput{&a, X_WA, &b, X_WB, s});
}

ToiResult toiOf(const ConvexPolytope& a, const Eigen::Isometry3d& X_WA, const ConvexPolytope& b,
                const Eigen::Isometry3d& X_WB, const Eigen::Vector3d& s,
                double max_distance = std::numeric_limits<double>::infinity()) {
  return toi(DirectionalInput{&a, X_WA, &b, X_WB, s, max_distance});
}

constexpr double kTol = 1e-12;

TEST(Query, TwoCubesSeparatedAlongX) {
  // B at x = -3: M = [2, 4] x [-1, 1]^2, the line along +x enters at t = 2.
  const MddResult r = mddOf(unitCube(), at(0, 0, 0), unitCube(), at(-3, 0, 0), {1, 0, 0});
  EXPECT_EQ(r.status, ContactStatus::kSeparated);
  EXPECT_NEAR(r.distance, 2.0, kTol);
  EXPECT_NEAR(r.t_lo, 2.0, kTol);
  EXPECT_TRUE(r.contact.normal_W.isApprox(Eigen::Vector3d(-1, 0, 0), kTol));
  EXPECT_NEAR(r.contact.point_W.x(), -0.5, kTol);
  EXPECT_LE(r.contact.point_W.tail<2>().cwiseAbs().maxCoeff(), 0.5 + kTol);

  const ToiResult t = toiOf(unitCube(), at(0, 0, 0), unitCube(), at(-3, 0, 0), {1, 0, 0});
  EXPECT_EQ(t.status, ToiStatus::kHit);
  EXPECT_NEAR(t.toi, 2.0, kTol);
  EXPECT_TRUE(t.contact.normal_W.isApprox(Eigen::Vector3d(-1, 0, 0), kTol));

  // Non-unit direction: distances are lengths, not multiples of |s|.
  EXPECT_NEAR(mddOf(unitCube(), at(0, 0, 0), unitCube(), at(-3, 0, 0), {7, 0, 0}).distance, 2.0, kTol);
  EXPECT_NEAR(toiOf(unitCube(), at(0, 0, 0), unitCube(), at(-3, 0, 0), {0.01, 0, 0}).toi, 2.0, kTol);
}

TEST(Query, ExtremeDirectionMagnitudes) {
  // Regression: |s| overflowed (1e300) or underflowed (1e-200) in the
  // normalisation and valid directions were rejected.
  for (const double scale : {1e300, 1e-200, 1e-310}) {
    const MddResult r = mddOf(unitCube(), at(0, 0, 0), unitCube(), at(-3, 0, 0), {scale, 0, 0});
    EXPECT_EQ(r.status, ContactStatus::kSeparated) << scale;
    EXPECT_NEAR(r.distance, 2.0, kTol) << scale;
  }
}

TEST(Query, MovingAwayIsSeparatedBackwardAndNeverHits) {
  const MddResult r = mddOf(unitCube(), at(0, 0, 0), unitCube(), at(-3, 0, 0), {-1, 0, 0});
  EXPECT_EQ(r.status, ContactStatus::kSeparated);
  EXPECT_NEAR(r.distance, 2.0, kTol);  // B must move back by 2
  EXPECT_NEAR(r.t_hi, -2.0, kTol);
  EXPECT_TRUE(r.contact.normal_W.isApprox(Eigen::Vector3d(-1, 0, 0), kTol));
  const ToiResult t = toiOf(unitCube(), at(0, 0, 0), unitCube(), at(-3, 0, 0), {-1, 0, 0});
  EXPECT_EQ(t.status, ToiStatus::kNever);
  EXPECT_TRUE(std::isinf(t.toi));
}

TEST(Query, LineMissingMIsNoContact) {
  const MddResult r = mddOf(unitCube(), at(0, 0, 0), unitCube(), at(-3, 0, 0), {0, 1, 0});
  EXPECT_EQ(r.status, ContactStatus::kNoContact);
  EXPECT_TRUE(std::isnan(r.distance));
  EXPECT_TRUE(std::isnan(r.contact.normal_W.x()));
  EXPECT_EQ(r.contact.feature_a.type, FeatureType::kNone);
  EXPECT_EQ(toiOf(unitCube(), at(0, 0, 0), unitCube(), at(-3, 0, 0), {0, 1, 0}).status, ToiStatus::kNever);
}

TEST(Query, TouchingCubes) {
  const MddResult r = mddOf(unitCube(), at(0, 0, 0), unitCube(), at(-1, 0.3, 0.1), {1, 0, 0});
  EXPECT_EQ(r.status, ContactStatus::kTouching);
  EXPECT_EQ(r.distance, 0.0);
  EXPECT_NEAR(r.t_lo, 0.0, kTol);
  EXPECT_FALSE(std::signbit(r.t_lo));  // no -0.0 in outputs
  EXPECT_NEAR(r.t_hi, 2.0, kTol);
  const ToiResult t = toiOf(unitCube(), at(0, 0, 0), unitCube(), at(-1, 0.3, 0.1), {1, 0, 0});
  EXPECT_EQ(t.status, ToiStatus::kInContact);
  EXPECT_EQ(t.toi, 0.0);
  const IntersectResult i = intersect(IntersectInput{&unitCube(), at(0, 0, 0), &unitCube(), at(-1, 0.3, 0.1)});
  EXPECT_EQ(i.status, IntersectStatus::kTouching);
  EXPECT_TRUE(i.intersecting);
  // The direction lies in the touching plane: a grazing line, still touching.
  const MddResult g = mddOf(unitCube(), at(0, 0, 0), unitCube(), at(-1, 0.3, 0.1), {0, 1, 1});
  EXPECT_EQ(g.status, ContactStatus::kTouching);
  EXPECT_TRUE(g.stats.planar);
}

TEST(Query, PenetratingCubesTakeTheShorterWayOut) {
  // B at (-0.5, 0.25, 0): M = [-0.5, 1.5] x [-1.25, 0.75] x [-1, 1].
  const Eigen::Isometry3d X_WB = at(-0.5, 0.25, 0);
  const MddResult x = mddOf(unitCube(), at(0, 0, 0), unitCube(), X_WB, {1, 0, 0});
  EXPECT_EQ(x.status, ContactStatus::kPenetrating);
  EXPECT_NEAR(x.distance, -0.5, kTol);
  EXPECT_NEAR(x.t_lo, -0.5, kTol);
  EXPECT_NEAR(x.t_hi, 1.5, kTol);
  EXPECT_TRUE(x.contact.normal_W.isApprox(Eigen::Vector3d(-1, 0, 0), kTol));

  const MddResult y = mddOf(unitCube(), at(0, 0, 0), unitCube(), X_WB, {0, 1, 0});
  EXPECT_EQ(y.status, ContactStatus::kPenetrating);
  EXPECT_NEAR(y.distance, -0.75, kTol);
  EXPECT_TRUE(y.contact.normal_W.isApprox(Eigen::Vector3d(0, 1, 0), kTol));

  // Diagonal: x limits t to [-0.5, 1.5] * sqrt2, y to [-1.25, 0.75] * sqrt2.
  const MddResult d = mddOf(unitCube(), at(0, 0, 0), unitCube(), X_WB, {1, 1, 0});
  EXPECT_NEAR(d.t_lo, -0.5 * std::sqrt(2.0), kTol);
  EXPECT_NEAR(d.t_hi, 0.75 * std::sqrt(2.0), kTol);
  EXPECT_NEAR(d.distance, -0.5 * std::sqrt(2.0), kTol);

  EXPECT_EQ(toiOf(unitCube(), at(0, 0, 0), unitCube(), X_WB, {1, 0, 0}).status, ToiStatus::kInContact);
  EXPECT_EQ(intersect(IntersectInput{&unitCube(), at(0, 0, 0), &unitCube(), X_WB}).status,
            IntersectStatus::kPenetrating);
}

// Penetration shallower than any in the randomized families (1e-3 to 1e-9
// of the size) is penetration, not touching: touching is for the origin
// within the touch tolerance (about 1e-12 of the size) of M's boundary. Blobs
// in random poses; B moved from afar along a random direction to its first
// contact (the brute force's toi), then `depth` further (penetrating) or
// `depth` short of it (separated); exactly there, toi() is in contact. The
// brute force's statuses are asserted too: the placements are what they
// claim.
TEST(Query, ShallowPenetrationIsNotTouching) {
  generators::Rng rng(5);
  int searched = 0;
  for (const double depth : {1e-3, 1e-5, 1e-7, 1e-9}) {
    for (int k = 0; k < 25; ++k) {
      const ConvexPolytope a = ConvexPolytope::fromPoints(generators::blob(20, {1.0, 0.7, 0.5}, rng));
      const ConvexPolytope b = ConvexPolytope::fromPoints(generators::blob(20, {0.6, 0.9, 0.4}, rng));
      Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity();
      X_WA.linear() = generators::randomRotation(rng);
      const Eigen::Vector3d u = generators::randomUnitVector(rng);
      Eigen::Isometry3d X_WB0 = Eigen::Isometry3d::Identity();
      X_WB0.linear() = generators::randomRotation(rng);
      X_WB0.translation() = -5.0 * u;
      const ToiResult first = bruteForceToi(DirectionalInput{&a, X_WA, &b, X_WB0, u});
      ASSERT_EQ(first.status, ToiStatus::kHit);
      const auto status = [&](double t, bool brute) {
        Eigen::Isometry3d X_WB = X_WB0;
        X_WB.pretranslate(t * u);
        const IntersectInput in{&a, X_WA, &b, X_WB};
        if (brute) return bruteForceIntersect(in).status;
        const IntersectResult r = intersect(in);
        searched += r.stats.rays > 0 ? 1 : 0;
        return r.status;
      };
      const std::string where = "depth " + std::to_string(depth) + ", pair " + std::to_string(k);
      EXPECT_EQ(status(first.toi + depth, true), IntersectStatus::kPenetrating) << where;
      EXPECT_EQ(status(first.toi + depth, false), IntersectStatus::kPenetrating) << where;
      EXPECT_EQ(status(first.toi - depth, true), IntersectStatus::kSeparated) << where;
      EXPECT_EQ(status(first.toi - depth, false), IntersectStatus::kSeparated) << where;
      // At the first contact itself B touches A: toi() from there is "in
      // contact" at 0, not a hit at a t of round-off size (a hit is > 0).
      Eigen::Isometry3d X_WB = X_WB0;
      X_WB.pretranslate(first.toi * u);
      const ToiResult at_contact = toi(DirectionalInput{&a, X_WA, &b, X_WB, u});
      EXPECT_EQ(at_contact.status, ToiStatus::kInContact) << where << ", toi " << at_contact.toi;
    }
  }
  // Guard: some answers come from the ray search's exit face, where the
  // touching verdict is decided (3 of the 200; the portal test settles the
  // others).
  EXPECT_GE(searched, 3);
}

TEST(Query, TiltedTriangleVertexOnCubeFace) {
  // The triangle's lowest vertex (0, 0, 1) falls onto the top face z = 0.5.
  const ConvexPolytope tri = ConvexPolytope::fromPoints({{0, 0, 1}, {0, 1, 2}, {1, 0, 2}});
  const MddResult r = mddOf(unitCube(), at(0, 0, 0), tri, at(0, 0, 0), {0, 0, -1});
  EXPECT_EQ(r.status, ContactStatus::kSeparated);
  EXPECT_NEAR(r.distance, 0.5, kTol);
  EXPECT_TRUE(r.contact.point_W.isApprox(Eigen::Vector3d(0, 0, 0.5), kTol));
  EXPECT_TRUE(r.contact.normal_W.isApprox(Eigen::Vector3d(0, 0, 1), kTol));
  EXPECT_EQ(r.contact.feature_a.type, FeatureType::kFace);
  EXPECT_EQ(r.contact.feature_b.type, FeatureType::kVertex);
  EXPECT_TRUE(tri.vertex(r.contact.feature_b.index).isApprox(Eigen::Vector3d(0, 0, 1)));
  // And the cube moving up onto the triangle: the roles swap (vertex-face).
  const MddResult s = mddOf(tri, at(0, 0, 0), unitCube(), at(0, 0, 0), {0, 0, 1});
  EXPECT_NEAR(s.distance, 0.5, kTol);
  EXPECT_EQ(s.contact.feature_a.type, FeatureType::kVertex);
  EXPECT_EQ(s.contact.feature_b.type, FeatureType::kFace);
}

TEST(Query, EdgeOnEdge) {
  // A: the cube turned 45 degrees about y, top edge along y at z = sqrt(2)/2.
  // B: a wedge whose lowest edge runs along x at z = 1.
  Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity();
  X_WA.linear() = Eigen::AngleAxisd(kPi / 4, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const ConvexPolytope wedge = ConvexPolytope::fromPoints({{-1, 0, 1}, {1, 0, 1}, {0, -1, 2}, {0, 1, 2}});
  const MddResult r = mddOf(unitCube(), X_WA, wedge, at(0, 0, 0), {0, 0, -1});
  EXPECT_EQ(r.status, ContactStatus::kSeparated);
  EXPECT_NEAR(r.distance, 1.0 - std::sqrt(0.5), kTol);
  EXPECT_TRUE(r.contact.point_W.isApprox(Eigen::Vector3d(0, 0, std::sqrt(0.5)), kTol));
  EXPECT_TRUE(r.contact.normal_W.isApprox(Eigen::Vector3d(0, 0, 1), kTol));
  EXPECT_EQ(r.contact.feature_a.type, FeatureType::kEdge);
  EXPECT_EQ(r.contact.feature_b.type, FeatureType::kEdge);
}

TEST(Query, CoplanarAndParallelTriangles) {
  const ConvexPolytope tri = ConvexPolytope::fromPoints({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  // Same plane, B two units along x: the line along -x meets M in [1, 3].
  const MddResult in_plane = mddOf(tri, at(0, 0, 0), tri, at(2, 0, 0), {-1, 0, 0});
  EXPECT_EQ(in_plane.status, ContactStatus::kSeparated);
  EXPECT_NEAR(in_plane.distance, 1.0, kTol);
  EXPECT_TRUE(in_plane.contact.point_W.isApprox(Eigen::Vector3d(1, 0, 0), kTol));
  EXPECT_TRUE(in_plane.stats.planar);
  EXPECT_NEAR(toiOf(tri, at(0, 0, 0), tri, at(2, 0, 0), {-1, 0, 0}).toi, 1.0, kTol);
  // Same plane, B's corner on A's (or within the touch tolerance of it): in
  // contact from the start, whichever way B moves, not a hit at t = 0 (the
  // planar path's in-contact test). A micrometre apart: a hit moving in,
  // never moving away.
  for (const double gap : {0.0, 1e-13}) {
    for (const double way : {-1.0, 1.0}) {
      const ToiResult in = toiOf(tri, at(0, 0, 0), tri, at(1 + gap, 0, 0), {way, 0, 0});
      EXPECT_EQ(in.status, ToiStatus::kInContact) << gap << " " << way;
      EXPECT_EQ(in.toi, 0.0) << gap;
      EXPECT_TRUE(in.stats.planar) << gap;
    }
  }
  const ToiResult micro = toiOf(tri, at(0, 0, 0), tri, at(1 + 1e-6, 0, 0), {-1, 0, 0});
  EXPECT_EQ(micro.status, ToiStatus::kHit);
  EXPECT_NEAR(micro.toi, 1e-6, 1e-12);
  EXPECT_EQ(toiOf(tri, at(0, 0, 0), tri, at(1 + 1e-6, 0, 0), {1, 0, 0}).status, ToiStatus::kNever);
  // Overlapping in one plane: touching (flat sets have no interior).
  EXPECT_EQ(mddOf(tri, at(0, 0, 0), tri, at(0.2, 0.2, 0), {1, 0, 0}).status, ContactStatus::kTouching);
  EXPECT_EQ(intersect(IntersectInput{&tri, at(0, 0, 0), &tri, at(0.2, 0.2, 0)}).status, IntersectStatus::kTouching);
  // Parallel planes one unit apart, footprints overlapping: falls by 1.
  const MddResult fall = mddOf(tri, at(0, 0, 0), tri, at(0.1, 0.1, 1), {0, 0, -1});
  EXPECT_EQ(fall.status, ContactStatus::kSeparated);
  EXPECT_NEAR(fall.distance, 1.0, kTol);
  EXPECT_TRUE(fall.contact.normal_W.isApprox(Eigen::Vector3d(0, 0, 1), kTol));
  const IntersectResult apart = intersect(IntersectInput{&tri, at(0, 0, 0), &tri, at(0.1, 0.1, 1)});
  EXPECT_EQ(apart.status, IntersectStatus::kSeparated);
  EXPECT_TRUE(apart.separating_normal_W.isApprox(Eigen::Vector3d(0, 0, 1), kTol));
  // Footprints disjoint: the falling triangle misses.
  EXPECT_EQ(mddOf(tri, at(0, 0, 0), tri, at(2, 2, 1), {0, 0, -1}).status, ContactStatus::kNoContact);
}

TEST(Query, ToiStopsAtMaxDistance) {
  const Eigen::Isometry3d X_WB = at(-3, 0, 0);
  EXPECT_EQ(toiOf(unitCube(), at(0, 0, 0), unitCube(), X_WB, {1, 0, 0}, 1.5).status, ToiStatus::kNever);
  const ToiResult hit = toiOf(unitCube(), at(0, 0, 0), unitCube(), X_WB, {1, 0, 0}, 2.5);
  EXPECT_EQ(hit.status, ToiStatus::kHit);
  EXPECT_NEAR(hit.toi, 2.0, kTol);
}

TEST(Query, IntersectSeparatingNormalProvesSeparation) {
  const IntersectResult r = intersect(IntersectInput{&unitCube(), at(0, 0, 0), &unitCube(), at(-1.2, 0.3, 0)});
  ASSERT_EQ(r.status, IntersectStatus::kSeparated);
  EXPECT_FALSE(r.intersecting);
  double max_a = -1e9;
  double min_b = 1e9;
  for (const Eigen::Vector3d& v : unitCube().vertices()) {
    max_a = std::max(max_a, r.separating_normal_W.dot(v));
    min_b = std::min(min_b, r.separating_normal_W.dot(v + Eigen::Vector3d(-1.2, 0.3, 0)));
  }
  EXPECT_LT(max_a, min_b);
}

TEST(Query, QueriesPrintThemselvesAsJsonLines) {
  const ConvexPolytope tri = ConvexPolytope::fromPoints({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const std::string line = toJsonLine(DirectionalInput{&tri, at(0, 0, 0), &tri, at(0.1, 0, 2), {0, 0, -1}}, "t1");
  EXPECT_EQ(line.rfind(R"({"id": "t1", "a": [[)", 0), 0u);
  EXPECT_NE(line.find("0.10000000000000001"), std::string::npos);  // 17 significant digits
  EXPECT_NE(line.find(R"("direction": [0, 0, -1]})"), std::string::npos);
}

TEST(Query, InvalidInputsThrowOurErrors) {
  const ConvexPolytope& c = unitCube();
  auto message = [](auto&& call) -> std::string {
    try {
      call();
    } catch (const InvalidInputError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(message([&] {
              mdd(DirectionalInput{nullptr, at(0, 0, 0), &c, at(0, 0, 0), {1, 0, 0}});
            }),
            "mdd: polytope A is null");
  EXPECT_EQ(message([&] {
              toi(DirectionalInput{&c, at(0, 0, 0), nullptr, at(0, 0, 0), {1, 0, 0}});
            }),
            "toi: polytope B is null");
  EXPECT_NE(message([&] {
              mdd(DirectionalInput{&c, at(0, 0, 0), &c, at(0, 0, 0), {0, 0, 0}});
            }).find("direction"),
            std::string::npos);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message([&] {
              toi(DirectionalInput{&c, at(0, 0, 0), &c, at(0, 0, 0), {nan, 0, 0}});
            }).find("finite"),
            std::string::npos);
  Eigen::Isometry3d scaled = Eigen::Isometry3d::Identity();
  scaled.linear() *= 2.0;
  EXPECT_NE(message([&] { intersect(IntersectInput{&c, at(0, 0, 0), &c, scaled}); }).find("X_WB"), std::string::npos);
  EXPECT_NE(message([&] {
              mdd(DirectionalInput{&c, at(nan, 0, 0), &c, at(0, 0, 0), {1, 0, 0}});
            }).find("X_WA"),
            std::string::npos);
  EXPECT_NE(message([&] {
              toi(DirectionalInput{&c, at(0, 0, 0), &c, at(0, 0, 0), {1, 0, 0}, nan});
            }).find("max_distance"),
            std::string::npos);
  // Validated poses are remembered by exact value only: a pose one rounding
  // step from a valid one that was just used is still checked in full.
  Eigen::Isometry3d turned = at(0.3, 0.1, 0.2);
  turned.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  EXPECT_NO_THROW(intersect(IntersectInput{&c, at(0, 0, 0), &c, turned}));
  Eigen::Isometry3d stretched = turned;
  stretched.linear() *= 1.0 + 1e-6;
  EXPECT_NE(message([&] {
              intersect(IntersectInput{&c, at(0, 0, 0), &c, stretched});
            }).find("X_WB"),
            std::string::npos);
  Eigen::Isometry3d poisoned = turned;
  poisoned.linear()(1, 2) = nan;
  EXPECT_NE(message([&] { intersect(IntersectInput{&c, at(0, 0, 0), &c, poisoned}); }).find("X_WB"), std::string::npos);
}

// requireFinitePose (public, for callers that test a pose before a
// traversal): says which part is at fault, ignores the last row, and does
// not check rigidity (the pair queries do).
TEST(Query, RequireFinitePoseNamesTheQueryAndThePart) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto message = [](const Eigen::Isometry3d& X) -> std::string {
    try {
      requireFinitePose(X, "the robot pose X_WR", "myQuery");
    } catch (const InvalidInputError& e) {
      return e.what();
    }
    return "no error";
  };
  Eigen::Isometry3d X = at(1, 2, 3);
  EXPECT_EQ(message(X), "no error");
  X.linear() *= 2.0;  // not rigid, but finite
  EXPECT_EQ(message(X), "no error");
  X.matrix()(3, 0) = nan;  // the last row is not part of the pose
  EXPECT_EQ(message(X), "no error");
  X = at(1, std::numeric_limits<double>::infinity(), 3);
  EXPECT_EQ(message(X), "myQuery: the robot pose X_WR has a non-finite translation entry (NaN or infinity)");
  X = at(1, 2, 3);
  X.linear()(2, 1) = nan;
  EXPECT_EQ(message(X), "myQuery: the robot pose X_WR has a non-finite rotation entry (NaN or infinity)");
}

/// A coherent sequence: B slides past A while the direction turns.
std::vector<DirectionalInput> coherentSequence(const ConvexPolytope& a, const ConvexPolytope& b, int n) {
  std::vector<DirectionalInput> out;
  for (int k = 0; k < n; ++k) {
    const double s = 0.01 * k;
    Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
    X_WB.linear() = Eigen::AngleAxisd(0.3 + s, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    X_WB.translation() = Eigen::Vector3d(-6.0 + 4.0 * s, 1.0 - s, 0.5);
    out.push_back(DirectionalInput{&a, Eigen::Isometry3d::Identity(), &b, X_WB,
                                   Eigen::Vector3d(1.0, 0.2 * std::sin(3 * s), 0.1 * std::cos(2 * s))});
  }
  return out;
}

TEST(Query, WarmStartGivesTheColdAnswers) {
  const ConvexPolytope a = ConvexPolytope::fromPoints(generators::paperPolytope("P4"));
  const ConvexPolytope b = ConvexPolytope::fromPoints(generators::paperPolytope("P6"));
  WarmStart warm;
  WarmStart warm_toi;
  int contacts = 0;
  for (const DirectionalInput& in : coherentSequence(a, b, 300)) {
    const MddResult cold = mdd(in);
    const MddResult hot = mdd(in, &warm);
    ASSERT_EQ(cold.status, hot.status);
    if (cold.status != ContactStatus::kNoContact) ++contacts;
    EXPECT_NEAR(cold.distance, hot.distance, 1e-9 * 10) << "step with distance " << cold.distance;
    const ToiResult t_cold = toi(in);
    const ToiResult t_hot = toi(in, &warm_toi);
    EXPECT_EQ(t_cold.status, t_hot.status);
    if (t_cold.status == ToiStatus::kHit) {
      EXPECT_NEAR(t_cold.toi, t_hot.toi, 1e-9 * 10);
    }
  }
  EXPECT_GT(contacts, 200);  // the sequence is not all misses
}

// ---- Warm starts from another pose ------------------------------------------

// Shapes of the warm-start property test: generic hulls, and bodies with
// vertical edges (prisms, boxes, upright triangles), whose edges stay parallel
// under rotations about z, as on the planar mesh configs. The draws of one
// call's arguments are made last argument first, the order GCC evaluated them
// (C++ leaves it unspecified), so that the seeded shapes stay as they were.
ConvexPolytope randomShape(generators::Rng& rng) {
  std::uniform_int_distribution<int> kind(0, 3);
  std::uniform_real_distribution<double> size(0.3, 1.2);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  switch (kind(rng)) {
    case 0: return ConvexPolytope::fromPoints(generators::blob(12, {size(rng), size(rng), size(rng)}, rng));
    case 1: {
      const double height = size(rng);
      const double radius = size(rng);
      return ConvexPolytope::fromPoints(generators::prism(3 + (kind(rng) % 4), radius, height));
    }
    case 2: return ConvexPolytope::fromPoints(generators::box({size(rng), size(rng), size(rng)}));
    default: {
      const double h = size(rng);
      const double y = unit(rng);
      const double x = unit(rng);
      const Eigen::Vector3d p(x, y, 0.0);
      return ConvexPolytope::fromPoints(generators::triangle(p - Eigen::Vector3d(0, 0, h), p + Eigen::Vector3d(0, 0, h),
                                                             generators::drawVector(unit, rng)));
    }
  }
}

// A pose near the origin: mostly a rotation about z (vertical edges stay
// vertical), sometimes any rotation. The translation is drawn z, y, x: the
// order GCC evaluated the constructor's arguments (C++ leaves it unspecified),
// kept so the seeded poses stay as they were.
Eigen::Isometry3d randomPose(generators::Rng& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  const double z = 0.3 * unit(rng);
  const double y = 2.0 * unit(rng);
  const double x = 2.0 * unit(rng);
  X.translation() = Eigen::Vector3d(x, y, z);
  X.linear() = unit(rng) > -0.5 ? Eigen::AngleAxisd(kPi * unit(rng), Eigen::Vector3d::UnitZ()).toRotationMatrix()
                                : generators::randomRotation(rng);
  return X;
}

// A direction roughly from B toward A (so that most queries hit), mostly
// horizontal.
Eigen::Vector3d randomDirection(const Eigen::Isometry3d& X_WB, generators::Rng& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  // y before x, as GCC evaluated the constructor's arguments.
  const double y = unit(rng);
  const double x = unit(rng);
  Eigen::Vector3d s = -X_WB.translation() + 0.8 * Eigen::Vector3d(x, y, 0.0);
  if (unit(rng) > 0.5) s.z() = 0.0;
  return s.squaredNorm() > 1e-6 ? s : Eigen::Vector3d::UnitX();
}

bool sameValue(double cold, double hot) {
  if (std::isnan(cold) || std::isinf(cold)) return std::isnan(cold) ? std::isnan(hot) : cold == hot;
  return std::abs(cold - hot) <= kTol * std::max(1.0, std::abs(cold));
}

// A WarmStart left by queries of the same pair at another pose (as a planner
// leaves it, one per pair) may change the speed only: toi(), mdd() and
// intersect() at the new pose give the cold answers. Found by the mesh
// soundness sweep (QueryRegressions.WarmStartFromAnotherPoseKeepsTheToi).
TEST(Query, WarmStartFromAnotherPoseGivesTheColdAnswers) {
  generators::Rng rng(20261124);
  constexpr int kPairs = 3000;
  int hits = 0;
  for (int k = 0; k < kPairs; ++k) {
    const ConvexPolytope a = randomShape(rng);
    const ConvexPolytope b = randomShape(rng);
    const Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity();
    const Eigen::Isometry3d X_WB1 = randomPose(rng);
    const Eigen::Isometry3d X_WB2 = randomPose(rng);
    const DirectionalInput p1{&a, X_WA, &b, X_WB1, randomDirection(X_WB1, rng)};
    const DirectionalInput p2{&a, X_WA, &b, X_WB2, randomDirection(X_WB2, rng)};
    // Every query fills its part of the warm start at P1.
    WarmStart warm_p1;
    toi(p1, &warm_p1);
    mdd(p1, &warm_p1);
    intersect(IntersectInput{&a, X_WA, &b, X_WB1}, &warm_p1);
    const std::string where = "pair " + std::to_string(k) + ": " + toJsonLine(p2);

    WarmStart warm = warm_p1;
    const ToiResult t_cold = toi(p2);
    const ToiResult t_hot = toi(p2, &warm);
    EXPECT_EQ(t_cold.status, t_hot.status) << where;
    EXPECT_TRUE(sameValue(t_cold.toi, t_hot.toi)) << where << "\n  cold " << t_cold.toi << " warm " << t_hot.toi;
    if (t_cold.status == ToiStatus::kHit) ++hits;

    warm = warm_p1;
    const MddResult m_cold = mdd(p2);
    const MddResult m_hot = mdd(p2, &warm);
    EXPECT_EQ(m_cold.status, m_hot.status) << where;
    EXPECT_TRUE(sameValue(m_cold.distance, m_hot.distance))
        << where << "\n  cold " << m_cold.distance << " warm " << m_hot.distance;

    warm = warm_p1;
    const IntersectInput i2{&a, X_WA, &b, X_WB2};
    EXPECT_EQ(intersect(i2).status, intersect(i2, &warm).status) << where;
    if (::testing::Test::HasFailure()) break;  // one pair's report is enough
  }
  EXPECT_GT(hits, kPairs / 3);  // most pairs reach a contact: the searches ran
}

TEST(Query, ConcurrentQueriesGiveTheSameAnswers) {
  const ConvexPolytope a = ConvexPolytope::fromPoints(generators::paperPolytope("P3"));
  const ConvexPolytope b = ConvexPolytope::fromPoints(generators::paperPolytope("P5"));
  const std::vector<DirectionalInput> inputs = coherentSequence(a, b, 400);
  std::vector<double> expected;
  for (const DirectionalInput& in : inputs) expected.push_back(toi(in).toi);
  // Guard: most queries hit (a finite toi), so the threads' searches run.
  const auto hits = std::count_if(expected.begin(), expected.end(), [](double t) { return std::isfinite(t); });
  EXPECT_GE(hits, static_cast<long>(inputs.size() / 2));
  std::vector<int> mismatches(4, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      WarmStart warm;
      for (size_t k = 0; k < inputs.size(); ++k) {
        const double cold = toi(inputs[k]).toi;
        const double hot = toi(inputs[k], &warm).toi;
        if (cold != expected[k] || std::abs(hot - expected[k]) > 1e-8) ++mismatches[t];
      }
    });
  }
  for (std::thread& th : threads) th.join();
  for (int t = 0; t < 4; ++t) EXPECT_EQ(mismatches[t], 0) << "thread " << t;
}

}  // namespace
}  // namespace mddual
