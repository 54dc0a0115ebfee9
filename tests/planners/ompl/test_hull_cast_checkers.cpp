// HullCastMotionValidator, the Bullet peer baseline (swept hulls of the end
// poses of OMPL's segments, as Tesseract's continuous motion validator):
// exact on translation edges; the whole-edge cast misses a link turning past
// an obstacle inside its arc, which the segments see; a thin obstacle in the
// sliver between a segment's arc and chord is missed even so, and
// MddMotionValidator catches both. The arm cast (ArmHullCastMotionValidator)
// on a planar arm: the same two cases, an obstacle at the edge's end pose
// that every checker sees, and the self pairs.
#include <gtest/gtest.h>

#include <ompl/base/ScopedState.h>
#include <cmath>
#include <memory>
#include <vector>

#include "mddual/constants.h"
#include "mddual/error.h"
#include "mddual/generators.h"
#include "mddual/planning/dense_contact.h"
#include "mddual/planning/example_scenes.h"
#include "mddual/planning/hull_cast_checkers.h"
#include "mddual/planning/mdd_checkers.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;

scene::Piece boxPiece(const Eigen::Vector3d& half, const Eigen::Vector3d& centre) {
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector3d& p : generators::box(half)) points.push_back(p + centre);
  return examples::convexPiece(points, "box");
}

/// Both validators on one space over the same robot and world.
struct Validators {
  PlanningSpacePtr space;
  ob::SpaceInformationPtr si;
  HullCastMotionValidatorPtr hull;
  MddMotionValidatorPtr mdd;
  std::shared_ptr<const HullCastScene> cast;
};

Validators makeSetup(SpaceKind kind, std::vector<scene::Piece> robot, std::vector<scene::Piece> world) {
  Validators s;
  s.space =
      PlanningSpace::make(kind, Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-10), Eigen::Vector3d::Constant(10)));
  auto r = std::make_shared<scene::RigidBody>(std::move(robot), "robot");
  auto w = std::make_shared<scene::World>(std::move(world), "world");
  s.si = std::make_shared<ob::SpaceInformation>(s.space->stateSpace());
  auto mdd_scene = std::make_shared<MddScene>(r, w);
  s.si->setStateValidityChecker(std::make_shared<MddStateValidityChecker>(s.si, s.space, mdd_scene));
  s.mdd = std::make_shared<MddMotionValidator>(s.si, s.space, mdd_scene);
  s.cast = std::make_shared<const HullCastScene>(r, w);
  s.hull = std::make_shared<HullCastMotionValidator>(s.si, s.space, s.cast);
  s.si->setMotionValidator(s.mdd);
  s.si->setup();
  return s;
}

Eigen::Isometry3d at(const Eigen::Vector3d& p, double yaw = 0.0) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = p;
  return X;
}

TEST(HullCast, TranslationAgreesWithTheExactAnswer) {
  // A unit cube robot; a unit cube obstacle at x = 5.
  Validators s = makeSetup(SpaceKind::kR3, {boxPiece(Eigen::Vector3d::Constant(0.5), Eigen::Vector3d::Zero())},
                           {boxPiece(Eigen::Vector3d::Constant(0.5), Eigen::Vector3d(5, 0, 0))});
  ob::ScopedState<> a(s.space->stateSpace()), b(s.space->stateSpace());
  // Through the obstacle: colliding for both.
  s.space->setPose(at({0, 0, 0}), a.get());
  s.space->setPose(at({9, 0, 0}), b.get());
  EXPECT_FALSE(s.hull->checkMotion(a.get(), b.get()));
  EXPECT_FALSE(s.mdd->checkMotion(a.get(), b.get()));
  // Parallel, 1 apart: free for both.
  s.space->setPose(at({0, 2, 0}), a.get());
  s.space->setPose(at({9, 2, 0}), b.get());
  EXPECT_TRUE(s.hull->checkMotion(a.get(), b.get()));
  EXPECT_TRUE(s.mdd->checkMotion(a.get(), b.get()));
  // Parallel at 1e-3 and overlapping by 1e-3.
  s.space->setPose(at({0, 1.001, 0}), a.get());
  s.space->setPose(at({9, 1.001, 0}), b.get());
  EXPECT_TRUE(s.hull->checkMotion(a.get(), b.get()));
  s.space->setPose(at({0, 0.999, 0}), a.get());
  s.space->setPose(at({9, 0.999, 0}), b.get());
  EXPECT_FALSE(s.hull->checkMotion(a.get(), b.get()));
  EXPECT_EQ(s.hull->counts().motion_checks, 4u);
}

