// Directed clearance against the brute force (the Minkowski difference built
// explicitly, per pair, with its own candidate selection), and edge contacts
// against directed clearance and a dense check.
#include <gtest/gtest.h>

#include <ompl/base/ScopedState.h>
#include <cmath>
#include <limits>

#include "mddual/brute_force.h"
#include "mddual/generators.h"
#include "mddual/planning/clearance.h"
#include "test_support.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;
using testing::Fixture;
using testing::kInf;

/// Brute-force reference of directedClearance(): every pair whose bounding
/// spheres can meet along the line, toi (free start) or mdd (colliding pairs).
struct Reference {
  double distance = kInf;
  bool start_collides = false;
};
Reference reference(const MddScene& scene, const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& u) {
  Reference ref;
  // Colliding pairs first (their bounding spheres overlap at X_WR).
  double deepest = 0.0;
  for (const scene::Piece& piece : scene.robot().pieces()) {
    const Eigen::Vector3d c = X_WR * piece.centre;
    for (const scene::Piece& obstacle : scene.world().pieces()) {
      if ((obstacle.centre - c).norm() > 1.001 * (piece.radius + obstacle.radius)) continue;
      const BruteForce bf(&obstacle.polytope, Eigen::Isometry3d::Identity(), &piece.polytope, X_WR);
      if (!bf.intersect().intersecting) continue;
      ref.start_collides = true;
      const MddResult r = bf.mdd(u);
      deepest = std::min(deepest, std::isfinite(r.distance) ? std::min(r.distance, 0.0) : 0.0);
    }
  }
  if (ref.start_collides) {
    ref.distance = deepest;
    return ref;
  }
  // Free: every pair whose spheres can meet moving forward along u.
  for (const scene::Piece& piece : scene.robot().pieces()) {
    const Eigen::Vector3d c = X_WR * piece.centre;
    for (const scene::Piece& obstacle : scene.world().pieces()) {
      const Eigen::Vector3d w = obstacle.centre - c;
      const double reach = 1.001 * (piece.radius + obstacle.radius);
      if ((w - w.dot(u) * u).norm() > reach || w.dot(u) < -reach) continue;
      const BruteForce bf(&obstacle.polytope, Eigen::Isometry3d::Identity(), &piece.polytope, X_WR);
      const ToiResult t = bf.toi(u);
      if (t.status == ToiStatus::kHit) ref.distance = std::min(ref.distance, t.toi);
    }
  }
  return ref;
}

/// Largest violation of the world piece's face planes by p (0 on or inside).
double outside(const scene::Piece& piece, const Eigen::Vector3d& p) {
  double worst = -kInf;
  for (int f = 0; f < piece.polytope.numFaces(); ++f) {
    worst = std::max(worst, piece.polytope.faceNormal(f).dot(p) - piece.polytope.faceOffset(f));
  }
  return worst;
}

class Clearance : public ::testing::TestWithParam<int> {};

TEST_P(Clearance, MatchesTheBruteForce) {
  const examples::ExampleScene scene = testing::standardScenes(testing::seed())[static_cast<std::size_t>(GetParam())];
  const Fixture fx = testing::makeFixture(scene);
  testing::Rng rng(testing::seed() * 31 + static_cast<std::uint64_t>(GetParam()));
  ob::ScopedState<> s(fx.space->stateSpace());
  const int n = (GetParam() == 1 ? 25 : 60) * testing::scale();  // the mesh's reference is slow
  int hits = 0, colliding = 0;
  for (int i = 0; i < n; ++i) {
    testing::randomState(*fx.space, rng, s.get());
    // The length before the direction: the order GCC evaluated the operands of
    // the product (C++ leaves them unsequenced), kept so the samples stay.
    const double length = std::uniform_real_distribution<double>(0.1, 10.0)(rng);
    Eigen::Vector3d d = generators::randomUnitVector(rng) * length;
    if (fx.space->kind() == SpaceKind::kSE2) d.z() = 0.0;
    const Eigen::Isometry3d X = fx.space->pose(s.get());
    const DirectedClearance c = directedClearance(*fx.mdd, *fx.space, s.get(), d);
    const Reference ref = reference(*fx.mdd, X, d.normalized());
    const double tol = 1e-9 * (1.0 + X.translation().norm() + scene.robot->radius());
    EXPECT_EQ(c.start_collides, ref.start_collides) << scene.name << " state " << i;
    if (ref.distance == kInf) {
      EXPECT_EQ(c.distance, kInf) << scene.name << " state " << i;
    } else {
      EXPECT_NEAR(c.distance, ref.distance, tol) << scene.name << " state " << i;
    }
    colliding += c.start_collides;
    if (c.start_collides || c.distance == kInf) continue;
    ++hits;
    // The contact: a point of the world piece, the normal from it toward the robot.
    ASSERT_GE(c.contact.world_piece, 0);
    ASSERT_GE(c.contact.robot_piece, 0);
    const scene::Piece& obstacle = scene.world->pieces()[static_cast<std::size_t>(c.contact.world_piece)];
    EXPECT_LT(std::abs(outside(obstacle, c.contact.p_WC)), 1e-8 * (1.0 + c.contact.p_WC.norm()))
        << "contact point off the world piece";
    EXPECT_NEAR(c.contact.n_W.norm(), 1.0, 1e-12);
    EXPECT_LE(c.contact.n_W.dot(d), 1e-12);  // the robot moves against the normal
    // Just short of the contact the robot is free; at it, touching.
    Eigen::Isometry3d before = X;
    before.translation() += (c.distance - 1e-6) * d.normalized();
    EXPECT_FALSE(fx.mdd->collides(before));
    // A limit below the contact: nothing.
    EXPECT_EQ(directedClearance(*fx.mdd, X, d, 0.5 * c.distance).distance, kInf);
  }
  std::printf("%-10s clearance: %d states, %d hits, %d colliding starts\n", scene.name.c_str(), n, hits, colliding);
  EXPECT_GT(hits, n / 10);
}

