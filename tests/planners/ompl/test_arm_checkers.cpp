// The OMPL layer for arms: ArmSpace (layouts, OMPL's interpolation, errors),
// the checkers' contract (checkMotion against the dense reference, lastValid
// before the first colliding state), FCL on the same pieces against the
// exact state check, and RRT-Connect planning on arm7 with every edge of the
// solution verified densely. Its own executable: OMPL's RNG is seeded before
// any exists.
#include <gtest/gtest.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>
#include <ompl/base/spaces/SO3StateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/RandomNumbers.h>

#include <unistd.h>

#include <cmath>
#include <fstream>
#include <functional>

#include "arm_fixture.h"
#include "mddual/constants.h"
#include "mddual/planning/arm_checkers.h"
#include "mddual/planning/arm_problem.h"
#include "mddual/scene/srdf.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;
using testing::ArmFixture;
using testing::denseFirstContact;
using testing::kArm7Dir;
using testing::makeArm;
using testing::randomConfiguration;
using testing::Rng;

const bool kSeeded = [] {
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(testing::seed()));
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  return true;
}();

constexpr int kMaxPlannerIterations = 200000;

/// arm7's `arm` group as an OMPL space with the exact checkers installed.
struct ArmSetup {
  ArmFixture arm;
  ArmSpacePtr space;
  ob::SpaceInformationPtr si;
  ArmChecking checking;
};

ArmSetup makeSetup() {
  ArmSetup s;
  s.arm = makeArm();
  const scene::Srdf srdf = scene::loadSrdf(kArm7Dir / "arm7.srdf");
  s.space = ArmSpace::make(s.arm.model, scene::groupVariables(srdf, *s.arm.model, "arm"));
  s.si = std::make_shared<ob::SpaceInformation>(s.space->stateSpace());
  s.checking = useExactChecking(s.si, s.space, s.arm.scene);
  s.si->setup();
  return s;
}

TEST(ArmSpace, MakesTheGroupsSpace) {
  const ArmSetup s = makeSetup();
  ASSERT_EQ(s.space->dimension(), 7);
  const auto* rv = s.space->stateSpace()->as<ob::RealVectorStateSpace>();
  EXPECT_EQ(rv->getDimensionName(3), "joint4");
  EXPECT_DOUBLE_EQ(rv->getBounds().low[3], -3.0);
  EXPECT_DOUBLE_EQ(rv->getBounds().high[3], -0.07);
  ob::ScopedState<> state(s.space->stateSpace());
  Rng rng(testing::seed());
  const std::vector<double> q = randomConfiguration(*s.arm.model, rng);
  s.space->setState(state.get(), q.data());
  const std::vector<double> back = s.space->configuration(state.get());
  for (int v = 0; v < 7; ++v) EXPECT_EQ(back[static_cast<std::size_t>(v)], q[static_cast<std::size_t>(v)]);
  // The finger, outside the group, keeps its fixed value.
  EXPECT_EQ(back[7], s.space->fixedConfiguration()[7]);
}

