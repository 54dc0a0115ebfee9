// MddMotionValidator: soundness against a dense FCL check on random edges of
// the scenes (zero misses), exact first contacts on translation edges
// (against an FCL bisection, to 1e-9 of the edge), lastValid per OMPL's
// contract (testing::checkEdge, shared with tests/configs/
// test_mesh_soundness.cpp), the thin wall OMPL's discrete check passes through, and the FCL
// continuous validator on the same edges.
#include <gtest/gtest.h>

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/ScopedState.h>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "mddual/generators.h"
#include "test_support.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;
using testing::EdgeTally;
using testing::Fixture;

class MotionSoundness : public ::testing::TestWithParam<int> {};

TEST_P(MotionSoundness, NoMissesAndExactTranslationContacts) {
  const examples::ExampleScene& scene = testing::allScenes()[static_cast<std::size_t>(GetParam())];
  const Fixture fx = testing::makeFixture(scene);
  testing::Rng rng(testing::seed() * 7919 + static_cast<std::uint64_t>(GetParam()));
  const double extent = (scene.bounds.max() - scene.bounds.min()).head<2>().norm();
  const bool can_rotate = fx.space->kind() == SpaceKind::kSE2 || fx.space->kind() == SpaceKind::kSE3;
  // 2 edges each: 10,000 per file scene (the count), 1,000 per scene
  // built in code (10,000 at scale 10).
  const int n = (testing::isFileScene(GetParam()) ? 5000 : 500) * testing::scale();
  ob::ScopedState<> s1(fx.space->stateSpace()), s2(fx.space->stateSpace());
  EdgeTally translation, rotation;
  for (int i = 0; i < n; ++i) {
    for (bool second : {false, true}) {
      const bool rotate = second && can_rotate;  // translation-only spaces: two translation edges
      testing::randomValidState(*fx.si, *fx.space, rng, s1.get());
      // Short and long edges, and pure rotations.
      const double max_length = rotate && i % 5 == 1 ? 0.0 : (i % 3 == 0 ? 0.05 : 0.3) * extent;
      testing::randomEdgeEnd(*fx.space, s1.get(), max_length, rotate, kPi, rng, s2.get());
      testing::checkEdge(fx, s1.get(), s2.get(), rotate ? &rotation : &translation);
    }
  }
  for (const EdgeTally* t : {&translation, &rotation}) {
    if (t->edges == 0) continue;
    std::printf("%-10s %s %s %s\n", scene.name.c_str(), toString(fx.space->kind()),
                t == &translation ? "translation" : "rotating", testing::describe(*t).c_str());
    EXPECT_EQ(t->misses, 0);
    EXPECT_EQ(t->early, 0);
    EXPECT_EQ(t->fraction_errors, 0);
    // A mix of valid and invalid edges.
    EXPECT_GT(t->valid, t->edges / 20);
    EXPECT_LT(t->valid, t->edges - t->edges / 20);
  }
  if (translation.edges > 0) {
    EXPECT_GT(translation.fraction_checked, translation.edges / 10);
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, MotionSoundness, ::testing::Range(0, testing::kSceneCount), testing::sceneParamName);

// A robot of flat convex polygons of many corners, whose enlarged pieces are
// prisms over the polygons grown in their planes (enlargePiece, the 5,000-gon
// of the hostile-input hunt): no misses on rotating edges among the blobs.
TEST(MotionSoundness, FlatManyCorneredRobotPiecesHaveNoMisses) {
  examples::ExampleScene scene = examples::blobScene(testing::seed());
  std::vector<scene::Piece> robot;
  for (int k = 0; k < 2; ++k) {
    generators::Points points;
    const int n = k == 0 ? 40 : 24;
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * kPi * i / n;
      const Eigen::Vector3d p(0.9 * std::cos(a), 0.5 * std::sin(a), 0.0);
      points.push_back(k == 0 ? p : Eigen::Vector3d(0.3, p.x(), p.y()));  // the second in the plane x = 0.3
    }
    robot.push_back(
        scene::Piece::make(ConvexPolytope::fromPoints(points), scene::PieceKind::kConvex, "disc " + std::to_string(n)));
  }
  scene.robot = std::make_shared<scene::RigidBody>(std::move(robot), "discs");
  const Fixture fx = testing::makeFixture(scene);
  for (int i = 0; i < 2; ++i) {
    const ConvexPolytope& grown = fx.mdd->enlargedPiece(0, i).polytope;
    ASSERT_EQ(grown.numFaces(), grown.numVertices() / 2 + 2) << "robot piece " << i << " is enlarged as a prism";
  }
  testing::Rng rng(testing::seed() * 104729);
  const double extent = (scene.bounds.max() - scene.bounds.min()).head<2>().norm();
  ob::ScopedState<> s1(fx.space->stateSpace()), s2(fx.space->stateSpace());
  EdgeTally rotation;
  for (int i = 0; i < 1000 * testing::scale(); ++i) {
    testing::randomValidState(*fx.si, *fx.space, rng, s1.get());
    const double max_length = i % 5 == 1 ? 0.0 : (i % 3 == 0 ? 0.05 : 0.3) * extent;
    testing::randomEdgeEnd(*fx.space, s1.get(), max_length, true, kPi, rng, s2.get());
    testing::checkEdge(fx, s1.get(), s2.get(), &rotation);
  }
  std::printf("discs rotating %s\n", testing::describe(rotation).c_str());
  EXPECT_EQ(rotation.misses, 0);
  EXPECT_EQ(rotation.early, 0);
  EXPECT_GT(rotation.valid, rotation.edges / 20);
  EXPECT_LT(rotation.valid, rotation.edges - rotation.edges / 20);
}