TEST(HullCast, LastValidIsTheStartOfTheFirstFailingSegment) {
  Validators s = makeSetup(SpaceKind::kR3, {boxPiece(Eigen::Vector3d::Constant(0.5), Eigen::Vector3d::Zero())},
                           {boxPiece(Eigen::Vector3d::Constant(0.5), Eigen::Vector3d(5, 0, 0))});
  ob::ScopedState<> a(s.space->stateSpace()), b(s.space->stateSpace()), last(s.space->stateSpace());
  ob::ScopedState<> expected(s.space->stateSpace());
  s.space->setPose(at({0, 0, 0}), a.get());
  s.space->setPose(at({9, 0, 0}), b.get());
  const unsigned n = s.space->stateSpace()->validSegmentCount(a.get(), b.get());
  ASSERT_GT(n, 9u);  // segments shorter than the gap of 4 / 9 before the contact
  std::pair<ob::State*, double> lastValid(last.get(), -1.0);
  EXPECT_FALSE(s.hull->checkMotion(a.get(), b.get(), lastValid));
  // The cubes touch at x = 4 (t = 4 / 9): lastValid is the segment start just before.
  const double contact = 4.0 / 9.0;
  EXPECT_LE(lastValid.second, contact);
  EXPECT_GT(lastValid.second, contact - 1.0 / n);
  s.space->stateSpace()->interpolate(a.get(), b.get(), lastValid.second, expected.get());
  EXPECT_TRUE(s.space->stateSpace()->equalStates(last.get(), expected.get()));
  EXPECT_THROW(HullCastMotionValidator(s.si, s.space, nullptr), InvalidInputError);
}

/// A link 2 long and 2 half_width wide turning 90 degrees about one end
/// (SE(2)) past `obstacle`; a, b the ends, mid the pose at `mid_angle`.
struct TurningLink {
  Validators s;
  ob::ScopedState<> a, b, mid;
  explicit TurningLink(const scene::Piece& obstacle, double mid_angle = kPi / 4, double half_width = 0.05)
      : s(makeSetup(SpaceKind::kSE2, {boxPiece({1.0, half_width, 0.25}, {1.0, 0, 0})}, {obstacle})),
        a(s.space->stateSpace()),
        b(s.space->stateSpace()),
        mid(s.space->stateSpace()) {
    s.space->setPose(at({0, 0, 0}, 0.0), a.get());
    s.space->setPose(at({0, 0, 0}, kPi / 2), b.get());
    s.space->setPose(at({0, 0, 0}, mid_angle), mid.get());
  }
};

/// A box of half extents `half` (radial, tangential, z) centred at `radius`
/// along the direction at `angle` about z, its radial axis along it.
scene::Piece radialBox(double angle, double radius, const Eigen::Vector3d& half) {
  const Eigen::AngleAxisd R(angle, Eigen::Vector3d::UnitZ());
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector3d& p : generators::box(half)) points.push_back(R * (p + Eigen::Vector3d(radius, 0, 0)));
  return examples::convexPiece(points, "obstacle");
}

// The whole-edge cast's known failure, pinned: a small box on the arc's
// bisector at radius 1.7 to 1.9. The hull of the two end poses reaches only
// 2 cos(45 deg) + 0.05 sin(45 deg) = 1.45 along the bisector, so one cast
// between the ends (MoveIt's cast between two states) calls the edge free;
// the link passes through the box at 45 degrees. The validator's segments
// (OMPL's resolution) are short enough to see it.
TEST(HullCast, SegmentsSeeAnObstacleTheWholeEdgeCastMisses) {
  TurningLink c(radialBox(kPi / 4, 1.8, {0.1, 0.1, 0.5}));
  ASSERT_TRUE(c.s.si->isValid(c.a.get()));
  ASSERT_TRUE(c.s.si->isValid(c.b.get()));
  ASSERT_FALSE(c.s.si->isValid(c.mid.get()));  // a real collision on the edge
  EXPECT_FALSE(c.s.cast->castCollides(c.s.space->pose(c.a.get()), c.s.space->pose(c.b.get())))
      << "the whole-edge cast now sees the arc: update the docs";
  EXPECT_FALSE(c.s.hull->checkMotion(c.a.get(), c.b.get()));
  EXPECT_FALSE(c.s.mdd->checkMotion(c.a.get(), c.b.get()));
}

