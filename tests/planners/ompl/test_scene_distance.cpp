// sceneDistance() and MddStateValidityChecker::clearance()
// against FCL's distance over the same pieces: on random states of every test
// scene, the clearance of a free state equals the smallest FCL distance over
// the (robot piece, world piece) pairs to 1e-9 of the scene's size; a
// colliding state has clearance <= 0, minus the largest pair penetration
// depth (brute force); OMPL's MaximizeMinClearanceObjective
// now sees it.
//
// The FCL oracle: each pair as two fcl::Convex (the pieces' vertices and
// faces), fcl::distance with a tight tolerance, the smaller of libccd's and
// FCL's own GJK answers (FCL 0.7 overestimates some pairs with either: on the
// planar scene's extruded polygons libccd gave 2.850 where the brute force
// and we give 2.750; as FclScene::distance). Pairs whose
// bounding spheres are farther apart than our answer plus the tolerance are
// skipped: they cannot be nearer than our answer, so the skip cannot hide an
// answer that is too large, and an answer that is too small leaves the
// oracle's minimum above it (a failure too); the same for the pairs whose
// bounding boxes are that far apart.
#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/distance.h>
#include <gtest/gtest.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/objectives/MaximizeMinClearanceObjective.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "mddual/fcl_interop.h"
#include "mddual/penetration.h"
#include "mddual/planning/fcl_checkers.h"
#include "mddual/planning/scene_distance.h"
#include "test_support.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;
using testing::Fixture;

constexpr double kAccuracyRel = 1e-9;  ///< of the scene's size

/// The FCL models of a scene's pieces, built once per scene.
class FclPieces {
 public:
  explicit FclPieces(const MddScene& scene) : scene_(scene) {
    for (const auto& p : scene.robot().pieces()) robot_.push_back(toFclConvex(p.polytope));
  }
  /// Smallest FCL distance over the pairs whose sphere gap and box gap are
  /// both below `limit` (+infinity if none); `pairs` counts the FCL calls.
  double distance(const Eigen::Isometry3d& X_WR, double limit, int* pairs) {
    double best = std::numeric_limits<double>::infinity();
    const auto& robot = scene_.robot().pieces();
    const auto& world = scene_.world().pieces();
    for (std::size_t i = 0; i < robot.size(); ++i) {
      const Eigen::Vector3d c_W = X_WR * robot[i].centre;
      const Eigen::AlignedBox3d box_W = scene::transformedBox(robot[i].box, X_WR);
      for (std::size_t j = 0; j < world.size(); ++j) {
        const double gap = (c_W - world[j].centre).norm() - robot[i].radius - world[j].radius;
        if (gap > limit) continue;
        // The boxes' gap bounds the pair's distance from below too, and is far
        // tighter for the large flat walls of the trap, whose spheres are wide.
        if (box_W.exteriorDistance(world[j].box) > limit) continue;
        const fcl::Transform3<double> X_a = X_WR;
        const fcl::Transform3<double> X_b = fcl::Transform3<double>::Identity();
        for (const fcl::GJKSolverType solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
          fcl::DistanceRequest<double> request;
          request.gjk_solver_type = solver;
          request.distance_tolerance = 1e-14;
          fcl::DistanceResult<double> result;
          best = std::min(best, fcl::distance(robot_[i].get(), X_a, worldModel(j).get(), X_b, request, result));
        }
        ++*pairs;
      }
    }
    return best;
  }

 private:
  std::shared_ptr<fcl::Convex<double>> worldModel(std::size_t j) {
    auto it = world_.find(j);
    if (it == world_.end()) it = world_.emplace(j, toFclConvex(scene_.world().pieces()[j].polytope)).first;
    return it->second;
  }
  const MddScene& scene_;
  std::vector<std::shared_ptr<fcl::Convex<double>>> robot_;
  std::map<std::size_t, std::shared_ptr<fcl::Convex<double>>> world_;
};