// The dense check skips ahead by half FCL's distance over the largest point
// speed: sound when half FCL's distance never exceeds the true distance.
TEST_P(MotionSoundness, DenseCheckPremiseHalfFclDistanceIsALowerBound) {
  const examples::ExampleScene& scene = testing::allScenes()[static_cast<std::size_t>(GetParam())];
  const Fixture fx = testing::makeFixture(scene);
  testing::Rng rng(testing::seed() * 13 + static_cast<std::uint64_t>(GetParam()));
  ob::ScopedState<> s(fx.space->stateSpace());
  double worst_ratio = 0.0;
  int compared = 0;  // states with a finite FCL distance: the ones the premise is about
  // The trap's brute-force distances (hundreds of Minkowski differences
  // within FCL's distance) are slow: fewer states there (75 states take
  // 6 s; 25 took 6.9 s before distanceToTouching skipped the pairs beyond
  // its margin).
  const int states = (scene.name == "trap" ? 75 : 200) * testing::scale();
  for (int i = 0; i < states; ++i) {
    testing::randomValidState(*fx.si, *fx.space, rng, s.get());
    const Eigen::Isometry3d X = fx.space->pose(s.get());
    const double d_fcl = fx.fcl->distance(X);
    if (!std::isfinite(d_fcl)) continue;
    ++compared;
    const double d_true = testing::distanceToTouching(*fx.mdd, X, d_fcl + 1e-6);
    EXPECT_LE(0.5 * d_fcl, d_true + 1e-9) << scene.name << " state " << i;
    if (d_true > 0.0) worst_ratio = std::max(worst_ratio, d_fcl / d_true);
  }
  std::printf("%-10s FCL distance / true distance: at most %.6f (%d of %d states compared)\n", scene.name.c_str(),
              worst_ratio, compared, states);
  EXPECT_GE(compared, states * 9 / 10) << scene.name;  // all of them in every scene
}

// ---- The thin wall ------------------------------------------------------------------