INSTANTIATE_TEST_SUITE_P(Scenes, Clearance, ::testing::Values(0, 1, 2, 3), testing::sceneParamName);

TEST(Clearance, PenetrationDepthOfAnOverlap) {
  // A unit cube sunk 0.3 into a slab (top at z = 0): straight up it must
  // move 0.3 to separate; straight down, 0.3 the short way too (back up).
  std::vector<Eigen::Vector3d> slab = generators::box({5, 5, 0.5});
  for (Eigen::Vector3d& p : slab) p.z() -= 0.5;
  auto world = std::make_shared<scene::World>(std::vector<scene::Piece>{examples::convexPiece(slab, "slab")}, "slab");
  auto robot = std::make_shared<scene::RigidBody>(
      std::vector<scene::Piece>{examples::convexPiece(generators::box({0.5, 0.5, 0.5}), "cube")}, "cube");
  const MddScene mdd(robot, world);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(0, 0, 0.2);  // bottom at -0.3
  const DirectedClearance up = directedClearance(mdd, X, Eigen::Vector3d(0, 0, 2));
  EXPECT_TRUE(up.start_collides);
  EXPECT_NEAR(up.distance, -0.3, 1e-12);
  EXPECT_EQ(up.contact.world_piece, 0);
  EXPECT_NEAR(directedClearance(mdd, X, Eigen::Vector3d(0, 0, -1)).distance, -0.3, 1e-12);
  // Free above: the exact gap, with the contact on the slab's top face.
  X.translation().z() = 1.25;
  const DirectedClearance down = directedClearance(mdd, X, Eigen::Vector3d(0, 0, -1));
  EXPECT_FALSE(down.start_collides);
  EXPECT_NEAR(down.distance, 0.75, 1e-12);
  EXPECT_NEAR(down.contact.p_WC.z(), 0.0, 1e-12);
  EXPECT_NEAR(down.contact.n_W.z(), 1.0, 1e-12);
  EXPECT_EQ(directedClearance(mdd, X, Eigen::Vector3d(0, 0, 1)).distance, kInf);
  // Touching: 0, and it counts as colliding.
  X.translation().z() = 0.5;
  const DirectedClearance touch = directedClearance(mdd, X, Eigen::Vector3d(1, 0, 0));
  EXPECT_TRUE(touch.start_collides);
  EXPECT_EQ(touch.distance, 0.0);
}

TEST(Clearance, EdgeContactAgreesWithDirectedClearance) {
  const examples::ExampleScene scene = examples::blobScene(testing::seed());
  const Fixture fx = testing::makeFixture(scene);
  testing::Rng rng(testing::seed() + 99);
  ob::ScopedState<> s1(fx.space->stateSpace()), s2(fx.space->stateSpace());
  int compared = 0;
  for (int i = 0; i < 200 * testing::scale(); ++i) {
    testing::randomValidState(*fx.si, *fx.space, rng, s1.get());
    testing::randomEdgeEnd(*fx.space, s1.get(), 12.0, false, 0.0, rng, s2.get());
    const EdgeContact e = edgeContact(*fx.mdd, *fx.space, s1.get(), s2.get());
    const EdgeMotion m = fx.space->motion(s1.get(), s2.get());
    if (m.length() == 0.0) continue;
    const DirectedClearance c = directedClearance(*fx.mdd, m.pose(0), m.p_end - m.p_start);
    EXPECT_TRUE(e.exact);
    if (c.distance > m.length()) {
      EXPECT_FALSE(e.collides);
      continue;
    }
    ++compared;
    ASSERT_TRUE(e.collides);
    EXPECT_NEAR(e.fraction * m.length(), c.distance, 1e-9 * m.length());
    EXPECT_EQ(e.contact.world_piece, c.contact.world_piece);
    EXPECT_EQ(e.contact.robot_piece, c.contact.robot_piece);
  }
  EXPECT_GT(compared, 20);
}

}  // namespace
}  // namespace mddual::planning