/// Minus the largest penetration depth over the (robot piece, world piece)
/// pairs whose boxes and bounding spheres meet, by the brute force (0 if none
/// penetrates).
double bruteDeepest(const MddScene& scene, const Eigen::Isometry3d& X_WR) {
  double best = 0.0;
  std::vector<int> candidates;
  for (const scene::Piece& piece : scene.robot().pieces()) {
    const Eigen::Vector3d c_W = X_WR * piece.centre;
    candidates.clear();
    scene.world().candidates(scene::transformedBox(piece.box, X_WR), &candidates);
    for (int j : candidates) {
      // Bounding spheres apart: the pair does not penetrate (depth 0).
      const scene::Piece& obstacle = scene.world().pieces()[static_cast<std::size_t>(j)];
      if ((c_W - obstacle.centre).norm() > piece.radius + obstacle.radius) continue;
      PenetrationInput in;
      in.a = &piece.polytope;
      in.X_WA = X_WR;
      in.b = &scene.world().pieces()[static_cast<std::size_t>(j)].polytope;
      in.method = PenetrationMethod::kBruteForce;
      best = std::min(best, -penetrationDepth(in).depth);
    }
  }
  return best;
}

double sceneSize(const Fixture& fx) {
  return fx.mdd->world().box().diagonal().norm() + fx.mdd->robot().radius();
}

class SceneDistanceAgreement : public ::testing::TestWithParam<int> {};

TEST_P(SceneDistanceAgreement, ClearanceMatchesFclOnRandomStates) {
  const examples::ExampleScene& scene = testing::allScenes()[static_cast<std::size_t>(GetParam())];
  const Fixture fx = testing::makeFixture(scene);
  ASSERT_EQ(fx.mdd_checker->getSpecs().clearanceComputationType, ob::StateValidityCheckerSpecs::EXACT);
  FclPieces fcl(*fx.mdd);
  const double tol = kAccuracyRel * sceneSize(fx);
  testing::Rng rng(testing::seed() * 2000 + static_cast<std::uint64_t>(GetParam()));
  ob::ScopedState<> s(fx.space->stateSpace());
  const int n = 150 * testing::scale();
  int free = 0;
  int colliding = 0;
  int near_touching = 0;
  int fcl_pairs = 0;
  double max_err = 0.0;
  double max_err_brute = 0.0;
  double max_err_colliding = 0.0;
  for (int i = 0; i < n && !HasFailure(); ++i) {
    testing::randomState(*fx.space, rng, s.get());
    const Eigen::Isometry3d X = fx.space->pose(s.get());
    const double c = fx.mdd_checker->clearance(s.get());
    const SceneDistance d = sceneDistance(*fx.mdd, X);
    EXPECT_EQ(c, d.distance);
    const bool collides = fx.mdd->collides(X);
    if (collides) {
      ++colliding;
      EXPECT_LE(c, 0.0) << scene.name << " state " << i;
      // Minus the largest penetration depth over the pairs, by the brute force.
      const double deepest = bruteDeepest(*fx.mdd, X);
      max_err_colliding = std::max(max_err_colliding, std::abs(deepest - c) / sceneSize(fx));
      EXPECT_NEAR(c, deepest, tol) << scene.name << " state " << i;
      continue;
    }
    if (c <= tol) {  // free by intersect() but within the tolerance of touching
      ++near_touching;
      EXPECT_GE(c, 0.0) << scene.name << " state " << i;
      continue;
    }
    ++free;
    ASSERT_GE(d.robot_piece, 0);
    EXPECT_NEAR((d.p_W_robot - d.p_W_world).norm(), c, tol);
    const double f = fcl.distance(X, c + tol, &fcl_pairs);
    const double err = std::abs(f - c);
    max_err = std::max(max_err, err / sceneSize(fx));
    EXPECT_LE(err, tol) << scene.name << " state " << i << ": clearance " << c << ", FCL " << f;
    // The brute force (explicit Minkowski differences of the pairs whose
    // boxes come within c + tol: the same soundness argument as above).
    const double brute = testing::distanceToTouching(*fx.mdd, X, c + tol);
    max_err_brute = std::max(max_err_brute, std::abs(brute - c) / sceneSize(fx));
    EXPECT_NEAR(brute, c, tol) << scene.name << " state " << i;
  }
  std::printf(
      "%-10s %d states: %d free (compared, %d FCL pair distances), %d colliding, %d near touching; "
      "max |clearance - oracle| / scene size: FCL %.3g, brute force %.3g, colliding (-PD, brute force) %.3g\n",
      scene.name.c_str(), n, free, fcl_pairs, colliding, near_touching, max_err, max_err_brute, max_err_colliding);
  EXPECT_GE(free, n / 10);
}