TEST(ThinWall, DiscreteValidatorPassesThroughItOursDoesNot) {
  const examples::ExampleScene scene = examples::thinWallScene(0.05);
  const Fixture fx = testing::makeFixture(scene);
  const double resolution =
      fx.fcl_si->getStateValidityCheckingResolution() * fx.space->stateSpace()->getMaximumExtent();
  ASSERT_GT(resolution, 0.05 + 0.2);  // thinner than the resolution, robot included
  auto naive_options = FclCcdOptions();
  naive_options.solver = FclCcdSolver::kNaive;
  const FclContinuousMotionValidator naive(fx.fcl_si, fx.space, fx.fcl, naive_options);
  const FclContinuousMotionValidator ca(fx.fcl_si, fx.space, fx.fcl);
  auto many_options = FclCcdOptions();
  many_options.num_max_iterations = 1000;  // OMPL.app's request uses 10
  const FclContinuousMotionValidator ca_many(fx.fcl_si, fx.space, fx.fcl, many_options);
  testing::Rng rng(testing::seed());
  ob::ScopedState<> s1(fx.space->stateSpace()), s2(fx.space->stateSpace());
  const int n = 200 * testing::scale();
  int discrete_passes = 0, naive_passes = 0, ca_passes = 0, ca_many_passes = 0;
  for (int i = 0; i < n; ++i) {
    const double y = std::uniform_real_distribution<double>(-4.5, 4.5)(rng);
    const double x1 = std::uniform_real_distribution<double>(5.0, 45.0)(rng);
    const double x2 = std::uniform_real_distribution<double>(55.0, 95.0)(rng);
    s1[0] = x1;
    s1[1] = y;
    s2[0] = x2;
    s2[1] = y + std::uniform_real_distribution<double>(-0.5, 0.5)(rng);
    ASSERT_TRUE(fx.si->isValid(s1.get()));
    ASSERT_TRUE(fx.si->isValid(s2.get()));
    EXPECT_FALSE(fx.mdd_motion->checkMotion(s1.get(), s2.get()));
    // The exact first contact: the cube (half side 0.1) reaches x = 50.
    const EdgeContact first = fx.mdd_motion->firstInvalid(s1.get(), s2.get());
    EXPECT_NEAR(first.fraction, (49.9 - x1) / (x2 - x1), 1e-12);
    EXPECT_EQ(first.contact.world_piece, 0);
    EXPECT_NEAR(first.contact.n_W.x(), -1.0, 1e-12);  // from the wall toward the robot
    EXPECT_NEAR(first.contact.p_WC.x(), 50.0, 1e-9);
    discrete_passes += fx.fcl_si->checkMotion(s1.get(), s2.get());
    naive_passes += naive.checkMotion(s1.get(), s2.get());
    ca_passes += ca.checkMotion(s1.get(), s2.get());
    ca_many_passes += ca_many.checkMotion(s1.get(), s2.get());
  }
  std::printf(
      "thin wall (0.05, resolution %.3f): %d edges across it; passed by OMPL's discrete validator + FCL: %d, "
      "FCL naive CCD: %d, FCL conservative advancement: %d (%d with 1000 iterations), MDD: 0\n",
      resolution, n, discrete_passes, naive_passes, ca_passes, ca_many_passes);
  EXPECT_GT(discrete_passes, n / 2);  // OMPL's discrete check misses most of them
  EXPECT_GT(naive_passes, n / 2);     // the naive solver is a 10-sample discrete check
}

// Found by MotionSoundness at MDDUAL_PLANNING_SCALE=20 on the urdf scene:
// FCL's bisection put this translation edge's first contact 5.55e-7 of the
// edge after ours. The brute force (independent of both) has the robot
// touching at our fraction and 4.15e-7 deep at FCL's: FCL's intersection test
// missed that penetration, and ours is the exact contact.
TEST(MotionRegression, UrdfContactThatFclSeesLate) {
  const Fixture fx = testing::makeFixture(testing::allScenes()[4]);
  ASSERT_EQ(fx.scene.name, "urdf");
  ob::ScopedState<> s1(fx.space->stateSpace()), s2(fx.space->stateSpace());
  const Eigen::Quaterniond q(-0.44207756122140607, 0.72825734729570046, 0.25528676762021874, -0.45720600636079145);
  Eigen::Isometry3d X1 = Eigen::Isometry3d::Identity(), X2 = Eigen::Isometry3d::Identity();
  X1.linear() = X2.linear() = q.toRotationMatrix();
  X1.translation() << 3.8480775775434095, 1.3482686101760091, 3.802494305976039;
  X2.translation() << 5.3068438714743058, 0.00017899063311910268, 5.152350275553605;
  fx.space->setPose(X1, s1.get());
  fx.space->setPose(X2, s2.get());
  const EdgeContact c = fx.mdd_motion->firstInvalid(s1.get(), s2.get());
  ASSERT_TRUE(c.collides);
  EXPECT_TRUE(c.exact);
  EXPECT_NEAR(c.fraction, 0.94964930164692862, 1e-12);
  const EdgeMotion m = fx.space->motion(s1.get(), s2.get());
  const double fcl_fraction = 0.94964985710407657;  // FCL's bisection, as measured
  EXPECT_LE(testing::distanceToTouching(*fx.mdd, m.pose(c.fraction), 1e-6),
            testing::touchTolerance(*fx.mdd, m.pose(c.fraction)));
  EXPECT_GT(testing::distanceToTouching(*fx.mdd, m.pose(fcl_fraction), 1e-6), 1e-7);  // deep where FCL first sees it
  EXPECT_TRUE(fx.mdd->collides(m.pose(fcl_fraction)));
}

