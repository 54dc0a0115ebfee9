// useExactChecking() on OMPL objects the user made: a state space and a
// SpaceInformation of the user's own (SE(3), SE(2), R^3, SE(3) x R^1), the
// MDD checkers installed in one call, a plan with OMPL's RRT-Connect, and
// every edge of the solution checked again by a dense FCL check on the same
// pieces (test_support.h), independent of MDD-DUAL. Refused layouts throw
// with messages that name the space and the reason.
#include <gtest/gtest.h>

#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/base/spaces/SO3StateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>
#include <cmath>
#include <limits>
#include <string>

#include "mddual/error.h"
#include "mddual/planning/exact_checking.h"
#include "test_support.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;
using testing::kInf;

/// Planner iterations allowed (a count, not a time: the same plan on any machine).
constexpr int kMaxPlannerIterations = 200000;
/// Step of the dense FCL check of the solution's edges (fraction of an edge;
/// the check skips ahead by the FCL distance, so this is the finest step).
constexpr double kDenseStep = 1e-4;

// OMPL's global seed before any RNG exists: the samplers and the planner are
// seeded, hence the plan is the same on every run.
const bool kSeeded = [] {
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(testing::seed()));
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  return true;
}();

ob::RealVectorBounds boundsOf(const Eigen::AlignedBox3d& box, unsigned int dims) {
  ob::RealVectorBounds b(dims);
  for (unsigned int k = 0; k < dims; ++k) {
    b.setLow(k, box.min()[static_cast<int>(k)]);
    b.setHigh(k, box.max()[static_cast<int>(k)]);
  }
  return b;
}

/// The FCL side of a Fixture on the user's space (for denseFirstInvalid).
testing::Fixture fclFixture(const examples::ExampleScene& scene, const ExactChecking& exact) {
  testing::Fixture fx;
  fx.scene = scene;
  fx.space = exact.space;
  fx.fcl = std::make_shared<FclScene>(scene.robot, scene.world);
  fx.fcl_si = std::make_shared<ob::SpaceInformation>(exact.space->stateSpace());
  fx.fcl_checker = std::make_shared<FclStateValidityChecker>(fx.fcl_si, fx.space, fx.fcl);
  fx.fcl_si->setStateValidityChecker(fx.fcl_checker);
  fx.fcl_si->setup();
  return fx;
}

/// A valid state from si's own sampler (seeded through OMPL's global seed).
void sampleValid(const ob::SpaceInformation& si, ob::State* state) {
  ob::StateSamplerPtr sampler = si.allocStateSampler();
  do {
    sampler->sampleUniform(state);
  } while (!si.isValid(state));
}

/// Installs the checkers on the user's si, plans from a start to a goal whose
/// straight edge is invalid, and checks the solution edge by edge with FCL.
void planAndVerify(const examples::ExampleScene& scene, const ob::StateSpacePtr& user_space,
                   const ExactCheckingOptions& options = ExactCheckingOptions()) {
  auto si = std::make_shared<ob::SpaceInformation>(user_space);
  const ExactChecking exact = useExactChecking(si, scene.robot, scene.world, options);
  ASSERT_TRUE(exact.space && exact.scene && exact.state_checker && exact.motion_validator);
  EXPECT_EQ(si->getStateValidityChecker(), exact.state_checker);
  EXPECT_EQ(si->getMotionValidator(), exact.motion_validator);
  EXPECT_EQ(exact.space->stateSpace(), user_space);
  si->setup();

  ob::ScopedState<> start(user_space), goal(user_space);
  sampleValid(*si, start.get());
  int tries = 0;
  do {
    sampleValid(*si, goal.get());
    ASSERT_LT(++tries, 1000) << "no goal behind an obstacle";
  } while (si->checkMotion(start.get(), goal.get()));

  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  pdef->setStartAndGoalStates(start, goal);
  og::RRTConnect planner(si);
  planner.setProblemDefinition(pdef);
  planner.setup();
  int iterations = 0;
  const ob::PlannerStatus status =
      planner.solve(ob::PlannerTerminationCondition([&] { return ++iterations > kMaxPlannerIterations; }));
  ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << scene.name;
  EXPECT_GT(exact.state_checker->counts().state_checks, 0u);
  EXPECT_GT(exact.motion_validator->counts().motion_checks, 0u);

  const auto& path = *pdef->getSolutionPath()->as<og::PathGeometric>();
  ASSERT_GE(path.getStateCount(), 3u);  // the straight edge is invalid
  const testing::Fixture fx = fclFixture(scene, exact);
  int samples = 0;
  for (unsigned int i = 0; i + 1 < path.getStateCount(); ++i) {
    const ob::State* s1 = path.getState(i);
    const ob::State* s2 = path.getState(i + 1);
    EXPECT_TRUE(user_space->satisfiesBounds(s1)) << "state " << i;
    EXPECT_EQ(testing::denseFirstInvalid(fx, s1, s2, 0.0, kDenseStep, &samples), kInf) << scene.name << " edge " << i;
    EXPECT_TRUE(si->checkMotion(s1, s2)) << "edge " << i;
  }
  // Both ends and the states between them were checked by FCL.
  EXPECT_GT(samples, 2 * static_cast<int>(path.getStateCount() - 1));
  EXPECT_TRUE(user_space->satisfiesBounds(path.getState(static_cast<unsigned int>(path.getStateCount() - 1))));
}

