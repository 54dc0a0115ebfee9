// Every documented error of the OMPL layer: an mddual::InvalidInputError whose
// message names what is wrong.
#include <gtest/gtest.h>

#include <ompl/base/ScopedState.h>
#include <cmath>
#include <limits>
#include <string>

#include "mddual/constants.h"
#include "mddual/error.h"
#include "mddual/generators.h"
#include "mddual/planning/clearance.h"
#include "mddual/planning/scene_distance.h"
#include "test_support.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;
using testing::kInf;
using testing::kNaN;

/// Runs f, expects InvalidInputError with `needle` in its message.
template <typename F>
void expectError(F&& f, const std::string& needle) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one mentioning '" << needle << "'";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << "message: " << e.what();
  }
}

const Eigen::AlignedBox3d kUnitBounds(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1));

TEST(Errors, PlanningSpace) {
  expectError([] { PlanningSpace::se3(Eigen::AlignedBox3d()); }, "bounds");  // empty box
  expectError([] { PlanningSpace::se2(Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0))); },
              "axis 1");
  expectError([] { PlanningSpace::r3(Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, kInf, 1))); },
              "not finite");
  // SE(2)/R(2) ignore z's bounds.
  EXPECT_NO_THROW(PlanningSpace::se2(Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 0))));
  expectError([] { PlanningSpace::r3(kUnitBounds, Eigen::Quaterniond(0, 0, 0, 0)); }, "fixed orientation");
  expectError([] { PlanningSpace::r2(kUnitBounds, kNaN); }, "fixed z");
}

TEST(Errors, SetPose) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  const PlanningSpacePtr se2 = PlanningSpace::se2(kUnitBounds);
  ob::ScopedState<> s(se2->stateSpace());
  X.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX()).toRotationMatrix();
  expectError([&] { se2->setPose(X, s.get()); }, "rotates about +z");
  X.linear().setIdentity();
  X.translation().z() = 0.1;
  expectError([&] { se2->setPose(X, s.get()); }, "z = 0");
  X.translation().z() = kNaN;
  expectError([&] { se2->setPose(X, s.get()); }, "not finite");
  X.translation().setZero();
  X.linear() = 2.0 * Eigen::Matrix3d::Identity();
  expectError([&] { se2->setPose(X, s.get()); }, "not a rotation");

  const PlanningSpacePtr r3 = PlanningSpace::r3(kUnitBounds);
  ob::ScopedState<> t(r3->stateSpace());
  X.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  expectError([&] { r3->setPose(X, t.get()); }, "fixed orientation");
  const PlanningSpacePtr r2 = PlanningSpace::r2(kUnitBounds, 0.5);
  ob::ScopedState<> u(r2->stateSpace());
  X.linear().setIdentity();
  expectError([&] { r2->setPose(X, u.get()); }, "z = 0.5");
}