TEST(ArmSpace, EdgesFollowOmplsInterpolationThroughContinuousJoints) {
  // A robot whose second joint is continuous: a compound space with SO2.
  const std::filesystem::path urdf =
      std::filesystem::temp_directory_path() / ("mddual_arm_continuous_" + std::to_string(::getpid()) + ".urdf");
  std::ofstream(urdf) << (R"(<robot name="c"><link name="base"/>
    <link name="a"><collision><geometry><box size="0.1 0.1 0.4"/></geometry></collision></link>
    <link name="b"><collision><geometry><box size="0.4 0.1 0.1"/></geometry></collision></link>
    <joint name="j1" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 1 0"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    <joint name="j2" type="continuous"><parent link="a"/><child link="b"/><origin xyz="0 0 0.4"/>
      <axis xyz="0 0 1"/></joint></robot>)");
  auto model = std::make_shared<const scene::RobotModel>(scene::loadRobotModel(urdf));
  std::filesystem::remove(urdf);
  const ArmSpacePtr space = ArmSpace::make(model, {0, 1});
  ASSERT_NE(dynamic_cast<ob::CompoundStateSpace*>(space->stateSpace().get()), nullptr);
  ob::ScopedState<> s1(space->stateSpace()), s2(space->stateSpace()), mid(space->stateSpace());
  Rng rng(testing::seed());
  std::uniform_real_distribution<double> angle(-kPi, kPi), unit(0.0, 1.0);
  int wrapped = 0;
  for (int i = 0; i < 500; ++i) {
    const std::vector<double> a = {unit(rng) * 2 - 1, angle(rng)}, b = {unit(rng) * 2 - 1, angle(rng)};
    space->setState(s1.get(), a.data());
    space->setState(s2.get(), b.data());
    std::vector<double> q0(2), q1(2);
    space->edge(s1.get(), s2.get(), q0.data(), q1.data());
    wrapped += std::abs(b[1] - a[1]) > kPi ? 1 : 0;
    const double t = unit(rng);
    space->stateSpace()->interpolate(s1.get(), s2.get(), t, mid.get());
    const std::vector<double> q = space->configuration(mid.get());
    EXPECT_NEAR(q[0], q0[0] + t * (q1[0] - q0[0]), 1e-12);
    EXPECT_NEAR(std::remainder(q[1] - (q0[1] + t * (q1[1] - q0[1])), 2 * kPi), 0.0, 1e-12);
  }
  EXPECT_GT(wrapped, 100) << "too few edges the short way round across +-pi";
  // A path across +-pi and back: its configurations step as OMPL's edges do
  // (3.0 -> -3.0 is +0.28 rad, not -6.0), away from [-pi, pi) and back.
  std::vector<ob::ScopedState<>> path(4, ob::ScopedState<>(space->stateSpace()));
  const double angles[] = {2.5, 3.0, -3.0, 2.9};
  std::vector<const ob::State*> states;
  for (int i = 0; i < 4; ++i) {
    const std::vector<double> q = {0.1 * i, angles[i]};
    space->setState(path[static_cast<std::size_t>(i)].get(), q.data());
    states.push_back(path[static_cast<std::size_t>(i)].get());
  }
  const std::vector<std::vector<double>> unwrapped = space->pathConfigurations(states);
  ASSERT_EQ(unwrapped.size(), 4u);
  EXPECT_NEAR(unwrapped[0][1], 2.5, 1e-12);
  EXPECT_NEAR(unwrapped[1][1], 3.0, 1e-12);
  EXPECT_NEAR(unwrapped[2][1], 2 * kPi - 3.0, 1e-12);
  EXPECT_NEAR(unwrapped[3][1], 2.9, 1e-12);
  EXPECT_NEAR(unwrapped[3][0], 0.3, 1e-12);
}

