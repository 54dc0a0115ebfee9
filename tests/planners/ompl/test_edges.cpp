// Edges as values (edges.h): translation edges and extended edges equal the
// EdgeMotion built by hand, first contacts of extended edges in closed form
// (a box moving toward a wall, a rod turning toward a wall), bad inputs throw.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "mddual/error.h"
#include "mddual/planning/clearance.h"
#include "mddual/planning/edges.h"
#include "mddual/planning/example_scenes.h"
#include "test_support.h"

namespace mddual::planning {
namespace {

using testing::kInf;
using testing::kNaN;
/// Round-off allowed on exact fractions and poses (relative to scene sizes of ~10).
constexpr double kExactTol = 1e-9;

std::vector<Eigen::Vector3d> boxCorners(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < 8; ++i) {
    out.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  }
  return out;
}

/// A robot box (corners lo, hi in frame R) and one wall box in the world.
std::shared_ptr<const MddScene> boxAndWall(const Eigen::Vector3d& robot_lo, const Eigen::Vector3d& robot_hi,
                                           const Eigen::Vector3d& wall_lo, const Eigen::Vector3d& wall_hi) {
  auto robot = std::make_shared<scene::RigidBody>(
      std::vector<scene::Piece>{examples::convexPiece(boxCorners(robot_lo, robot_hi), "robot box")}, "robot");
  auto world = std::make_shared<scene::World>(
      std::vector<scene::Piece>{examples::convexPiece(boxCorners(wall_lo, wall_hi), "wall")}, "world");
  return std::make_shared<const MddScene>(robot, world);
}

Eigen::Isometry3d poseAt(const Eigen::Vector3d& p, double yaw = 0.0) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = p;
  return X;
}

using testing::poseError;

TEST(Edges, TranslationEdgeEqualsTheHandBuiltMotion) {
  const Eigen::Isometry3d X = poseAt(Eigen::Vector3d(1, 2, 3), 0.7);
  const EdgeMotion m = translationEdge(X, Eigen::Vector3d(0, 3, 4), 2.5);  // |d| = 5
  EdgeMotion hand;
  hand.p_start = Eigen::Vector3d(1, 2, 3);
  hand.p_end = Eigen::Vector3d(1, 2 + 1.5, 3 + 2.0);
  hand.R_start = X.linear();
  hand.q_start = Eigen::Quaterniond(X.linear());
  hand.X_end = poseAt(hand.p_end, 0.7);
  EXPECT_LT((m.p_start - hand.p_start).norm(), kExactTol);
  EXPECT_LT((m.p_end - hand.p_end).norm(), kExactTol);
  EXPECT_LT((m.R_start - hand.R_start).norm(), kExactTol);
  EXPECT_LT(m.q_start.angularDistance(hand.q_start), kExactTol);
  EXPECT_EQ(m.angle, 0.0);
  EXPECT_FALSE(m.rotates());
  EXPECT_FALSE(m.endDiffers());
  EXPECT_LT(poseError(m.X_end, hand.X_end), kExactTol);
  EXPECT_NEAR(m.length(), 2.5, kExactTol);
}

// A unit cube (half side 0.5) at the origin moving along +x toward a wall at
// x in [5, 6]: it touches after 4.5; turned by 45 degrees about z, after
// 5 - 0.5 sqrt(2).
TEST(Edges, ExtendedTranslationEdgeHitsTheWallInClosedForm) {
  const auto scene = boxAndWall(Eigen::Vector3d::Constant(-0.5), Eigen::Vector3d::Constant(0.5),
                                Eigen::Vector3d(5, -5, -5), Eigen::Vector3d(6, 5, 5));
  for (const double yaw : {0.0, kPi / 4}) {
    const double touch = yaw == 0.0 ? 4.5 : 5.0 - 0.5 * std::sqrt(2.0);
    const EdgeMotion edge = translationEdge(poseAt(Eigen::Vector3d::Zero(), yaw), Eigen::Vector3d::UnitX(), 2.0);
    EXPECT_FALSE(edgeContact(*scene, edge).collides);
    for (const double factor : {3.0, 5.0}) {
      const EdgeContact c = edgeContact(*scene, extendedEdge(edge, factor));
      ASSERT_TRUE(c.collides) << "factor " << factor;
      EXPECT_TRUE(c.exact);
      EXPECT_FALSE(c.start_collides);
      EXPECT_NEAR(c.fraction * 2.0 * factor, touch, kExactTol) << "yaw " << yaw << " factor " << factor;
      EXPECT_NEAR(c.contact.p_WC.x(), 5.0, kExactTol);
    }
    // The same as the directed clearance along the edge.
    EXPECT_NEAR(directedClearance(*scene, poseAt(Eigen::Vector3d::Zero(), yaw), Eigen::Vector3d::UnitX()).distance,
                touch, kExactTol);
    // Too short to reach the wall.
    EXPECT_FALSE(edgeContact(*scene, extendedEdge(edge, 0.99 * touch / 2.0)).collides);
  }
}