// What the segments still miss, on a thin link (0.004 wide): a segment
// turning 2 alpha about the link's end has a hull reaching
// h = 2 cos(alpha) + 0.002 sin(alpha) along its bisector, short of the
// link's reach of 2. A box beyond h on the bisector of the middle segment is
// outside every segment's hull, and the link passes through it there.
TEST(HullCast, MissesAThinObstacleBetweenArcAndChord) {
  const TurningLink probe(radialBox(kPi, 5.0, {0.1, 0.1, 0.1}));  // only to count the segments
  const unsigned n = probe.s.space->stateSpace()->validSegmentCount(probe.a.get(), probe.b.get());
  ASSERT_GE(n, 2u);
  const double alpha = kPi / 4 / n;
  const double bisector = kPi / 2 * (n / 2 + 0.5) / n;
  const double h = 2.0 * std::cos(alpha) + 0.002 * std::sin(alpha);
  const double r0 = h + 5e-5, r1 = 2.05;
  ASSERT_LT(r0, 2.0) << "no sliver between arc and chord at " << n << " segments";
  TurningLink c(radialBox(bisector, (r0 + r1) / 2, {(r1 - r0) / 2, 0.02, 0.5}), bisector, 0.002);
  ASSERT_TRUE(c.s.si->isValid(c.a.get()));
  ASSERT_TRUE(c.s.si->isValid(c.b.get()));
  ASSERT_FALSE(c.s.si->isValid(c.mid.get()));
  EXPECT_TRUE(c.s.hull->checkMotion(c.a.get(), c.b.get())) << "the segments now see the sliver: update the docs";
  EXPECT_FALSE(c.s.mdd->checkMotion(c.a.get(), c.b.get()));
}

// ---- Arms ------------------------------------------------------------------------

/// The planar arm of two 1 m links (examples::planarArm) over one world box,
/// with the exact arm checkers and the arm cast on one space.
struct ArmValidators {
  std::shared_ptr<const ArmScene> scene;
  ArmSpacePtr space;
  ob::SpaceInformationPtr si;
  ArmMotionValidatorPtr mdd;
  ArmHullCastMotionValidatorPtr hull;
  std::shared_ptr<const FclArmScene> fcl;
};

ArmValidators makeArmSetup(const scene::Piece& obstacle, double half_width = 0.05) {
  const examples::PlanarArm arm = examples::planarArm({1.0, 1.0}, half_width, 0.05);
  std::vector<scene::Piece> world{obstacle};
  ArmValidators s;
  s.scene = std::make_shared<const ArmScene>(arm.model, std::make_shared<const scene::World>(std::move(world), "world"),
                                             arm.filter);
  s.space = ArmSpace::make(arm.model, {0, 1});
  s.si = std::make_shared<ob::SpaceInformation>(s.space->stateSpace());
  const ArmChecking exact = useExactChecking(s.si, s.space, s.scene);
  s.mdd = exact.motion_validator;
  s.hull = std::make_shared<ArmHullCastMotionValidator>(s.si, s.space, std::make_shared<ArmHullCastScene>(s.scene));
  s.fcl = std::make_shared<const FclArmScene>(s.scene);
  s.si->setup();
  return s;
}

