// MddScene on its hierarchies against the loops over candidate pairs they
// replace (every robot piece, the world pieces whose boxes meet its box, one
// core query per pair), on every test scene and the trap: state checks,
// translation sweeps (first contacts and yes/no answers) and the same on the
// enlarged piece sets; and the rotating-edge scheme's bookkeeping.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "mddual/generators.h"
#include "test_support.h"

namespace mddual::planning {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

/// The old state check: every robot piece of `set` against the world pieces
/// whose boxes meet its box at X_WR.
bool pairLoopCollides(const MddScene& mdd, int set, const Eigen::Isometry3d& X_WR) {
  std::vector<int> candidates;
  for (int i = 0; i < static_cast<int>(mdd.robot().pieces().size()); ++i) {
    const scene::Piece& piece = mdd.setPiece(set, i);
    candidates.clear();
    mdd.world().candidates(scene::transformedBox(piece.box, X_WR), &candidates);
    for (int j : candidates) {
      IntersectInput in;
      in.a = &mdd.world().pieces()[static_cast<std::size_t>(j)].polytope;
      in.b = &piece.polytope;
      in.X_WB = X_WR;
      if (intersect(in).intersecting) return true;
    }
  }
  return false;
}

/// The old sweep: one toi per candidate pair (boxes swept over the whole
/// length), the smallest contact distance (0 when the start collides).
double pairLoopSweep(const MddScene& mdd, int set, const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& v_W,
                     double max_distance) {
  std::vector<int> candidates;
  double best = kInf;
  for (int i = 0; i < static_cast<int>(mdd.robot().pieces().size()); ++i) {
    candidates.clear();
    mdd.sweptCandidates(set, i, X_WR, v_W, max_distance, &candidates);
    for (int j : candidates) {
      DirectionalInput in;
      in.a = &mdd.world().pieces()[static_cast<std::size_t>(j)].polytope;
      in.b = &mdd.setPiece(set, i).polytope;
      in.X_WB = X_WR;
      in.s_W = v_W;
      in.max_distance = max_distance;
      const ToiResult r = toi(in);
      if (r.status != ToiStatus::kNever && r.toi <= max_distance) best = std::min(best, r.toi);
    }
  }
  return best;
}

/// A random pose in the scene's bounds, any orientation of its space kind.
Eigen::Isometry3d randomPose(const examples::ExampleScene& scene, testing::Rng& rng) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  for (int k = 0; k < 3; ++k) {
    X.translation()[k] = std::uniform_real_distribution<double>(scene.bounds.min()[k], scene.bounds.max()[k])(rng);
  }
  if (scene.kind == SpaceKind::kSE3) X.linear() = generators::randomRotation(rng);
  if (scene.kind == SpaceKind::kSE2) {
    X.linear() = Eigen::AngleAxisd(std::uniform_real_distribution<double>(-kPi, kPi)(rng), Eigen::Vector3d::UnitZ())
                     .toRotationMatrix();
  }
  return X;
}

class PairLoop : public ::testing::TestWithParam<int> {};

TEST_P(PairLoop, StatesAndSweepsAnswerAsTheLoopOverCandidatePairs) {
  const examples::ExampleScene& scene = testing::allScenes()[static_cast<std::size_t>(GetParam())];
  const MddScene mdd(scene.robot, scene.world);
  testing::Rng rng(testing::seed() * 31 + static_cast<std::uint64_t>(GetParam()));
  const double extent = (scene.bounds.max() - scene.bounds.min()).norm();
  int states = 0, colliding = 0, sweeps = 0, hits = 0, starts = 0;
  double worst = 0.0;
  for (int k = 0; k < 150 * testing::scale(); ++k) {
    const Eigen::Isometry3d X = randomPose(scene, rng);
    // The robot's pieces, the coarsest and the finest enlarged sets.
    for (int set : {0, 1, mdd.refinementLevels() + 1}) {
      const bool loop = pairLoopCollides(mdd, set, X);
      EXPECT_EQ(mdd.collidesSet(set, X, nullptr, nullptr), loop) << scene.name << " state " << k << " set " << set;
      ++states;
      colliding += loop;
      Eigen::Vector3d v = generators::randomUnitVector(rng);
      if (scene.kind == SpaceKind::kSE2 || scene.kind == SpaceKind::kR2) v.z() = 0.0;
      if (v.norm() < 1e-3) v = Eigen::Vector3d::UnitX();
      const double length = std::uniform_real_distribution<double>(0.0, 0.3 * extent)(rng);
      const double expected = pairLoopSweep(mdd, set, X, v, length);
      const SweepResult first = mdd.sweepSet(set, X, v, length, /*first_contact=*/true);
      const double got = first.start_collides ? 0.0 : first.distance;
      ++sweeps;
      if (std::isfinite(expected)) {
        ++(expected == 0.0 ? starts : hits);
        const double err = std::abs(got - expected);
        worst = std::max(worst, err);
        EXPECT_LE(err, 1e-12 * (1.0 + length)) << scene.name << " sweep " << k << " set " << set;
        EXPECT_EQ(first.start_collides, expected == 0.0);
        EXPECT_GE(first.contact.robot_piece, 0);
        EXPECT_GE(first.contact.world_piece, 0);
      } else {
        EXPECT_EQ(got, kInf) << scene.name << " sweep " << k << " set " << set;
      }
      // Yes/no: the same answer.
      const SweepResult any = mdd.sweepSet(set, X, v, length, /*first_contact=*/false);
      EXPECT_EQ(any.start_collides || any.distance <= length, std::isfinite(expected));
    }
  }
  std::printf("%-10s %d state checks (%d colliding), %d sweeps (%d hits, %d starting in contact), worst error %.2e\n",
              scene.name.c_str(), states, colliding, sweeps, hits, starts, worst);
  EXPECT_GT(colliding, 0);
  EXPECT_LT(colliding, states);
  EXPECT_GT(hits, 0);
}

