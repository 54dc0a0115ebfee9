// PlanningSpace: poses and back, and that EdgeMotion is OMPL's own
// interpolation (the validators' reasoning rests on it).
#include <gtest/gtest.h>

#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <cmath>

#include "mddual/generators.h"
#include "mddual/planning/state_space.h"
#include "test_support.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;
constexpr double kPi = 3.14159265358979323846;
using testing::Rng;

const Eigen::AlignedBox3d kBounds(Eigen::Vector3d(-5, -4, -3), Eigen::Vector3d(5, 4, 3));

double poseError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return std::max((a.linear() - b.linear()).cwiseAbs().maxCoeff(),
                  (a.translation() - b.translation()).cwiseAbs().maxCoeff());
}

class AllKinds : public ::testing::TestWithParam<SpaceKind> {};

TEST_P(AllKinds, PoseRoundTrip) {
  const PlanningSpacePtr space = PlanningSpace::make(
      GetParam(), kBounds, 0.25, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY())));
  Rng rng(7);
  ob::ScopedState<> s(space->stateSpace()), t(space->stateSpace());
  for (int i = 0; i < 200; ++i) {
    testing::randomState(*space, rng, s.get());
    const Eigen::Isometry3d X = space->pose(s.get());
    space->setPose(X, t.get());
    EXPECT_LT(poseError(space->pose(t.get()), X), 1e-12);
    EXPECT_TRUE(space->stateSpace()->satisfiesBounds(t.get()));
  }
}

TEST_P(AllKinds, EdgeMotionIsOmplInterpolation) {
  const PlanningSpacePtr space = PlanningSpace::make(GetParam(), kBounds);
  Rng rng(11);
  ob::ScopedState<> s1(space->stateSpace()), s2(space->stateSpace()), st(space->stateSpace());
  int rotating = 0;
  for (int i = 0; i < 500; ++i) {
    testing::randomState(*space, rng, s1.get());
    testing::randomState(*space, rng, s2.get());
    if (i % 5 == 0) testing::randomEdgeEnd(*space, s1.get(), 3.0, false, 0.0, rng, s2.get());
    const EdgeMotion m = space->motion(s1.get(), s2.get());
    rotating += m.rotates();
    if (GetParam() == SpaceKind::kR2 || GetParam() == SpaceKind::kR3 || i % 5 == 0) {
      EXPECT_FALSE(m.rotates());
    }
    EXPECT_LE(m.angle, kPi + 1e-12);
    EXPECT_LT(poseError(m.X_end, space->pose(s2.get())), 1e-15);
    for (double t : {0.0, 0.25, 0.5, 0.9, 1.0, std::uniform_real_distribution<double>(0, 1)(rng)}) {
      space->stateSpace()->interpolate(s1.get(), s2.get(), t, st.get());
      EXPECT_LT(poseError(m.pose(t), space->pose(st.get())), 1e-12) << "t = " << t << " edge " << i;
    }
  }
  if (GetParam() == SpaceKind::kSE2 || GetParam() == SpaceKind::kSE3) {
    EXPECT_GT(rotating, 300);
  }
}

INSTANTIATE_TEST_SUITE_P(Kinds, AllKinds,
                         ::testing::Values(SpaceKind::kSE2, SpaceKind::kSE3, SpaceKind::kR2, SpaceKind::kR3),
                         [](const auto& p) { return std::string(toString(p.param)); });

TEST(PlanningSpace, Se2YawGoesTheShortWayAcrossPi) {
  const PlanningSpacePtr space = PlanningSpace::se2(kBounds);
  ob::ScopedState<ob::SE2StateSpace> s1(space->stateSpace()), s2(space->stateSpace());
  s1->setXY(0, 0);
  s1->setYaw(3.0);
  s2->setXY(1, 0);
  s2->setYaw(-3.0);
  const EdgeMotion m = space->motion(s1.get(), s2.get());
  EXPECT_NEAR(m.angle, 2 * kPi - 6.0, 1e-15);
  EXPECT_GT(m.axis_R.z(), 0.0);  // yaw increases through pi
}

TEST(PlanningSpace, Se3TinyRotationKeepsTheStartOrientationLikeOmpl) {
  const PlanningSpacePtr space = PlanningSpace::se3(kBounds);
  ob::ScopedState<> s1(space->stateSpace()), s2(space->stateSpace()), st(space->stateSpace());
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  space->setPose(X, s1.get());
  X.translation() = Eigen::Vector3d(1, 2, 0);
  X.linear() = Eigen::AngleAxisd(5e-5, Eigen::Vector3d::UnitX()).toRotationMatrix();  // |q1.q2| > 1 - 1e-9
  space->setPose(X, s2.get());
  const EdgeMotion m = space->motion(s1.get(), s2.get());
  EXPECT_FALSE(m.rotates());
  EXPECT_TRUE(m.endDiffers());
  space->stateSpace()->interpolate(s1.get(), s2.get(), 0.7, st.get());
  EXPECT_LT(poseError(m.pose(0.7), space->pose(st.get())), 1e-15);
  // Just above OMPL's threshold: slerp, and the motion rotates.
  X.linear() = Eigen::AngleAxisd(2e-4, Eigen::Vector3d::UnitX()).toRotationMatrix();
  space->setPose(X, s2.get());
  EXPECT_TRUE(space->rotates(s1.get(), s2.get()));
}

TEST(PlanningSpace, BoundsExitFraction) {
  const PlanningSpacePtr space = PlanningSpace::r3(kBounds);
  EXPECT_NEAR(space->boundsExitFraction({0, 0, 0}, {10, 0, 0}), 0.5, 1e-12);
  EXPECT_NEAR(space->boundsExitFraction({0, 0, 0}, {0, -8, 0}), 0.5, 1e-12);
  EXPECT_EQ(space->boundsExitFraction({0, 0, 0}, {1, 1, 1}), std::numeric_limits<double>::infinity());
  EXPECT_TRUE(space->positionInBounds({5, 4, 3}));
  EXPECT_FALSE(space->positionInBounds({5.001, 0, 0}));
  // R2 ignores z.
  EXPECT_TRUE(PlanningSpace::r2(kBounds)->positionInBounds({0, 0, 100}));
}

}  // namespace
}  // namespace mddual::planning