// Joint 1 turns from -45 to +45 degrees with joint 2 straight: the tip's arc
// reaches x = 2 on the bisector, the hull of the two end poses of link 2 only
// 2 cos(45 deg) + 0.05 sin(45 deg) = 1.45. A box at x in [1.65, 1.85] is
// inside the arc and outside that hull: the arm passes through it at t = 0.5,
// the certified check refuses the edge, one cast between the ends calls it
// free (the peer's known miss, hull_cast_checkers.h and docs/arms.md), the
// validator's segments see it.
TEST(ArmHullCast, SegmentsSeeAnObstacleTheWholeEdgeCastMisses) {
  const ArmValidators s = makeArmSetup(boxPiece({0.1, 0.1, 0.1}, {1.75, 0.0, 0.0}));
  const std::vector<double> q0{-kPi / 4, 0.0}, q1{kPi / 4, 0.0}, mid{0.0, 0.0};
  ASSERT_FALSE(s.scene->collides(q0.data()));
  ASSERT_FALSE(s.scene->collides(q1.data()));
  ASSERT_TRUE(s.scene->collides(mid.data()));
  const double dense = denseFirstContact(*s.scene, q0, q1, 1000);
  EXPECT_GT(dense, 0.3);
  EXPECT_LE(dense, 0.5);
  ob::ScopedState<> a(s.si), b(s.si);
  s.space->setState(a.get(), q0.data());
  s.space->setState(b.get(), q1.data());
  EXPECT_TRUE(s.si->isValid(a.get()));
  EXPECT_TRUE(s.si->isValid(b.get()));
  EXPECT_FALSE(s.mdd->checkMotion(a.get(), b.get()));
  EXPECT_FALSE(s.hull->checkMotion(a.get(), b.get()));
  EXPECT_FALSE(s.hull->checkMotion(b.get(), a.get()));
  ArmContact contact;
  const ArmHullCastScene cast(s.scene);
  EXPECT_FALSE(cast.castCollides(q0.data(), q1.data(), &contact)) << "the arm cast now sees the arc: update the docs";
  EXPECT_EQ(contact.link, -1);
  // A short edge that ends in the box is seen by both.
  EXPECT_TRUE(cast.castCollides(q0.data(), mid.data(), &contact));
  EXPECT_EQ(contact.link, 2);
  EXPECT_EQ(contact.world_piece, 0);
}

// What the segments still miss, on a thin arm (links 0.01 wide): each
// segment turns joint 1 by 2 alpha; its hull reaches
// h = 2 cos(alpha) + 0.005 sin(alpha) along its bisector, short of the arm's
// reach of 2. A slab beyond h on the middle segment's bisector is outside
// every segment's hull; the arm passes through it there.
TEST(ArmHullCast, MissesAThinObstacleBetweenArcAndChord) {
  const ArmValidators probe = makeArmSetup(boxPiece({0.1, 0.1, 0.1}, {5.0, 0.0, 0.0}), 0.005);
  const std::vector<double> q0{-kPi / 4, 0.0}, q1{kPi / 4, 0.0};
  ob::ScopedState<> a(probe.si), b(probe.si);
  probe.space->setState(a.get(), q0.data());
  probe.space->setState(b.get(), q1.data());
  const unsigned n = probe.si->getStateSpace()->validSegmentCount(a.get(), b.get());
  ASSERT_GE(n, 2u);
  const double alpha = kPi / 4 / n;
  const double bisector = -kPi / 4 + kPi / 2 * (n / 2 + 0.5) / n;
  const std::vector<double> mid{bisector, 0.0};
  const double h = 2.0 * std::cos(alpha) + 0.005 * std::sin(alpha);
  ASSERT_LT(h + 2e-4, 2.0) << "no sliver between arc and chord at " << n << " segments";
  const double r0 = h + 2e-4, r1 = 2.05;
  const ArmValidators s = makeArmSetup(radialBox(bisector, (r0 + r1) / 2, {(r1 - r0) / 2, 0.02, 0.1}), 0.005);
  ASSERT_FALSE(s.scene->collides(q0.data()));
  ASSERT_FALSE(s.scene->collides(q1.data()));
  ASSERT_TRUE(s.scene->collides(mid.data()));
  EXPECT_FALSE(s.mdd->checkMotion(a.get(), b.get()));
  EXPECT_TRUE(s.hull->checkMotion(a.get(), b.get())) << "the segments now see the sliver: update the docs";
}