TEST(UseExactChecking, UserSe3PlansWithRrtConnect) {
  const examples::ExampleScene scene = examples::blobScene(testing::seed(), 25);
  auto space = std::make_shared<ob::SE3StateSpace>();
  space->setBounds(boundsOf(scene.bounds, 3));
  planAndVerify(scene, space);
}

TEST(UseExactChecking, UserSe2PlansWithRrtConnect) {
  const examples::ExampleScene scene = examples::planarScene(testing::seed(), 30);
  auto space = std::make_shared<ob::SE2StateSpace>();
  space->setBounds(boundsOf(scene.bounds, 2));
  planAndVerify(scene, space);
}

TEST(UseExactChecking, UserR3PlansWithRrtConnect) {
  const examples::ExampleScene scene = examples::primitivesScene(testing::seed(), 20);
  auto space = std::make_shared<ob::RealVectorStateSpace>(3);
  space->setBounds(boundsOf(scene.bounds, 3));
  ExactCheckingOptions options;
  options.layout.q_WR = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()));
  planAndVerify(scene, space, options);
}

/// SE(3) x R^1: a joint the scene ignores, with bounds of its own.
std::shared_ptr<ob::CompoundStateSpace> se3TimesR1(const Eigen::AlignedBox3d& bounds) {
  auto se3 = std::make_shared<ob::SE3StateSpace>();
  se3->setBounds(boundsOf(bounds, 3));
  se3->setName("body");
  auto joint = std::make_shared<ob::RealVectorStateSpace>(1);
  joint->setBounds(-1.0, 1.0);
  joint->setName("joint");
  auto compound = std::make_shared<ob::CompoundStateSpace>();
  compound->addSubspace(se3, 1.0);
  compound->addSubspace(joint, 0.5);
  compound->setName("arm");
  return compound;
}

TEST(UseExactChecking, UserCompoundSe3TimesR1PlansWithRrtConnect) {
  const examples::ExampleScene scene = examples::blobScene(testing::seed() + 1, 25);
  planAndVerify(scene, se3TimesR1(scene.bounds));
}

TEST(UseExactChecking, CompoundPosePartIsTheSe3Component) {
  const examples::ExampleScene scene = examples::blobScene(testing::seed(), 10);
  const auto space = se3TimesR1(scene.bounds);
  auto si = std::make_shared<ob::SpaceInformation>(space);
  const ExactChecking exact = useExactChecking(si, scene.robot, scene.world);
  si->setup();
  EXPECT_EQ(exact.space->kind(), SpaceKind::kSE3);
  EXPECT_EQ(exact.space->poseComponent(), 0);
  ob::ScopedState<> s(space);
  s->as<ob::CompoundState>()->as<ob::SE3StateSpace::StateType>(0)->setXYZ(1.5, 2.5, 3.5);
  s->as<ob::CompoundState>()->as<ob::SE3StateSpace::StateType>(0)->rotation().setIdentity();
  s->as<ob::CompoundState>()->as<ob::RealVectorStateSpace::StateType>(1)->values[0] = 0.25;
  const Eigen::Isometry3d X = exact.space->pose(s.get());
  EXPECT_EQ(X.translation(), Eigen::Vector3d(1.5, 2.5, 3.5));
  EXPECT_TRUE(X.linear().isIdentity(0.0));
  EXPECT_EQ(exact.state_checker->isValid(s.get()), !exact.scene->collides(X) && space->satisfiesBounds(s.get()));
}