// ---- lastValid ------------------------------------------------------------------------

class LastValid : public ::testing::Test {
 protected:
  LastValid() : fx(testing::makeFixture(examples::thinWallScene(0.05))) {}
  Fixture fx;
};

TEST_F(LastValid, JustBeforeTheContact) {
  ob::ScopedState<> s1(fx.space->stateSpace()), s2(fx.space->stateSpace()), last(fx.space->stateSpace());
  s1[0] = 40.0;
  s1[1] = 1.0;
  s2[0] = 60.0;
  s2[1] = -1.0;
  std::pair<ob::State*, double> lv(last.get(), -1.0);
  EXPECT_FALSE(fx.mdd_motion->checkMotion(s1.get(), s2.get(), lv));
  const double contact = (49.9 - 40.0) / 20.0;
  EXPECT_LT(lv.second, contact);
  EXPECT_GT(lv.second, contact - 1e-8);
  EXPECT_TRUE(fx.si->isValid(last.get()));
  EXPECT_TRUE(fx.fcl_si->isValid(last.get()));
  ob::ScopedState<> expected(fx.space->stateSpace());
  fx.space->stateSpace()->interpolate(s1.get(), s2.get(), lv.second, expected.get());
  EXPECT_EQ(last, expected);
  // The motion up to lastValid is valid.
  EXPECT_TRUE(fx.mdd_motion->checkMotion(s1.get(), last.get()));
  // Without storage: the fraction alone.
  std::pair<ob::State*, double> fraction_only(nullptr, -1.0);
  EXPECT_FALSE(fx.mdd_motion->checkMotion(s1.get(), s2.get(), fraction_only));
  EXPECT_EQ(fraction_only.second, lv.second);
}

TEST_F(LastValid, EdgeStartingInCollisionIsInvalidAtZero) {
  ob::ScopedState<> s1(fx.space->stateSpace()), s2(fx.space->stateSpace()), last(fx.space->stateSpace());
  s1[0] = 50.0;  // inside the wall
  s1[1] = 0.0;
  s2[0] = 30.0;
  s2[1] = 0.0;
  std::pair<ob::State*, double> lv(last.get(), -1.0);
  EXPECT_FALSE(fx.mdd_motion->checkMotion(s1.get(), s2.get()));
  EXPECT_FALSE(fx.mdd_motion->checkMotion(s1.get(), s2.get(), lv));
  EXPECT_EQ(lv.second, 0.0);
  EXPECT_EQ(last, s1);
  EXPECT_TRUE(fx.mdd_motion->firstInvalid(s1.get(), s2.get()).start_collides);
  EXPECT_TRUE(fx.mdd_motion->firstInvalid(s1.get(), s2.get(), EdgeQuery::kLastValid).start_collides);
  // kValidity computes no first contact: refused, not a meaningless fraction.
  EXPECT_THROW(fx.mdd_motion->firstInvalid(s1.get(), s2.get(), EdgeQuery::kValidity), InvalidInputError);
}

TEST_F(LastValid, ValidEdgeLeavesItUntouched) {
  ob::ScopedState<> s1(fx.space->stateSpace()), s2(fx.space->stateSpace()), last(fx.space->stateSpace());
  s1[0] = 10.0;
  s1[1] = 0.0;
  s2[0] = 40.0;
  s2[1] = 3.0;
  last[0] = 77.0;
  last[1] = 2.0;
  std::pair<ob::State*, double> lv(last.get(), -1.0);
  EXPECT_TRUE(fx.mdd_motion->checkMotion(s1.get(), s2.get(), lv));
  EXPECT_EQ(lv.second, -1.0);
  EXPECT_EQ(last[0], 77.0);
}