TEST(Edges, ExtendedEdgeEqualsTheHandBuiltMotion) {
  EdgeMotion m;
  m.p_start = Eigen::Vector3d(1, -2, 0.5);
  m.p_end = Eigen::Vector3d(2, 0, 1.5);
  m.q_start = Eigen::Quaterniond(Eigen::AngleAxisd(0.8, Eigen::Vector3d(1, 2, 3).normalized()));
  m.R_start = m.q_start.toRotationMatrix();
  m.axis_R = Eigen::Vector3d(-1, 0.5, 2).normalized();
  m.angle = 0.6;
  m.X_end = m.pose(1.0);
  for (const double factor : {0.5, 1.0, 2.5, 7.0}) {
    const EdgeMotion e = extendedEdge(m, factor);
    EdgeMotion hand = m;
    hand.p_end = m.p_start + factor * (m.p_end - m.p_start);
    hand.angle = factor * m.angle;
    EXPECT_EQ(e.p_start, hand.p_start);
    EXPECT_LT((e.p_end - hand.p_end).norm(), kExactTol);
    EXPECT_EQ(e.axis_R, hand.axis_R);
    EXPECT_EQ(e.R_start, hand.R_start);
    EXPECT_NEAR(e.angle, hand.angle, kExactTol);
    EXPECT_FALSE(e.endDiffers());
    EXPECT_LT(poseError(e.X_end, hand.pose(1.0)), kExactTol);
    // e at t is m at factor t: the same motion, the same speeds.
    for (const double t : {0.0, 0.1, 0.37, 0.5, 1.0}) {
      EXPECT_LT(poseError(e.pose(t), m.pose(factor * t)), kExactTol) << "factor " << factor << " t " << t;
    }
  }
}

// A rod (half length 1, half width 0.05) turning about z at the origin toward
// a wall y >= 0.6: the corner (1, 0.05) reaches it at theta* with sin(theta)
// + 0.05 cos(theta) = 0.6. The edge turns 0.3 rad (free); extended 3 times,
// 0.9 rad, it hits. Rotating edges give a lower bound of the contact, within
// the rotating scheme's enlargement (at most 1.73 delta / 8 of the rod at the
// default 3 refinements, about 4.5e-3; over the lever arm 1 cos(theta*) ~ 0.8,
// under 6e-3 rad).
TEST(Edges, ExtendedRotatingEdgeHitsTheWallNearTheClosedForm) {
  constexpr double kHalfWidth = 0.05;
  constexpr double kWallY = 0.6;
  constexpr double kRotatingTol = 0.02;  // rad; the bound above with margin
  const auto scene =
      boxAndWall(Eigen::Vector3d(-1, -kHalfWidth, -kHalfWidth), Eigen::Vector3d(1, kHalfWidth, kHalfWidth),
                 Eigen::Vector3d(-3, kWallY, -1), Eigen::Vector3d(3, kWallY + 1, 1));
  const double theta_star = std::asin(kWallY / std::sqrt(1.0 + kHalfWidth * kHalfWidth)) - std::atan(kHalfWidth);
  EdgeMotion edge;  // in place, about +z of the body
  edge.angle = 0.3;
  edge.X_end = edge.pose(1.0);
  EXPECT_FALSE(edgeContact(*scene, edge).collides);
  const EdgeContact c = edgeContact(*scene, extendedEdge(edge, 3.0));
  ASSERT_TRUE(c.collides);
  EXPECT_FALSE(c.exact);
  const double theta = c.fraction * 0.9;
  EXPECT_LE(theta, theta_star + kExactTol);
  EXPECT_GE(theta, theta_star - kRotatingTol);
  // Turning 0.95 theta* is free (clearance ~ 0.03, far above the enlargement).
  EXPECT_FALSE(edgeContact(*scene, extendedEdge(edge, 0.95 * theta_star / 0.3)).collides);
}

template <typename F>
void expectInvalid(F&& f, const std::string& part) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one containing '" << part << "'";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(Edges, BadInputsThrow) {
  const Eigen::Isometry3d X = poseAt(Eigen::Vector3d(1, 2, 3), 0.3);
  const Eigen::Vector3d d = Eigen::Vector3d::UnitX();
  Eigen::Isometry3d nan_pose = X;
  nan_pose.translation().x() = kNaN;
  expectInvalid([&] { translationEdge(nan_pose, d, 1.0); }, "X_WR is not finite");
  Eigen::Isometry3d scaled = X;
  scaled.linear() *= 2.0;
  expectInvalid([&] { translationEdge(scaled, d, 1.0); }, "not a rotation");
  expectInvalid([&] { translationEdge(X, Eigen::Vector3d::Zero(), 1.0); }, "direction is zero or not finite");
  expectInvalid([&] { translationEdge(X, Eigen::Vector3d(kNaN, 0, 0), 1.0); }, "direction is zero or not finite");
  expectInvalid([&] { translationEdge(X, d, -1.0); }, "negative or not finite");
  expectInvalid([&] { translationEdge(X, d, kNaN); }, "negative or not finite");
  expectInvalid([&] { translationEdge(X, d, kInf); }, "negative or not finite");
  EXPECT_EQ(translationEdge(X, d, 0.0).length(), 0.0);  // a single state is fine

  const EdgeMotion edge = translationEdge(X, d, 1.0);
  for (const double factor : {0.0, -1.0, kNaN, kInf}) {
    expectInvalid([&] { extendedEdge(edge, factor); }, "is not finite and positive");
  }
  EdgeMotion bad = edge;
  bad.p_end.y() = kNaN;
  expectInvalid([&] { extendedEdge(bad, 2.0); }, "non-finite fields");
  bad = edge;
  bad.angle = -0.1;
  expectInvalid([&] { extendedEdge(bad, 2.0); }, "angle -0.1");
  bad = edge;
  bad.angle = 0.1;
  bad.axis_R = Eigen::Vector3d(0, 0, 2);
  expectInvalid([&] { extendedEdge(bad, 2.0); }, "rotation axis is not a unit vector");
  bad = edge;
  bad.R_start *= 2.0;
  expectInvalid([&] { extendedEdge(bad, 2.0); }, "R_start is not a rotation");
}

}  // namespace
}  // namespace mddual::planning