std::string sceneName(const ::testing::TestParamInfo<int>& p) {
  return testing::sceneName(p.param);
}
INSTANTIATE_TEST_SUITE_P(Scenes, PairLoop, ::testing::Range(0, testing::kSceneCount), sceneName);

// ---- Rotating edges -----------------------------------------------------------------

TEST(MddSceneRotation, ValidityOnlyAndFirstContactAgreeAndTheFractionIsALowerBound) {
  // On the trap (thin walls of triangles, a long robot): both modes of
  // checkEdge give the same verdict, and a colliding edge's fraction is no
  // later than the first colliding state found by bisection on states.
  const examples::ExampleScene& scene = testing::allScenes()[8];
  ASSERT_EQ(scene.name, "trap");
  const MddScene mdd(scene.robot, scene.world);
  testing::Rng rng(testing::seed() * 101);
  int edges = 0, colliding = 0;
  while (edges < 200 * testing::scale()) {
    EdgeMotion m;
    Eigen::Isometry3d X = randomPose(scene, rng);
    if (mdd.collides(X)) continue;
    m.p_start = X.translation();
    m.q_start = Eigen::Quaterniond(X.linear());
    m.R_start = X.linear();
    m.p_end = m.p_start + std::uniform_real_distribution<double>(0.0, 4.0)(rng) * generators::randomUnitVector(rng);
    m.axis_R = generators::randomUnitVector(rng);
    m.angle = std::uniform_real_distribution<double>(0.0, kPi)(rng);
    m.X_end = m.pose(1.0);
    ++edges;
    const EdgeContact first = mdd.checkEdge(m, true);
    const EdgeContact any = mdd.checkEdge(m, false);
    EXPECT_EQ(first.collides, any.collides) << "edge " << edges;
    EXPECT_FALSE(first.exact);
    EXPECT_GT(first.sub_edges, 0);
    if (!first.collides) {
      // No state of the edge collides (sampled).
      for (int k = 0; k <= 100; ++k) EXPECT_FALSE(mdd.collides(m.pose(k / 100.0))) << "edge " << edges;
      continue;
    }
    ++colliding;
    ASSERT_GE(first.fraction, 0.0);
    ASSERT_LE(first.fraction, 1.0);
    // The first sampled colliding state is no earlier than the fraction.
    for (int k = 0; k <= 1000; ++k) {
      const double t = k / 1000.0;
      if (!mdd.collides(m.pose(t))) continue;
      EXPECT_LE(first.fraction, t) << "edge " << edges;
      break;
    }
  }
  EXPECT_GT(colliding, edges / 10);
  EXPECT_LT(colliding, edges - edges / 10);
}

TEST(MddSceneRotation, TheTreesCoverTheirPieces) {
  const examples::ExampleScene& scene = testing::allScenes()[8];
  const MddScene mdd(scene.robot, scene.world);
  EXPECT_EQ(mdd.robotTree().numPieces(), static_cast<int>(scene.robot->pieces().size()));
  EXPECT_EQ(mdd.worldTree().numPieces(), static_cast<int>(scene.world->pieces().size()));
  // The robot radius bounds every node's distance from the body origin.
  for (int n = 0; n < mdd.robotTree().numNodes(); ++n) {
    EXPECT_LE(mdd.robotTree().node(n).max_norm, scene.robot->radius() * (1.0 + 1e-9));
  }
}

}  // namespace
}  // namespace mddual::planning