TEST_F(LastValid, LeavingTheBounds) {
  ob::ScopedState<> s1(fx.space->stateSpace()), s2(fx.space->stateSpace()), last(fx.space->stateSpace());
  s1[0] = 10.0;
  s1[1] = 0.0;
  s2[0] = 10.0;
  s2[1] = 15.0;  // bounds: |y| <= 5
  std::pair<ob::State*, double> lv(last.get(), -1.0);
  EXPECT_FALSE(fx.mdd_motion->checkMotion(s1.get(), s2.get()));
  EXPECT_FALSE(fx.mdd_motion->checkMotion(s1.get(), s2.get(), lv));
  EXPECT_NEAR(lv.second, 5.0 / 15.0, 1e-8);
  EXPECT_LE(lv.second, 5.0 / 15.0 + 1e-15);
  EXPECT_TRUE(fx.si->isValid(last.get()));
}

TEST_F(LastValid, CountersCountEveryCheck) {
  fx.mdd_motion->resetCounts();
  fx.mdd_motion->resetMotionCounter();
  ob::ScopedState<> s1(fx.space->stateSpace()), s2(fx.space->stateSpace());
  s1[0] = 10.0;
  s1[1] = 0.0;
  s2[0] = 30.0;
  s2[1] = 0.0;
  EXPECT_TRUE(fx.mdd_motion->checkMotion(s1.get(), s2.get()));
  s2[0] = 70.0;
  EXPECT_FALSE(fx.mdd_motion->checkMotion(s1.get(), s2.get()));
  const CheckerCounts c = fx.mdd_motion->counts();
  EXPECT_EQ(c.motion_checks, 2u);
  EXPECT_GE(c.pair_queries, 1u);
  EXPECT_GT(c.seconds, 0.0);
  EXPECT_EQ(fx.mdd_motion->getValidMotionCount(), 1u);
  EXPECT_EQ(fx.mdd_motion->getInvalidMotionCount(), 1u);
  fx.mdd_motion->resetCounts();
  EXPECT_EQ(fx.mdd_motion->counts().motion_checks, 0u);
}