// The same turn with the box at the end pose (around link 2's middle at +45
// degrees): the end state collides, and every checker refuses the edge;
// the cast's lastValid is a segment start before the first contact.
TEST(ArmHullCast, SeesACollisionAtTheEndPose) {
  const Eigen::Vector3d centre = std::sqrt(0.5) * Eigen::Vector3d(1.5, 1.5, 0.0);
  const ArmValidators s = makeArmSetup(boxPiece({0.08, 0.08, 0.1}, centre));
  const std::vector<double> q0{-kPi / 4, 0.0}, q1{kPi / 4, 0.0};
  ASSERT_FALSE(s.scene->collides(q0.data()));
  ASSERT_TRUE(s.scene->collides(q1.data()));
  EXPECT_TRUE(s.fcl->collides(q1.data()));
  ob::ScopedState<> a(s.si), b(s.si);
  s.space->setState(a.get(), q0.data());
  s.space->setState(b.get(), q1.data());
  EXPECT_FALSE(s.si->isValid(b.get()));
  EXPECT_FALSE(s.mdd->checkMotion(a.get(), b.get()));
  EXPECT_FALSE(s.hull->checkMotion(a.get(), b.get()));
  std::pair<ob::State*, double> last(s.si->allocState(), -1.0);
  EXPECT_FALSE(s.hull->checkMotion(a.get(), b.get(), last));
  const double dense = denseFirstContact(*s.scene, q0, q1, 1000);
  ASSERT_GT(dense, 0.1);
  EXPECT_GE(last.second, 0.0);
  EXPECT_LE(last.second, dense);
  ob::ScopedState<> expected(s.si);
  s.si->getStateSpace()->interpolate(a.get(), b.get(), last.second, expected.get());
  EXPECT_TRUE(s.si->equalStates(last.first, expected.get()));
  s.si->freeState(last.first);
  EXPECT_EQ(s.hull->counts().motion_checks, 2u);
}

// Self pairs: a three-link arm folding link 3 back onto link 1 over a short
// link 2 (link 1 and link 3 are checked, the adjacent pairs are not).
// Without a world, the cast sees the fold through its self pairs.
TEST(ArmHullCast, ChecksTheSelfPairs) {
  const examples::PlanarArm arm = examples::planarArm({1.0, 0.06, 1.0}, 0.05, 0.05);
  const auto scene = std::make_shared<const ArmScene>(
      arm.model, std::make_shared<const scene::World>(std::vector<scene::Piece>{}, "empty"), arm.filter);
  const ArmHullCastScene cast(scene);
  const std::vector<double> open{0.0, 0.0, 0.0}, folded{0.0, kPi / 2, kPi / 2};
  ASSERT_FALSE(scene->collides(open.data()));
  ASSERT_TRUE(scene->collides(folded.data()));
  ArmContact contact;
  EXPECT_TRUE(cast.castCollides(open.data(), folded.data(), &contact));
  EXPECT_EQ(contact.link, 1);
  EXPECT_EQ(contact.other_link, 3);
  EXPECT_FALSE(cast.castCollides(open.data(), open.data()));
}

TEST(ArmHullCast, RefusesBadArguments) {
  const ArmValidators s = makeArmSetup(boxPiece({0.1, 0.1, 0.1}, {1.75, 0.0, 0.0}));
  EXPECT_THROW(ArmHullCastScene(nullptr), InvalidInputError);
  const auto cast = std::make_shared<ArmHullCastScene>(s.scene);
  EXPECT_THROW(ArmHullCastMotionValidator(nullptr, s.space, cast), InvalidInputError);
  EXPECT_THROW(ArmHullCastMotionValidator(s.si, nullptr, cast), InvalidInputError);
  EXPECT_THROW(ArmHullCastMotionValidator(s.si, s.space, nullptr), InvalidInputError);
  const examples::PlanarArm other = examples::planarArm({1.0, 1.0});
  const ArmSpacePtr other_space = ArmSpace::make(other.model, {0, 1});
  auto other_si = std::make_shared<ob::SpaceInformation>(other_space->stateSpace());
  EXPECT_THROW(ArmHullCastMotionValidator(other_si, other_space, cast), InvalidInputError);
  EXPECT_THROW(ArmHullCastMotionValidator(other_si, s.space, cast), InvalidInputError);
}

}  // namespace
}  // namespace mddual::planning