TEST(Errors, SceneAndCheckers) {
  const examples::ExampleScene scene = examples::thinWallScene(0.05);
  expectError([&] { MddScene(nullptr, scene.world); }, "robot is null");
  expectError([&] { MddScene(scene.robot, nullptr); }, "world is null");
  MddSceneOptions bad;
  bad.rotation_tolerance = kNaN;
  expectError([&] { MddScene(scene.robot, scene.world, bad); }, "not finite");
  bad.rotation_tolerance = 1e-9;
  expectError([&] { MddScene(scene.robot, scene.world, bad); }, "below 1e-6");
  bad.rotation_tolerance = 0.0;
  bad.refinement_levels = 9;
  expectError([&] { MddScene(scene.robot, scene.world, bad); }, "refinement_levels");
  bad.refinement_levels = 3;
  bad.last_valid_level = -1;
  expectError([&] { MddScene(scene.robot, scene.world, bad); }, "last_valid_level -1 is outside [0, 8]");
  bad.last_valid_level = 9;
  expectError([&] { MddScene(scene.robot, scene.world, bad); }, "last_valid_level 9 is outside [0, 8]");
  expectError([&] { FclScene(nullptr, scene.world); }, "robot is null");
  expectError([&] { FclScene(scene.robot, nullptr); }, "world is null");

  const testing::Fixture fx = testing::makeFixture(scene);
  const auto other = std::make_shared<ob::SpaceInformation>(PlanningSpace::r2(scene.bounds)->stateSpace());
  expectError([&] { MddStateValidityChecker(nullptr, fx.space, fx.mdd); }, "SpaceInformation is null");
  expectError([&] { MddStateValidityChecker(fx.si, nullptr, fx.mdd); }, "PlanningSpace is null");
  expectError([&] { MddStateValidityChecker(fx.si, fx.space, nullptr); }, "scene is null");
  expectError([&] { MddStateValidityChecker(other, fx.space, fx.mdd); }, "state space");
  expectError([&] { MddMotionValidator(other, fx.space, fx.mdd); }, "state space");
  expectError([&] { MddMotionValidator(other, fx.space, fx.mdd); }, "useExactChecking()");
  expectError([&] { MddMotionValidator(fx.si, fx.space, nullptr); }, "scene is null");
  expectError([&] { FclStateValidityChecker(other, fx.space, fx.fcl); }, "state space");
  expectError([&] { FclStateValidityChecker(fx.fcl_si, fx.space, nullptr); }, "FclScene is null");
  expectError([&] { FclContinuousMotionValidator(other, fx.space, fx.fcl); }, "state space");
  FclCcdOptions options;
  options.num_max_iterations = 1;
  expectError([&] { FclContinuousMotionValidator(fx.fcl_si, fx.space, fx.fcl, options); }, "num_max_iterations");
  options.num_max_iterations = 10;
  options.toc_err = 0.0;
  expectError([&] { FclContinuousMotionValidator(fx.fcl_si, fx.space, fx.fcl, options); }, "toc_err");
}

TEST(Errors, Queries) {
  const examples::ExampleScene scene = examples::thinWallScene(0.05);
  const MddScene mdd(scene.robot, scene.world);
  const Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  expectError([&] { directedClearance(mdd, X, Eigen::Vector3d::Zero()); }, "direction is zero");
  expectError([&] { directedClearance(mdd, X, Eigen::Vector3d(kNaN, 0, 0)); }, "not finite");
  expectError([&] { directedClearance(mdd, X, Eigen::Vector3d::UnitX(), -1.0); }, "max_distance");
  expectError([&] { directedClearance(mdd, X, Eigen::Vector3d::UnitX(), kNaN); }, "max_distance");
  expectError([&] { mdd.sweepSet(0, X, Eigen::Vector3d::Zero(), 1.0, true); }, "direction is zero");
  // Directions whose norm under- or overflows are directions all the same
  // (the wall is at x = 50: 49.9 from the cube). sweep's v is a displacement:
  // sweepSet takes the direction.
  const double to_wall = directedClearance(mdd, X, Eigen::Vector3d::UnitX()).distance;
  EXPECT_NEAR(to_wall, 49.9, 1e-9);
  for (const double size : {1e-200, 1e200}) {
    EXPECT_EQ(directedClearance(mdd, X, Eigen::Vector3d(size, 0, 0)).distance, to_wall) << size;
    EXPECT_EQ(mdd.sweepSet(0, X, Eigen::Vector3d(size, 0, 0), kInf, true).distance, to_wall) << size;
  }
  // rotation_tolerance: printed as given (1e-300 was "0.000000"), and at most
  // 1e6 robot radii (1e60 failed later in a query, naming a polytope point).
  MddSceneOptions tiny;
  tiny.rotation_tolerance = 1e-300;
  expectError([&] { MddScene(scene.robot, scene.world, tiny); }, "rotation_tolerance 1e-300 is below");
  tiny.rotation_tolerance = 1e60;
  expectError([&] { MddScene(scene.robot, scene.world, tiny); }, "above 1e6 times the robot radius");
  // A zero translation is a state check, not an error.
  EXPECT_FALSE(mdd.sweep(X, Eigen::Vector3d::Zero()).start_collides);
}