// A planner that drops every lastValid at or below a fraction (the
// min_valid_path_fraction of KPIECE and STRIDE, 0.2 by default, and of BKPIECE
// and LBKPIECE, 0.5): with the shortcut on, each of its decisions on random
// rotating edges (valid; kept part; dropped) is the one it makes with no
// discarded fraction (the search, or the first-step shortcut where the state
// one step in collides), and the shortcut's answer is (s1, 0) only where the
// state at the fraction collides. Scenes: mesh (SE(3)), planar (SE(2)), trap
// (SE(3)).
TEST(LastValidDiscard, APlannerDecidesAsWithoutTheShortcut) {
  const std::array<double, 2> fractions{0.2, 0.5};
  std::array<int, 2> shortcuts{0, 0}, kept{0, 0};
  int invalid = 0, edges = 0;
  for (const int index : {1, 2, 8}) {
    const examples::ExampleScene& scene = testing::allScenes()[static_cast<std::size_t>(index)];
    const Fixture fx = testing::makeFixture(scene);
    testing::Rng rng(testing::seed() * 104729 + static_cast<std::uint64_t>(index));
    const double extent = (scene.bounds.max() - scene.bounds.min()).head<2>().norm();
    ob::ScopedState<> s1(fx.space->stateSpace()), s2(fx.space->stateSpace());
    ob::ScopedState<> last_off(fx.space->stateSpace()), last_on(fx.space->stateSpace());
    for (int i = 0; i < 150 * testing::scale(); ++i) {
      testing::randomValidState(*fx.si, *fx.space, rng, s1.get());
      testing::randomEdgeEnd(*fx.space, s1.get(), (i % 2 == 0 ? 0.1 : 0.3) * extent, true, kPi, rng, s2.get());
      const std::string where =
          scene.name + " edge " + std::to_string(i) + ": " + testing::edgeString(fx, s1.get(), s2.get());
      std::pair<ob::State*, double> off(last_off.get(), -1.0);
      fx.mdd_motion->setDiscardedLastValidFraction(0.0);
      const bool valid_off = fx.mdd_motion->checkMotion(s1.get(), s2.get(), off);
      // As KPIECE1 calls it: lastValid.first is the end state itself.
      ob::ScopedState<> s2_alias(s2);
      std::pair<ob::State*, double> alias(s2_alias.get(), -1.0);
      EXPECT_EQ(fx.mdd_motion->checkMotion(s1.get(), s2_alias.get(), alias), valid_off) << where;
      if (!valid_off) {
        EXPECT_EQ(alias.second, off.second) << where;
        EXPECT_EQ(s2_alias, last_off) << where;
      }
      ++edges;
      invalid += valid_off ? 0 : 1;
      for (std::size_t k = 0; k < fractions.size(); ++k) {
        const double f = fractions[k];
        std::pair<ob::State*, double> on(last_on.get(), -1.0);
        fx.mdd_motion->setDiscardedLastValidFraction(f);
        const bool valid_on = fx.mdd_motion->checkMotion(s1.get(), s2.get(), on);
        fx.mdd_motion->setDiscardedLastValidFraction(0.0);
        ASSERT_EQ(valid_on, valid_off) << where << " fraction " << f;
        if (valid_on) continue;
        EXPECT_EQ(on.second > f, off.second > f)
            << where << " fraction " << f << " lastValid " << on.second << " / " << off.second;
        const bool collides_at_f = fx.mdd->collides(fx.space->motion(s1.get(), s2.get()).pose(f));
        if (collides_at_f) {
          ++shortcuts[k];
          EXPECT_EQ(on.second, 0.0) << where << " fraction " << f;
          EXPECT_EQ(last_on, s1) << where << " fraction " << f;
        } else if (off.second == 0.0 && on.second > 0.0) {
          // Without a discarded fraction, the first-step shortcut (and only
          // it: the state one step in collides): both within the edge's
          // first discrete step, below f either way.
          const unsigned int steps = fx.si->getStateSpace()->validSegmentCount(s1.get(), s2.get());
          ASSERT_GE(steps, 2u) << where;
          const double step = 1.0 / steps;
          EXPECT_TRUE(fx.mdd->collides(fx.space->motion(s1.get(), s2.get()).pose(step))) << where;
          EXPECT_LE(on.second, step) << where << " fraction " << f;
          EXPECT_LT(step, f) << where;
        } else {
          EXPECT_EQ(on.second, off.second) << where << " fraction " << f;
          EXPECT_EQ(last_on, last_off) << where << " fraction " << f;
        }
        kept[k] += off.second > f;
      }
    }
  }
  for (std::size_t k = 0; k < fractions.size(); ++k) {
    std::printf("fraction %.1f: %d edges, %d invalid: %d shortcuts, %d kept parts\n", fractions[k], edges, invalid,
                shortcuts[k], kept[k]);
    // Not a degenerate sample: both kinds of invalid edge.
    EXPECT_GT(shortcuts[k], invalid / 10) << "fraction " << fractions[k];
    EXPECT_GT(kept[k], invalid / 10) << "fraction " << fractions[k];
  }
}

