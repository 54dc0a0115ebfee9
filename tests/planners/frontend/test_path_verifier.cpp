// PathVerifier: paths through a thin wall are flagged by both of its checks,
// free paths pass (also within 1e-7 of the wall, where FCL's GJK may report a
// contact that the brute force does not confirm), rotating segments are
// checked along OMPL's interpolation, states out of bounds are flagged.
#include <gtest/gtest.h>

#include <ompl/base/ScopedState.h>
#include <cmath>
#include <vector>

#include "mddual/constants.h"
#include "mddual/planning/example_scenes.h"
#include "mddual/planning/path_verifier.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;

/// The OMPL layer's thin-wall scene: a wall x in [50, 50.05], a cube robot of
/// side 0.2, bounds x in [0, 100], y in [-5, 5].
class VerifierTest : public ::testing::Test {
 protected:
  VerifierTest()
      : scene_(examples::thinWallScene(0.05)),
        r2_(examples::makeSpace(scene_, SpaceKind::kR2)),
        se2_(examples::makeSpace(scene_, SpaceKind::kSE2)),
        verifier_(scene_.robot, scene_.world, scene_.bounds) {}

  /// A path of `space` through poses (x, y, yaw).
  VerifyResult verify(const PlanningSpacePtr& space, const std::vector<Eigen::Vector3d>& xyyaw) const {
    std::vector<ob::ScopedState<>> states;
    std::vector<const ob::State*> path;
    for (const Eigen::Vector3d& p : xyyaw) {
      states.emplace_back(space->stateSpace());
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
      X.translation() = Eigen::Vector3d(p.x(), p.y(), 0.0);
      X.linear() = Eigen::AngleAxisd(p.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
      space->setPose(X, states.back().get());
    }
    for (const auto& s : states) path.push_back(s.get());
    return verifier_.verify(*space, path);
  }

  examples::ExampleScene scene_;
  PlanningSpacePtr r2_;
  PlanningSpacePtr se2_;
  PathVerifier verifier_;
};

TEST_F(VerifierTest, StepIsAFiftiethOfOmplsDefaultResolution) {
  EXPECT_NEAR(verifier_.step(), 0.01 * scene_.bounds.diagonal().norm() / 50.0, 1e-15);
  EXPECT_LT(verifier_.step(), 0.05);  // finer than the wall
  // The strict scene refines down to 1e-6 of the robot radius.
  EXPECT_NEAR(verifier_.mddScene().rotationTolerance() / std::ldexp(1.0, verifier_.mddScene().refinementLevels()),
              1e-6 * scene_.robot->radius(), 1e-18);
}

TEST_F(VerifierTest, PathThroughTheWallIsInvalidForBothChecks) {
  const VerifyResult r = verify(r2_, {{10, 0, 0}, {40, 1, 0}, {60, 1, 0}, {90, 0, 0}});
  EXPECT_FALSE(r.valid);
  EXPECT_TRUE(r.mdd_collision);
  EXPECT_TRUE(r.fcl_collision);
  EXPECT_FALSE(r.out_of_bounds);
  EXPECT_EQ(r.mdd_segment, 1);
  EXPECT_EQ(r.fcl_segment, 1);
  // First FCL hit: the robot's face (x + 0.1) within a step past x = 50.
  const double hit_x = 40 + 20 * r.fcl_fraction;
  EXPECT_GT(hit_x + 0.1, 50.0);
  EXPECT_LT(hit_x + 0.1, 50.0 + 0.05 + verifier_.step());
  EXPECT_GT(r.seconds, 0.0);
}

TEST_F(VerifierTest, FreePathsAreValid) {
  const VerifyResult r = verify(r2_, {{10, 0, 0}, {40, 2, 0}, {49.8, -3, 0}, {20, 4.5, 0}});
  EXPECT_TRUE(r.valid);
  EXPECT_FALSE(r.mdd_collision);
  EXPECT_FALSE(r.fcl_collision);
  EXPECT_GT(r.fcl_samples, 4);
  // The distance bound skips most of the open space: far fewer samples than
  // the path's length over the step.
  EXPECT_LT(r.fcl_samples, static_cast<long long>(80.0 / verifier_.step() / 4));
}

TEST_F(VerifierTest, AlmostTouchingIsFreeAndPenetratingIsNot) {
  // The face 1e-7 before the wall: free for both checks, whatever FCL's GJK
  // says there (a contact it reports is not confirmed by the brute force).
  const double gap = 1e-7;
  const VerifyResult near = verify(r2_, {{40, 0, 0}, {50 - 0.1 - gap, 0, 0}});
  EXPECT_TRUE(near.valid) << near.fcl_unconfirmed;
  // 1e-4 into the wall: both.
  const VerifyResult deep = verify(r2_, {{40, 0, 0}, {50 - 0.1 + 1e-4, 0, 0}});
  EXPECT_FALSE(deep.valid);
  EXPECT_TRUE(deep.mdd_collision);
  EXPECT_TRUE(deep.fcl_collision);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(50 - 0.1 + 1e-4, 0, 0);
  EXPECT_TRUE(verifier_.bruteForcePenetrates(X));
  X.translation().x() = 50 - 0.1 - gap;
  EXPECT_FALSE(verifier_.bruteForcePenetrates(X));
  X.translation().x() = 50 - 0.1;  // exactly touching: not a penetration for check (b)
  EXPECT_FALSE(verifier_.bruteForcePenetrates(X));
}

TEST_F(VerifierTest, RotatingSegments) {
  // At x = 49.88 the cube's face is 0.02 before the wall; turning by 90
  // degrees swings its corners (0.1414 from the centre) into it at 45.
  const VerifyResult turn = verify(se2_, {{30, 0, 0}, {49.88, 0, 0}, {49.88, 0, kPi / 2}});
  EXPECT_FALSE(turn.valid);
  EXPECT_TRUE(turn.mdd_collision);
  EXPECT_TRUE(turn.fcl_collision);
  EXPECT_EQ(turn.mdd_segment, 1);
  EXPECT_EQ(turn.fcl_segment, 1);
  // Closed form of the first contact: the cube's extent along x at yaw a is
  // 0.1 (cos a + sin a), which reaches the wall (0.12 ahead) at
  // a = asin(1.2 / sqrt 2) - pi / 4 = 0.2278, a fraction 0.1450 of the turn.
  // Past it the corner stays in the wall (its extent peaks at 0.1414 < 0.17),
  // so the dense check's first hit is the first sample after the contact: at
  // most one sample spacing later, 1 / ceil(L / step) with L the arc length
  // of the cube's farthest point (0.1 sqrt 3 from the centre) over the turn.
  const double first_contact = (std::asin(1.2 / std::sqrt(2.0)) - kPi / 4) / (kPi / 2);
  const double spacing = 1.0 / std::ceil(kPi / 2 * 0.1 * std::sqrt(3.0) / verifier_.step());
  EXPECT_NEAR(first_contact, 0.1450, 5e-5);
  EXPECT_GT(turn.fcl_fraction, first_contact);
  EXPECT_LE(turn.fcl_fraction, first_contact + spacing);
  // The same turn with room to spare (0.1 before the wall: 0.0414 > 0.02 + 0.0214).
  const VerifyResult room = verify(se2_, {{30, 0, 0}, {49.8, 0, 0}, {49.8, 0, kPi / 2}, {30, 3, -2.5}});
  EXPECT_TRUE(room.valid);
}

TEST_F(VerifierTest, StatesOutOfBounds) {
  Eigen::AlignedBox3d wide = scene_.bounds;
  wide.max().y() = 10;
  const PlanningSpacePtr space = PlanningSpace::make(SpaceKind::kR2, wide);
  const VerifyResult r = verify(space, {{10, 0, 0}, {10, 7, 0}});
  EXPECT_TRUE(r.out_of_bounds);
  EXPECT_FALSE(r.mdd_collision);
  EXPECT_FALSE(r.fcl_collision);
  EXPECT_FALSE(r.valid);
}

TEST_F(VerifierTest, SingleStateAndEmptyPaths) {
  EXPECT_TRUE(verify(r2_, {{10, 0, 0}}).valid);
  const VerifyResult in_wall = verify(r2_, {{50, 0, 0}});
  EXPECT_TRUE(in_wall.mdd_collision);
  EXPECT_TRUE(in_wall.fcl_collision);
  EXPECT_TRUE(verifier_.verify(*r2_, std::vector<const ob::State*>{}).valid);
}

}  // namespace
}  // namespace mddual::planning