INSTANTIATE_TEST_SUITE_P(Scenes, SceneDistanceAgreement,
                         ::testing::Range(0, static_cast<int>(testing::allScenes().size())), testing::sceneParamName);

TEST(SceneDistance, CollidingStatesHaveNonPositiveClearanceAndDeeperIsLower) {
  // The robot placed on a world piece's centre overlaps it; the clearance is
  // then minus a penetration depth, at most the piece pair's sphere overlap.
  const examples::ExampleScene& scene = testing::allScenes()[0];
  const Fixture fx = testing::makeFixture(scene);
  ob::ScopedState<> s(fx.space->stateSpace());
  int tested = 0;
  for (std::size_t j = 0; j < fx.mdd->world().pieces().size() && tested < 10; ++j) {
    const scene::Piece& piece = fx.mdd->world().pieces()[j];
    if (piece.kind != scene::PieceKind::kConvex) continue;
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = piece.centre - fx.mdd->robot().pieces()[0].centre;
    fx.space->setPose(X, s.get());
    const SceneDistance d = sceneDistance(*fx.mdd, fx.space->pose(s.get()));
    EXPECT_TRUE(fx.mdd->collides(fx.space->pose(s.get())));
    EXPECT_LT(d.distance, 0.0);
    EXPECT_EQ(d.status, DistanceStatus::kPenetrating);
    EXPECT_EQ(fx.mdd_checker->clearance(s.get()), d.distance);
    ++tested;
  }
  EXPECT_GE(tested, 5);
}

TEST(SceneDistance, MaxMinClearanceObjectiveUsesIt) {
  const examples::ExampleScene& scene = testing::allScenes()[0];
  const Fixture fx = testing::makeFixture(scene);
  ob::MaximizeMinClearanceObjective objective(fx.si);
  testing::Rng rng(testing::seed());
  ob::ScopedState<> s(fx.space->stateSpace());
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (int i = 0; i < 40; ++i) {
    testing::randomValidState(*fx.si, *fx.space, rng, s.get());
    const double cost = objective.stateCost(s.get()).value();
    EXPECT_EQ(cost, fx.mdd_checker->clearance(s.get()));
    lo = std::min(lo, cost);
    hi = std::max(hi, cost);
  }
  EXPECT_GT(lo, 0.0);  // valid states are free
  EXPECT_GT(hi, lo);   // and the cost depends on the state
  // OMPL's isValid(state, dist) reports the same clearance.
  double dist = 0.0;
  EXPECT_TRUE(fx.si->getStateValidityChecker()->isValid(s.get(), dist));
  EXPECT_EQ(dist, fx.mdd_checker->clearance(s.get()));
}

TEST(SceneDistance, EmptyWorldIsInfinitelyFar) {
  const examples::ExampleScene& scene = testing::allScenes()[0];
  auto empty = std::make_shared<const scene::World>(std::vector<scene::Piece>(), "empty");
  const MddScene mdd(scene.robot, empty);
  const SceneDistance d = sceneDistance(mdd, Eigen::Isometry3d::Identity());
  EXPECT_EQ(d.distance, std::numeric_limits<double>::infinity());
  EXPECT_EQ(d.robot_piece, -1);
}

}  // namespace
}  // namespace mddual::planning