// Edges as a planner that extends up to lastValid makes them (mdd_rrtconnect):
// each starts at the lastValid state of a blocked rotating edge, a fraction
// of a discrete step from an obstacle. Most are blocked within their first
// step, where lastValid is (s1, 0) after one state test (the first-step
// shortcut); testing::checkEdge holds each to OMPL's contract and the dense
// FCL check, and to a first contact within that step.
TEST(LastValidFirstStep, EdgesFromABlockedEdgesLastValidKeepTheContract) {
  int chained = 0, invalid = 0, shortcuts = 0, below_bound = 0;
  for (const int index : {1, 2, 8}) {
    const examples::ExampleScene& scene = testing::allScenes()[static_cast<std::size_t>(index)];
    const Fixture fx = testing::makeFixture(scene);
    testing::Rng rng(testing::seed() * 7727 + static_cast<std::uint64_t>(index));
    const double extent = (scene.bounds.max() - scene.bounds.min()).head<2>().norm();
    ob::ScopedState<> s1(fx.space->stateSpace()), s2(fx.space->stateSpace()), last(fx.space->stateSpace());
    testing::EdgeTally tally;
    for (int i = 0; i < 100 * testing::scale(); ++i) {
      testing::randomValidState(*fx.si, *fx.space, rng, s1.get());
      testing::randomEdgeEnd(*fx.space, s1.get(), 0.3 * extent, true, kPi, rng, s2.get());
      std::pair<ob::State*, double> lv(last.get(), -1.0);
      if (fx.mdd_motion->checkMotion(s1.get(), s2.get(), lv) || lv.second == 0.0) continue;
      // The next extension: from lastValid toward a new random target.
      testing::randomEdgeEnd(*fx.space, last.get(), 0.3 * extent, true, kPi, rng, s2.get());
      const int before = tally.edges - tally.valid;
      testing::checkEdge(fx, last.get(), s2.get(), &tally);
      ++chained;
      invalid += tally.edges - tally.valid - before;
    }
    std::printf("%-10s chained %s\n", scene.name.c_str(), testing::describe(tally).c_str());
    EXPECT_EQ(tally.misses, 0);
    EXPECT_EQ(tally.early, 0);
    shortcuts += tally.first_step;
    below_bound += tally.first_step_below_bound;
  }
  std::printf("%d chained edges, %d invalid, %d by the first step (%d below the search's bound)\n", chained, invalid,
              shortcuts, below_bound);
  // Not a degenerate sample: the first step blocks many of them, not all;
  // and the shortcut acts (a lastValid of 0 where the search's bound is not).
  EXPECT_GT(shortcuts, invalid / 5);
  EXPECT_LT(shortcuts, invalid);
  EXPECT_GT(below_bound, 0);
}

// One such edge, pinned (the mesh scene, found by the test above): the state
// one step in (1/88 of the edge) collides, so lastValid is (s1, 0); the
// kLastValid search's bound (0.00225) and the first contact (0.00671) lie
// within that step. With a discarded fraction set (here 1e-9, whose state is
// free) the first-step shortcut is off and lastValid is the search's bound,
// backed off: the 0 above is the shortcut's.
TEST(LastValidFirstStep, PinnedEdgeBlockedInItsFirstStepKeepsItsStart) {
  const Fixture fx = testing::makeFixture(testing::allScenes()[1]);
  ASSERT_EQ(fx.scene.name, "mesh");
  ob::ScopedState<> s1(fx.space->stateSpace()), s2(fx.space->stateSpace()), last(fx.space->stateSpace());
  const auto pose = [](double x, double y, double z, double qw, double qx, double qy, double qz) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix();
    X.translation() << x, y, z;
    return X;
  };
  fx.space->setPose(pose(-1.8005309539688028, -8.8119905959946614, 1.0556007870172381, 0.76698515544302048,
                         0.018718895577888771, -0.62250922365943151, 0.15448508257214277),
                    s1.get());
  fx.space->setPose(pose(0.78855840755691808, -11.0984887032596, -3.8113636368144341, 0.62189452719405924,
                         0.33858634871090715, 0.31017729783866244, -0.63434732238593028),
                    s2.get());
  const double step = 1.0 / fx.si->getStateSpace()->validSegmentCount(s1.get(), s2.get());
  const EdgeMotion motion = fx.space->motion(s1.get(), s2.get());
  ASSERT_TRUE(motion.rotates());
  ASSERT_TRUE(fx.si->isValid(s1.get()));
  ASSERT_TRUE(fx.mdd->collides(motion.pose(step)));
  const EdgeContact first = fx.mdd_motion->firstInvalid(s1.get(), s2.get());
  const EdgeContact bound = fx.mdd_motion->firstInvalid(s1.get(), s2.get(), EdgeQuery::kLastValid);
  EXPECT_GT(bound.fraction, 1e-3);
  EXPECT_LE(bound.fraction, first.fraction);
  EXPECT_LE(first.fraction, step);
  std::pair<ob::State*, double> lv(last.get(), -1.0);
  EXPECT_FALSE(fx.mdd_motion->checkMotion(s1.get(), s2.get(), lv));
  EXPECT_EQ(lv.second, 0.0);
  EXPECT_EQ(last, s1);
  fx.mdd_motion->setDiscardedLastValidFraction(1e-9);
  std::pair<ob::State*, double> lv_search(last.get(), -1.0);
  EXPECT_FALSE(fx.mdd_motion->checkMotion(s1.get(), s2.get(), lv_search));
  fx.mdd_motion->setDiscardedLastValidFraction(0.0);
  EXPECT_GT(lv_search.second, 0.0);
  EXPECT_LE(lv_search.second, bound.fraction);
}