// Hostile-input hunt (helper): a NaN pose missed every box and volume test
// and came back free or infinitely far; it is an error, as in isValid.
TEST(Errors, NonFinitePosesAreErrorsNotFreeSpace) {
  const examples::ExampleScene scene = examples::blobScene(testing::seed());
  const MddScene mdd(scene.robot, scene.world);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation().x() = kNaN;
  expectError([&] { mdd.collides(X); }, "MddScene::collides: the robot pose X_WR has a non-finite translation");
  expectError([&] { mdd.sweep(X, Eigen::Vector3d::UnitX()); }, "MddScene::sweep: the robot pose X_WR");
  expectError([&] { directedClearance(mdd, X, Eigen::Vector3d::UnitX()); }, "non-finite translation");
  expectError([&] { sceneDistance(mdd, X); }, "sceneDistance: the robot pose X_WR has a non-finite translation");
  X.translation().x() = 0.0;
  X.linear()(1, 2) = kNaN;
  expectError([&] { mdd.collides(X); }, "non-finite rotation");
  expectError([&] { sceneDistance(mdd, X); }, "non-finite rotation");
  X.linear() = 2.0 * Eigen::Matrix3d::Identity();  // refused by the pair queries
  expectError([&] { mdd.collides(X); }, "not a rigid transform");
  // An empty world is free everywhere, but not for a NaN pose.
  const MddScene empty(scene.robot, std::make_shared<scene::World>());
  X = Eigen::Isometry3d::Identity();
  X.translation().z() = kNaN;
  expectError([&] { empty.collides(X); }, "non-finite translation");
  const testing::Fixture fx = testing::makeFixture(scene);
  ob::ScopedState<> s(fx.space->stateSpace());
  fx.space->setPose(Eigen::Isometry3d::Identity(), s.get());
  s->as<ob::SE3StateSpace::StateType>()->setX(kNaN);
  expectError([&] { fx.mdd_checker->clearance(s.get()); }, "non-finite");
}

// Hand-built motions PlanningSpace::motion never makes: a negative angle was
// read as no rotation (its collisions missed), a scaled axis failed deep in
// the core; and a robot without pieces was free everywhere.
TEST(Errors, EdgeMotionsAndRobotsThatCannotBeChecked) {
  const examples::ExampleScene scene = examples::blobScene(testing::seed());
  const MddScene mdd(scene.robot, scene.world);
  EdgeMotion m;
  m.p_end = Eigen::Vector3d(1, 0, 0);
  m.X_end.translation() = m.p_end;
  m.angle = -2.0;
  expectError([&] { mdd.checkEdge(m, EdgeQuery::kValidity); }, "angle");
  m.angle = kNaN;
  expectError([&] { mdd.checkEdge(m, EdgeQuery::kFirstContact); }, "angle");
  m.angle = 1.0;
  m.axis_R = Eigen::Vector3d(0, 0, 2);
  expectError([&] { mdd.checkEdge(m, EdgeQuery::kValidity); }, "axis_R must be a unit vector");
  m.axis_R = Eigen::Vector3d::UnitZ();
  m.R_start = 2.0 * Eigen::Matrix3d::Identity();
  expectError([&] { mdd.checkEdge(m, EdgeQuery::kValidity); }, "R_start");
  m.R_start.setIdentity();
  m.p_start.y() = kNaN;
  expectError([&] { mdd.checkEdge(m, EdgeQuery::kValidity); }, "positions must be finite");
  m.p_start.y() = 0.0;
  EXPECT_NO_THROW(mdd.checkEdge(m, EdgeQuery::kValidity));
  expectError([&] { MddScene(std::make_shared<scene::RigidBody>(), scene.world); }, "has no pieces");
}