TEST(ArmSpace, WrapNamesWhatIsWrong) {
  const ArmFixture arm = makeArm();
  auto rv = std::make_shared<ob::RealVectorStateSpace>(2);
  rv->setName("user");
  auto expectError = [](const std::function<void()>& f, const std::string& part) {
    try {
      f();
      ADD_FAILURE() << "no error (expected '" << part << "')";
    } catch (const InvalidInputError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  expectError(
      [&] {
        ArmSpace::wrap(rv, arm.model, {"joint1", "elbow"});
      },
      "state space 'user', coordinate 1: 'elbow' is not a joint of robot 'arm7'");
  expectError([&] { ArmSpace::wrap(rv, arm.model, {"joint1", "finger_right_joint"}); }, "a mimic joint");
  expectError([&] { ArmSpace::wrap(rv, arm.model, {"joint1", "joint1"}); }, "'joint1' twice");
  expectError([&] { ArmSpace::wrap(rv, arm.model, {"joint1"}); }, "1 joint names for 2 coordinates");
  expectError([&] { ArmSpace::wrap(std::make_shared<ob::SE3StateSpace>(), arm.model); },
              "component 0 ('RealVectorSpace");
  expectError([&] { ArmSpace::wrap(std::make_shared<ob::SO3StateSpace>(), arm.model); },
              "not a RealVectorStateSpace or a CompoundStateSpace");
  auto compound = std::make_shared<ob::CompoundStateSpace>();
  auto so2 = std::make_shared<ob::SO2StateSpace>();
  so2->setName("joint2");
  compound->addSubspace(so2, 1.0);
  expectError([&] { ArmSpace::wrap(compound, arm.model); }, "an SO2 coordinate for joint 'joint2'");
  // Names taken from the space itself.
  rv->setDimensionName(0, "joint3");
  rv->setDimensionName(1, "joint1");
  EXPECT_EQ(ArmSpace::wrap(rv, arm.model)->variables(), (std::vector<int>{2, 0}));
}

TEST(ArmCheckers, KeepOmplsContract) {
  const ArmSetup s = makeSetup();
  ArmSceneOptions finer = s.arm.scene->options();
  finer.contact_distance /= 10.0;
  const ArmScene verifier(s.arm.model, s.arm.scene->worldPtr(), s.arm.scene->filter(), Eigen::Isometry3d::Identity(),
                          finer);
  ob::ScopedState<> s1(s.si), s2(s.si), last(s.si);
  Rng rng(testing::seed() + 3);
  int invalid = 0, valid = 0, kept = 0;
  for (int i = 0; i < 100 * testing::scale(); ++i) {
    const std::vector<double> a = randomConfiguration(*s.arm.model, rng);
    std::vector<double> b = randomConfiguration(*s.arm.model, rng);
    for (std::size_t v = 0; v < 7; ++v) b[v] = a[v] + 0.4 * (b[v] - a[v]);
    s.space->setState(s1.get(), a.data());
    s.space->setState(s2.get(), b.data());
    if (!s.si->isValid(s1.get())) continue;
    std::vector<double> q0(8), q1(8);
    s.space->edge(s1.get(), s2.get(), q0.data(), q1.data());
    const double dense = denseFirstContact(*s.arm.scene, q0, q1, 1000);
    const bool ok = s.si->checkMotion(s1.get(), s2.get());
    std::pair<ob::State*, double> lv(last.get(), -1.0);
    EXPECT_EQ(s.si->getMotionValidator()->checkMotion(s1.get(), s2.get(), lv), ok);
    if (std::isfinite(dense)) {
      EXPECT_FALSE(ok) << "edge " << i << " collides at " << dense;
    }
    if (ok) {
      ++valid;
      continue;
    }
    ++invalid;
    // lastValid: a valid state, before the first colliding sample, and the
    // state OMPL interpolates there.
    EXPECT_GE(lv.second, 0.0);
    EXPECT_LE(lv.second, std::min(1.0, dense));
    EXPECT_TRUE(s.si->isValid(last.get()));
    ob::ScopedState<> expected(s.si);
    s.si->getStateSpace()->interpolate(s1.get(), s2.get(), lv.second, expected.get());
    EXPECT_LT(s.si->distance(expected.get(), last.get()), 1e-12);
    // The partial motion a planner keeps passes a check with a tenth of the
    // contact distance (the benchmark's verification): its states keep the
    // checker's clearance. Pinned: BKPIECE's partial motions ended within it.
    std::vector<double> l0(8), l1(8);
    s.space->edge(s1.get(), last.get(), l0.data(), l1.data());
    EXPECT_FALSE(verifier.checkEdge(l0.data(), l1.data(), EdgeQuery::kValidity).collides) << "edge " << i;
    if (lv.second > 0.0) {
      EXPECT_GE(s.arm.scene->clearance(l1.data()), 0.999 * s.arm.scene->options().contact_distance) << "edge " << i;
      ++kept;
    }
    // The same of the scene's exact kLastValid (no tolerance), whose
    // fraction sits at the contact distance itself.
    const ArmEdgeResult exact = s.arm.scene->checkEdge(q0.data(), q1.data(), EdgeQuery::kLastValid);
    ASSERT_TRUE(exact.collides);
    std::vector<double> qe(8);
    for (std::size_t v = 0; v < qe.size(); ++v) qe[v] = q0[v] + exact.fraction * (q1[v] - q0[v]);
    EXPECT_FALSE(verifier.checkEdge(q0.data(), qe.data(), EdgeQuery::kValidity).collides) << "edge " << i;
    if (exact.fraction > 0.0) {
      EXPECT_GE(s.arm.scene->clearance(qe.data()), 0.999 * s.arm.scene->options().contact_distance) << "edge " << i;
    }
  }
  EXPECT_GE(invalid, 10);
  EXPECT_GE(valid, 10);
  EXPECT_GE(kept, 5) << "too few partial motions to test lastValid's clearance";
}

TEST(ArmCheckers, FclAgreesWithTheExactStateCheck) {
  const ArmFixture arm = makeArm();
  const FclArmScene fcl(arm.scene);
  Rng rng(testing::seed() + 4);
  int colliding = 0, disagree = 0;
  const int n = 300 * testing::scale();
  for (int i = 0; i < n; ++i) {
    const std::vector<double> q = randomConfiguration(*arm.model, rng);
    const bool exact = arm.scene->collides(q.data());
    colliding += exact ? 1 : 0;
    if (fcl.collides(q.data()) != exact) {
      // Only at grazing contact, where the two tolerances differ.
      ++disagree;
      EXPECT_LT(std::abs(arm.scene->clearance(q.data())), 1e-6) << "sample " << i;
    }
  }
  EXPECT_GT(colliding, n / 10);
  EXPECT_LT(colliding, n * 9 / 10);
  EXPECT_LE(disagree, n / 100);
}

TEST(ArmCheckers, RrtConnectPlansAVerifiedPath) {
  // The first problem of each of two of arm7's sets whose straight edge is
  // blocked, planned with RRT-Connect on the exact checkers; every edge of
  // the solution is then checked densely.
  const ArmRobot robot = loadArmRobot(kArm7Dir / "arm7.urdf", kArm7Dir / "arm7.srdf");
  for (const char* set : {"bookshelf_thin", "cage"}) {
    bool planned = false;
    for (const scene::MbmProblemFiles& files : scene::listMbmProblems(kArm7Dir / "problems" / set)) {
      const ArmProblem problem = loadArmProblem(robot, files);
      auto si = std::make_shared<ob::SpaceInformation>(problem.space->stateSpace());
      useExactChecking(si, problem.space, problem.scene);
      og::SimpleSetup setup(si);
      ob::ScopedState<> from(si), to(si);
      problem.space->setState(from.get(), problem.start.data());
      problem.space->setState(to.get(), problem.goal.data());
      setup.setStartAndGoalStates(from, to);
      setup.setup();
      if (si->checkMotion(from.get(), to.get())) continue;
      setup.setPlanner(std::make_shared<og::RRTConnect>(si));
      int iterations = 0;
      const ob::PlannerStatus status =
          setup.solve(ob::PlannerTerminationCondition([&] { return ++iterations > kMaxPlannerIterations; }));
      ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << problem.name;
      const og::PathGeometric& path = setup.getSolutionPath();
      ASSERT_GE(path.getStateCount(), 3u) << problem.name;
      for (unsigned int i = 0; i + 1 < path.getStateCount(); ++i) {
        std::vector<double> q0(8), q1(8);
        problem.space->edge(path.getState(i), path.getState(i + 1), q0.data(), q1.data());
        EXPECT_TRUE(std::isinf(denseFirstContact(*problem.scene, q0, q1, 2000))) << problem.name << " edge " << i;
      }
      planned = true;
      break;
    }
    EXPECT_TRUE(planned) << set << ": no problem with a blocked straight edge";
  }
}

}  // namespace
}  // namespace mddual::planning