TEST(LastValidDiscard, FractionOutsideZeroToOneIsRefused) {
  const Fixture fx = testing::makeFixture(testing::allScenes()[1]);
  for (const double bad : {-0.1, 1.5, 2.0, testing::kNaN}) {
    EXPECT_THROW(fx.mdd_motion->setDiscardedLastValidFraction(bad), InvalidInputError) << bad;
  }
  EXPECT_EQ(fx.mdd_motion->discardedLastValidFraction(), 0.0);
  fx.mdd_motion->setDiscardedLastValidFraction(1.0);  // KPIECE accepts 1: every failed edge dropped
  EXPECT_EQ(fx.mdd_motion->discardedLastValidFraction(), 1.0);
}

// ---- Edges of the MddScene directly ----------------------------------------------------

TEST(MddSceneEdges, SubThresholdRotationChecksTheEndState) {
  // OMPL keeps the start orientation along an SE(3) edge rotating by less than
  // its threshold, but s2 itself is rotated: that state is checked as well.
  const examples::ExampleScene scene = examples::thinWallScene(0.05);
  const MddScene mdd(scene.robot, scene.world);
  EdgeMotion m;
  m.p_start = Eigen::Vector3d(49.87, 0, 0);  // the cube reaches x = 49.97 < 50
  m.p_end = m.p_start;
  m.X_end = Eigen::Isometry3d::Identity();
  m.X_end.translation() = m.p_end;
  EXPECT_FALSE(mdd.checkEdge(m).collides);
  // Rotated by 45 degrees at the same place, its corner reaches 50.01.
  m.X_end.linear() = Eigen::AngleAxisd(kPi / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const EdgeContact e = mdd.checkEdge(m);
  EXPECT_TRUE(e.collides);
  EXPECT_EQ(e.fraction, 1.0);
}

TEST(MddSceneEdges, PureRotationNearAWallIsChecked) {
  // A 2 x 0.2 bar spinning in place next to a wall it reaches only mid-turn.
  std::vector<scene::Piece> robot{examples::convexPiece(generators::box({1.0, 0.1, 0.1}), "bar")};
  std::vector<scene::Piece> world{examples::convexPiece(generators::box({0.1, 0.1, 0.1}), "post")};  // at the origin
  auto body = std::make_shared<scene::RigidBody>(std::move(robot), "bar");
  auto w = std::make_shared<scene::World>(std::move(world), "post");
  const MddScene mdd(body, w);
  EdgeMotion m;
  m.p_start = m.p_end = Eigen::Vector3d(0.0, 0.5, 0.0);  // the bar at y = 0.5, parallel to x
  m.axis_R = Eigen::Vector3d::UnitZ();
  m.angle = kPi / 2;  // turns to parallel to y: crosses the post
  m.X_end = m.pose(1.0);
  EXPECT_FALSE(mdd.collides(m.pose(0.0)));
  EXPECT_TRUE(mdd.collides(m.pose(1.0)));
  const EdgeContact e = mdd.checkEdge(m);
  EXPECT_TRUE(e.collides);
  EXPECT_FALSE(e.exact);
  // The first contact: the bar's near face (y = 0.4 at angle 0) reaches the
  // post (y = 0.1) when the bar's corner sweeps down; the lower bound is before it.
  double first = 1.0;
  for (int k = 0; k <= 100000; ++k) {
    if (mdd.collides(m.pose(k * 1e-5))) {
      first = k * 1e-5;
      break;
    }
  }
  EXPECT_LE(e.fraction, first);
  EXPECT_GT(e.fraction, first - 0.05);
  EXPECT_GT(e.sub_edges, 0);
}

}  // namespace
}  // namespace mddual::planning