// lastValid toward a state whose rotation is out of bounds: OMPL's
// validSegmentCount (SE(2): yaw 10) and interpolate (SE(3): quaternion of
// norm 2) assert on it; the edge is invalid and lastValid a valid state.
TEST(Errors, LastValidTowardARotationOutOfBoundsDoesNotAbort) {
  const examples::ExampleScene scene = examples::blobScene(testing::seed());
  for (SpaceKind kind : {SpaceKind::kSE2, SpaceKind::kSE3}) {
    const testing::Fixture fx = testing::makeFixture(scene, kind);
    testing::Rng rng(testing::seed() * 3);
    ob::ScopedState<> s1(fx.space->stateSpace()), s2(fx.space->stateSpace()), last(fx.space->stateSpace());
    testing::randomValidState(*fx.si, *fx.space, rng, s1.get());
    fx.si->copyState(s2.get(), s1.get());
    if (kind == SpaceKind::kSE2) {
      s2->as<ob::SE2StateSpace::StateType>()->setYaw(10.0);
    } else {
      auto& q = s2->as<ob::SE3StateSpace::StateType>()->rotation();
      q.x = 0.0, q.y = 0.0, q.z = 0.0, q.w = 2.0;
    }
    ASSERT_FALSE(fx.si->satisfiesBounds(s2.get()));
    std::pair<ob::State*, double> last_valid(last.get(), -1.0);
    EXPECT_FALSE(fx.mdd_motion->checkMotion(s1.get(), s2.get(), last_valid)) << toString(kind);
    EXPECT_GE(last_valid.second, 0.0);
    EXPECT_LE(last_valid.second, 1.0);
    EXPECT_TRUE(fx.si->isValid(last.get())) << toString(kind);
    EXPECT_TRUE(fx.mdd_motion->firstInvalid(s1.get(), s2.get(), EdgeQuery::kLastValid).collides);
  }
}

// An API hunt: a zero quaternion aborted the process in OMPL's SO(3)
// interpolate (checkMotion, edgeContact), and a yaw of 1e17 or more made
// checkMotion with lastValid search for minutes. The validator answers at
// once (invalid, lastValid s1); PlanningSpace::motion refuses the zero
// quaternion and wraps any yaw difference into [-pi, pi].
TEST(Errors, RotationsThatAreNoStateAnswerAtOnce) {
  const examples::ExampleScene scene = examples::blobScene(testing::seed());
  for (SpaceKind kind : {SpaceKind::kSE2, SpaceKind::kSE3}) {
    const testing::Fixture fx = testing::makeFixture(scene, kind);
    testing::Rng rng(testing::seed() * 5);
    ob::ScopedState<> s1(fx.space->stateSpace()), s2(fx.space->stateSpace()), last(fx.space->stateSpace());
    testing::randomValidState(*fx.si, *fx.space, rng, s1.get());
    fx.si->copyState(s2.get(), s1.get());
    if (kind == SpaceKind::kSE2) {
      s2->as<ob::SE2StateSpace::StateType>()->setYaw(1e300);
    } else {
      auto& q = s2->as<ob::SE3StateSpace::StateType>()->rotation();
      q.x = 0.0, q.y = 0.0, q.z = 0.0, q.w = 0.0;
    }
    EXPECT_FALSE(fx.mdd_motion->checkMotion(s1.get(), s2.get())) << toString(kind);
    std::pair<ob::State*, double> last_valid(last.get(), -1.0);
    EXPECT_FALSE(fx.mdd_motion->checkMotion(s1.get(), s2.get(), last_valid)) << toString(kind);
    EXPECT_EQ(last_valid.second, 0.0) << toString(kind);
    EXPECT_TRUE(fx.si->equalStates(last.get(), s1.get())) << toString(kind);
    const EdgeContact e = fx.mdd_motion->firstInvalid(s1.get(), s2.get(), EdgeQuery::kFirstContact);
    EXPECT_TRUE(e.collides);
    EXPECT_EQ(e.fraction, 0.0);
    EXPECT_FALSE(e.exact);
    if (kind == SpaceKind::kSE3) {
      expectError([&] { fx.space->motion(s1.get(), s2.get()); }, "motion: s2's quaternion is zero or not finite");
    } else {
      EXPECT_LE(fx.space->motion(s1.get(), s2.get()).angle, kPi);
    }
    // An infinite position: both overloads say invalid (the one with
    // lastValid threw "positions must be finite").
    fx.si->copyState(s2.get(), s1.get());
    const double inf = std::numeric_limits<double>::infinity();
    if (kind == SpaceKind::kSE2) {
      s2->as<ob::SE2StateSpace::StateType>()->setX(inf);
    } else {
      s2->as<ob::SE3StateSpace::StateType>()->setX(inf);
    }
    EXPECT_FALSE(fx.mdd_motion->checkMotion(s1.get(), s2.get())) << toString(kind);
    last_valid = {last.get(), -1.0};
    EXPECT_FALSE(fx.mdd_motion->checkMotion(s1.get(), s2.get(), last_valid)) << toString(kind);
    EXPECT_EQ(last_valid.second, 0.0) << toString(kind);
  }
}

