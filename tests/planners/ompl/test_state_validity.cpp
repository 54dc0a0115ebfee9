// MddStateValidityChecker against FclStateValidityChecker over the same
// pieces: the same answer on random states of the four scenes, except states
// within 1e-9 of touching (decided by the brute-force Minkowski difference,
// independent of both).
#include <gtest/gtest.h>

#include <ompl/base/ScopedState.h>
#include <cstdio>

#include "mddual/generators.h"
#include "mddual/planning/mdd_checkers.h"
#include "test_support.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;
using testing::Fixture;

struct Tally {
  int states = 0;
  int colliding = 0;
  int out_of_bounds = 0;
  int near_touching = 0;
  int disagreements = 0;
};

Tally compare(const Fixture& fx, int n, std::uint64_t seed) {
  testing::Rng rng(seed);
  Tally tally;
  ob::ScopedState<> s(fx.space->stateSpace());
  // Sample a box slightly larger than the bounds so the bounds check is exercised.
  for (int i = 0; i < n; ++i) {
    testing::randomState(*fx.space, rng, s.get());
    const bool mdd = fx.mdd_checker->isValid(s.get());
    const bool fcl = fx.fcl_checker->isValid(s.get());
    ++tally.states;
    tally.colliding += !mdd;
    if (mdd == fcl) continue;
    const Eigen::Isometry3d X = fx.space->pose(s.get());
    const double d = testing::distanceToTouching(*fx.mdd, X, 1e-6);
    if (d <= testing::touchTolerance(*fx.mdd, X)) {
      ++tally.near_touching;
      continue;
    }
    ++tally.disagreements;
    ADD_FAILURE() << fx.scene.name << ": state " << i << " MDD " << (mdd ? "valid" : "invalid") << ", FCL "
                  << (fcl ? "valid" : "invalid") << ", brute-force distance to touching " << d;
  }
  // Out-of-bounds states: both reject them.
  ob::ScopedState<> out(fx.space->stateSpace());
  for (int i = 0; i < 50; ++i) {
    testing::randomState(*fx.space, rng, out.get());
    Eigen::Isometry3d X = fx.space->pose(out.get());
    X.translation().x() = fx.space->bounds().max().x() + 0.5 + i;
    fx.space->setPose(X, out.get());
    EXPECT_FALSE(fx.mdd_checker->isValid(out.get()));
    EXPECT_FALSE(fx.fcl_checker->isValid(out.get()));
    ++tally.out_of_bounds;
  }
  return tally;
}

class StateAgreement : public ::testing::TestWithParam<int> {};

TEST_P(StateAgreement, MddAndFclAgreeOnRandomStates) {
  const examples::ExampleScene& scene = testing::allScenes()[static_cast<std::size_t>(GetParam())];
  const Fixture fx = testing::makeFixture(scene);
  const int n = 25000 * testing::scale();  // 100,000 over the four file scenes, as many over the others
  const Tally t = compare(fx, n, testing::seed() * 1000 + static_cast<std::uint64_t>(GetParam()));
  std::printf(
      "%-10s %s: %d states, %d colliding (%.1f%%), %d near touching excepted, %d disagreements; "
      "pair queries per check: MDD %.2f, FCL %.2f\n",
      scene.name.c_str(), toString(fx.space->kind()), t.states, t.colliding, 100.0 * t.colliding / t.states,
      t.near_touching, t.disagreements,
      static_cast<double>(fx.mdd_checker->counts().pair_queries) /
          static_cast<double>(fx.mdd_checker->counts().state_checks),
      static_cast<double>(fx.fcl_checker->counts().pair_queries) /
          static_cast<double>(fx.fcl_checker->counts().state_checks));
  EXPECT_EQ(t.disagreements, 0);
  // The sample must mix free and colliding states, or agreement means little.
  EXPECT_GT(t.colliding, n / 50);
  EXPECT_LT(t.colliding, n - n / 50);
  EXPECT_EQ(fx.mdd_checker->counts().state_checks, static_cast<std::uint64_t>(n + t.out_of_bounds));
}

INSTANTIATE_TEST_SUITE_P(Scenes, StateAgreement, ::testing::Range(0, testing::kSceneCount), testing::sceneParamName);

TEST(StateValidity, TouchingCountsAsCollision) {
  // A unit cube robot resting exactly on a slab: invalid; lifted by 1e-6: valid.
  std::vector<scene::Piece> robot{examples::convexPiece(generators::box({0.5, 0.5, 0.5}), "cube")};
  std::vector<Eigen::Vector3d> slab = generators::box({5, 5, 0.5});
  for (Eigen::Vector3d& p : slab) p.z() -= 0.5;
  std::vector<scene::Piece> world{examples::convexPiece(slab, "slab")};
  examples::ExampleScene scene;
  scene.robot = std::make_shared<scene::RigidBody>(std::move(robot), "cube");
  scene.world = std::make_shared<scene::World>(std::move(world), "slab");
  scene.bounds = Eigen::AlignedBox3d(Eigen::Vector3d(-4, -4, -4), Eigen::Vector3d(4, 4, 4));
  scene.kind = SpaceKind::kR3;
  const Fixture fx = testing::makeFixture(scene);
  ob::ScopedState<> s(fx.space->stateSpace());
  s[0] = 0.3;
  s[1] = -0.2;
  s[2] = 0.5;
  EXPECT_FALSE(fx.mdd_checker->isValid(s.get()));
  s[2] = 0.5 + 1e-6;
  EXPECT_TRUE(fx.mdd_checker->isValid(s.get()));
  EXPECT_TRUE(fx.fcl_checker->isValid(s.get()));
  s[2] = 0.4;
  EXPECT_FALSE(fx.mdd_checker->isValid(s.get()));
  EXPECT_FALSE(fx.fcl_checker->isValid(s.get()));
}

}  // namespace
}  // namespace mddual::planning