// The joint leaves its bounds in the middle of an edge whose pose part is
// free: the edge is invalid from there, and lastValid stops just before.
TEST(UseExactChecking, ExtraJointLeavingItsBoundsEndsTheEdge) {
  const examples::ExampleScene scene = examples::thinWallScene();
  Eigen::AlignedBox3d bounds = scene.bounds;
  bounds.min().z() = -1.0;
  bounds.max().z() = 1.0;
  const auto space = se3TimesR1(bounds);
  auto si = std::make_shared<ob::SpaceInformation>(space);
  const ExactChecking exact = useExactChecking(si, scene.robot, scene.world);
  si->setup();
  ob::ScopedState<> s1(space), s2(space), last(space);
  auto set = [&](ob::State* s, double x, double joint) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = Eigen::Vector3d(x, 0.0, 0.0);
    exact.space->setPose(X, s);
    s->as<ob::CompoundState>()->as<ob::RealVectorStateSpace::StateType>(1)->values[0] = joint;
  };
  set(s1.get(), 10.0, 0.0);
  set(s2.get(), 20.0, 4.0);  // the joint crosses its bound 1.0 at t = 0.25
  ASSERT_TRUE(si->isValid(s1.get()));
  EXPECT_FALSE(si->checkMotion(s1.get(), s2.get()));
  std::pair<ob::State*, double> lastValid(last.get(), -1.0);
  EXPECT_FALSE(si->checkMotion(s1.get(), s2.get(), lastValid));
  EXPECT_LT(lastValid.second, 0.25);
  EXPECT_GT(lastValid.second, 0.25 - 1e-6);
  EXPECT_TRUE(si->isValid(last.get()));
  const EdgeContact first = exact.motion_validator->firstInvalid(s1.get(), s2.get());
  EXPECT_NEAR(first.fraction, 0.25, 1e-12);
  // Within the joint's bounds the same edge is valid.
  set(s2.get(), 20.0, 0.9);
  EXPECT_TRUE(si->checkMotion(s1.get(), s2.get()));
}

void expectRefused(const ob::StateSpacePtr& space, const std::vector<std::string>& parts,
                   const ExactCheckingOptions& options = ExactCheckingOptions()) {
  const examples::ExampleScene scene = examples::thinWallScene();
  auto si = std::make_shared<ob::SpaceInformation>(space);
  try {
    useExactChecking(si, scene.robot, scene.world, options);
    ADD_FAILURE() << "accepted " << space->getName();
  } catch (const InvalidInputError& e) {
    for (const std::string& part : parts) EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
  // Nothing installed on a refused space.
  EXPECT_EQ(std::dynamic_pointer_cast<MddStateValidityChecker>(si->getStateValidityChecker()), nullptr);
}

TEST(UseExactChecking, RefusedLayoutsThrowNamingTheSpace) {
  auto so3 = std::make_shared<ob::SO3StateSpace>();
  so3->setName("orientation");
  expectRefused(so3, {"'orientation' (SO3StateSpace)", "not an SE2, SE3, R^2 or R^3 space"});

  auto r4 = std::make_shared<ob::RealVectorStateSpace>(4);
  r4->setBounds(-1.0, 1.0);
  r4->setName("r4");
  expectRefused(r4, {"'r4' (RealVectorStateSpace of dimension 4)", "not an SE2, SE3, R^2 or R^3"});

  auto unbounded = std::make_shared<ob::SE3StateSpace>();
  unbounded->setName("free_flyer");
  expectRefused(unbounded, {"'free_flyer'", "set its bounds", "empty or not finite"});

  const Eigen::AlignedBox3d box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(1.0));
  auto joint = std::make_shared<ob::RealVectorStateSpace>(1);
  joint->setBounds(-1.0, 1.0);
  joint->setName("joint");
  auto body = std::make_shared<ob::SE3StateSpace>();
  body->setBounds(boundsOf(box, 3));
  body->setName("body");
  auto not_first = std::make_shared<ob::CompoundStateSpace>();
  not_first->addSubspace(joint, 1.0);
  not_first->addSubspace(body, 1.0);
  not_first->setName("joint_first");
  expectRefused(not_first,
                {"'joint_first'", "the first component 'joint'", "is not a pose part", "'body'", "pose_subspace"});
  // Named, the same layout is accepted.
  {
    auto si = std::make_shared<ob::SpaceInformation>(not_first);
    const examples::ExampleScene scene = examples::thinWallScene();
    ExactCheckingOptions named;
    named.layout.pose_subspace = "body";
    EXPECT_EQ(useExactChecking(si, scene.robot, scene.world, named).space->poseComponent(), 1);
  }
}

}  // namespace
}  // namespace mddual::planning