// An API hunt's misuses: a null state (OMPL's own checkers dereference it),
// an unknown space kind or query, a piece set, level or piece that does not
// exist (std::out_of_range before), a NaN or negative angle.
TEST(Errors, MisusedApiCallsAreNamed) {
  const examples::ExampleScene scene = examples::blobScene(testing::seed());
  const testing::Fixture fx = testing::makeFixture(scene, SpaceKind::kSE3);
  ob::ScopedState<> s(fx.space->stateSpace());
  testing::Rng rng(testing::seed() * 7);
  testing::randomValidState(*fx.si, *fx.space, rng, s.get());
  expectError([&] { fx.mdd_checker->isValid(nullptr); }, "MddStateValidityChecker::isValid: the state is null");
  expectError([&] { fx.mdd_checker->clearance(nullptr); }, "the state is null");
  expectError([&] { fx.mdd_motion->checkMotion(s.get(), nullptr); }, "MddMotionValidator: s2 is null");
  std::pair<ob::State*, double> last(nullptr, 0.0);
  expectError([&] { fx.mdd_motion->checkMotion(nullptr, s.get(), last); }, "MddMotionValidator: s1 is null");
  expectError([&] { PlanningSpace::make(static_cast<SpaceKind>(7), fx.space->bounds()); }, "unknown space kind 7");
  const MddScene& mdd = *fx.mdd;
  const EdgeMotion motion = fx.space->motion(s.get(), s.get());
  expectError([&] { mdd.checkEdge(motion, static_cast<EdgeQuery>(9)); }, "unknown query 9");
  expectError([&] { mdd.pieceInSet(0, -1); }, "robot piece -1 does not exist");
  expectError([&] { mdd.enlargedPiece(99, 0); }, "enlargement level 99 does not exist");
  expectError([&] { mdd.sweepSet(9, Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitX(), 1.0, true); },
              "piece set 9 does not exist");
  expectError([&] { mdd.subEdgeCount(kNaN); }, "must be finite and >= 0");
  expectError([&] { mdd.subEdgeCount(-1.0); }, "must be finite and >= 0");
  EXPECT_EQ(mdd.subEdgeCount(1e300), std::numeric_limits<int>::max());
}

TEST(Errors, ExampleScenes) {
  expectError([] { examples::thinWallScene(0.0); }, "thickness");
  const std::vector<Eigen::Vector2d> clockwise = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  expectError([&] { examples::prismTriangles(clockwise, 0.0, 1.0, "x"); }, "counter-clockwise");
}

}  // namespace
}  // namespace mddual::planning
