// MddScene on its hierarchies against the loops over candidate pairs they
// replace (every robot piece, the world pieces whose boxes meet its box, one
// core query per pair), on every test scene and the trap: state checks,
// translation sweeps (first contacts and yes/no answers) and the same on the
// enlarged piece sets; the rotating-edge scheme's bookkeeping; and worlds
// that change (answers after random updates against a scene rebuilt from
// scratch, warm starts kept).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <vector>

#include "mddual/constants.h"
#include "mddual/generators.h"
#include "mddual/planning/scene_distance.h"
#include "test_support.h"

namespace mddual::planning {
namespace {

using testing::kInf;

/// The box of a polytope's vertices posed at X, grown by a margin against
/// round-off (boxes of touching pieces must meet).
Eigen::AlignedBox3d posedBox(const ConvexPolytope& p, const Eigen::Isometry3d& X) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& v : p.vertices()) box.extend(X * v);
  const double margin = 1e-9 * (1.0 + box.max().cwiseAbs().maxCoeff() + box.min().cwiseAbs().maxCoeff());
  box.min().array() -= margin;
  box.max().array() += margin;
  return box;
}

/// The boxes of the world pieces' vertices, and those that meet `box`: a
/// scan of every piece, independent of the scene's own broad phase (its
/// tree, its boxes).
struct WorldBoxes {
  explicit WorldBoxes(const MddScene& mdd) {
    for (const scene::Piece& p : mdd.world().pieces())
      boxes.push_back(posedBox(p.polytope, Eigen::Isometry3d::Identity()));
  }
  std::vector<int> meeting(const Eigen::AlignedBox3d& box) const {
    std::vector<int> out;
    for (std::size_t j = 0; j < boxes.size(); ++j) {
      if (boxes[j].intersects(box)) out.push_back(static_cast<int>(j));
    }
    return out;
  }
  std::vector<Eigen::AlignedBox3d> boxes;
};

/// The old state check: every robot piece of `set` against the world pieces
/// whose boxes meet its box at X_WR (found by a scan of every world piece).
bool pairLoopCollides(const MddScene& mdd, int set, const Eigen::Isometry3d& X_WR) {
  const WorldBoxes world(mdd);
  for (int i = 0; i < static_cast<int>(mdd.robot().pieces().size()); ++i) {
    const scene::Piece& piece = mdd.pieceInSet(set, i);
    for (int j : world.meeting(posedBox(piece.polytope, X_WR))) {
      IntersectInput in;
      in.a = &mdd.world().pieces()[static_cast<std::size_t>(j)].polytope;
      in.b = &piece.polytope;
      in.X_WB = X_WR;
      if (intersect(in).intersecting) return true;
    }
  }
  return false;
}

/// The old sweep: one toi per candidate pair (the world pieces whose boxes
/// meet the box of the piece's start and end boxes, which holds the swept
/// piece), the smallest contact distance (0 when the start collides).
double pairLoopSweep(const MddScene& mdd, int set, const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& v_W,
                     double max_distance) {
  const WorldBoxes world(mdd);
  double best = kInf;
  for (int i = 0; i < static_cast<int>(mdd.robot().pieces().size()); ++i) {
    const scene::Piece& piece = mdd.pieceInSet(set, i);
    Eigen::Isometry3d X_end = X_WR;
    X_end.pretranslate(max_distance * v_W.normalized());
    Eigen::AlignedBox3d swept = posedBox(piece.polytope, X_WR);
    swept.extend(posedBox(piece.polytope, X_end));
    for (int j : world.meeting(swept)) {
      DirectionalInput in;
      in.a = &mdd.world().pieces()[static_cast<std::size_t>(j)].polytope;
      in.b = &piece.polytope;
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

INSTANTIATE_TEST_SUITE_P(Scenes, PairLoop, ::testing::Range(0, testing::kSceneCount), testing::sceneParamName);

// ---- Rotating edges -----------------------------------------------------------------

/// An edge from a random pose that is free (or, when asked, collides), not
/// moving yet (the end is the start).
EdgeMotion randomStart(const examples::ExampleScene& scene, const MddScene& mdd, testing::Rng& rng,
                       bool colliding = false) {
  EdgeMotion m;
  Eigen::Isometry3d X = randomPose(scene, rng);
  while (mdd.collides(X) != colliding) X = randomPose(scene, rng);
  m.p_start = X.translation();
  m.p_end = m.p_start;
  m.q_start = Eigen::Quaterniond(X.linear());
  m.R_start = X.linear();
  m.X_end = X;
  return m;
}

/// A rotating edge from a free random pose: up to 4 m of translation, a
/// rotation by up to pi about a random axis.
EdgeMotion randomRotatingEdge(const examples::ExampleScene& scene, const MddScene& mdd, testing::Rng& rng) {
  EdgeMotion m = randomStart(scene, mdd, rng);
  // The direction before the length: the order GCC evaluated the operands of
  // the product (C++ leaves them unsequenced), kept so the seeded edges stay.
  const Eigen::Vector3d direction = generators::randomUnitVector(rng);
  m.p_end = m.p_start + std::uniform_real_distribution<double>(0.0, 4.0)(rng) * direction;
  m.axis_R = generators::randomUnitVector(rng);
  m.angle = std::uniform_real_distribution<double>(0.0, kPi)(rng);
  m.X_end = m.pose(1.0);
  return m;
}

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
    const EdgeMotion m = randomRotatingEdge(scene, mdd, rng);
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

TEST(MddSceneRotation, LastValidQueryKeepsTheVerdictAndBoundsTheFirstContactWithinItsTolerance) {
  // EdgeQuery::kLastValid on the trap: the verdict of kValidity; a colliding
  // edge's fraction is no later than the first colliding state found by
  // sampling; with a tolerance the bound is at most that much earlier than
  // with none (the search stops within it of the best contact found, and the
  // full search's answer is no later than that contact); and the bound is
  // useful: on average not far below kFirstContact's (a bound stuck at 0
  // would pass the rest).
  const examples::ExampleScene& scene = testing::allScenes()[8];
  ASSERT_EQ(scene.name, "trap");
  const MddScene mdd(scene.robot, scene.world);
  testing::Rng rng(testing::seed() * 103);
  constexpr double kTolerance = 0.05;
  constexpr double kMinShareOfFirstContact = 0.8;  // mean kLastValid fraction over mean kFirstContact one
  int edges = 0, colliding = 0, looser = 0;
  double sum_last_valid = 0.0, sum_first_contact = 0.0;
  while (edges < 200 * testing::scale()) {
    const EdgeMotion m = randomRotatingEdge(scene, mdd, rng);
    ++edges;
    const EdgeContact any = mdd.checkEdge(m, EdgeQuery::kValidity);
    const EdgeContact full = mdd.checkEdge(m, EdgeQuery::kLastValid);
    const EdgeContact cut = mdd.checkEdge(m, EdgeQuery::kLastValid, kTolerance);
    ASSERT_EQ(full.collides, any.collides) << "edge " << edges;
    ASSERT_EQ(cut.collides, any.collides) << "edge " << edges;
    EXPECT_FALSE(full.exact);
    if (!any.collides) continue;
    ++colliding;
    ASSERT_GE(cut.fraction, 0.0);
    ASSERT_LE(full.fraction, 1.0);
    EXPECT_GE(cut.fraction, full.fraction - kTolerance - 1e-9) << "edge " << edges;
    looser += cut.fraction < full.fraction - 1e-9;
    sum_last_valid += full.fraction;
    sum_first_contact += mdd.checkEdge(m, EdgeQuery::kFirstContact).fraction;
    for (int k = 0; k <= 1000; ++k) {
      const double t = k / 1000.0;
      if (!mdd.collides(m.pose(t))) continue;
      EXPECT_LE(full.fraction, t) << "edge " << edges;
      EXPECT_LE(cut.fraction, t) << "edge " << edges;
      break;
    }
  }
  EXPECT_GT(colliding, edges / 10);
  std::printf(
      "kLastValid: %d of %d colliding edges have a looser bound with tolerance %g; mean fraction %.4f "
      "(kFirstContact %.4f)\n",
      looser, colliding, kTolerance, sum_last_valid / colliding, sum_first_contact / colliding);
  EXPECT_GE(sum_last_valid, kMinShareOfFirstContact * sum_first_contact);
  // Out-of-range tolerances are refused.
  EdgeMotion m;
  m.axis_R = Eigen::Vector3d::UnitZ();
  m.angle = 1.0;
  m.X_end = m.pose(1.0);
  EXPECT_THROW(mdd.checkEdge(m, EdgeQuery::kLastValid, -0.1), InvalidInputError);
  EXPECT_THROW(mdd.checkEdge(m, EdgeQuery::kLastValid, std::nan("")), InvalidInputError);
  EXPECT_THROW(mdd.checkEdge(m, EdgeQuery::kLastValid, 1.5), InvalidInputError);
}

TEST(MddSceneRotation, LastValidLevelTradesQueriesForATighterBound) {
  // MddSceneOptions::last_valid_level on the trap's colliding rotating
  // edges, no tolerance: every level's bound is no later than the first
  // colliding state found by sampling; the finest level's is the
  // first-contact search's answer; the default level's is on average later
  // (keeps more of the edge) than level 0's, for more pair queries.
  const examples::ExampleScene& scene = testing::allScenes()[8];
  ASSERT_EQ(scene.name, "trap");
  MddSceneOptions options;
  std::vector<std::unique_ptr<MddScene>> scenes;  // levels 0, the default, the finest (and beyond it)
  for (const int level : {0, kDefaultLastValidLevel, options.refinement_levels, kMaxRefinementLevels}) {
    options.last_valid_level = level;
    scenes.push_back(std::make_unique<MddScene>(scene.robot, scene.world, options));
  }
  ASSERT_LT(0, kDefaultLastValidLevel);
  ASSERT_LT(kDefaultLastValidLevel, options.refinement_levels);
  testing::Rng rng(testing::seed() * 107);
  int edges = 0, colliding = 0;
  std::array<double, 4> sum_fraction{};
  std::array<long, 4> queries{};
  while (edges < 150 * testing::scale()) {
    const EdgeMotion m = randomRotatingEdge(scene, *scenes[0], rng);
    ++edges;
    if (!scenes[0]->checkEdge(m, EdgeQuery::kValidity).collides) continue;
    ++colliding;
    int first_colliding = 1000;  // no sample collides: the bound is only checked against the edge's end
    for (int k = 0; k <= 1000; ++k) {
      if (scenes[0]->collides(m.pose(k / 1000.0))) {
        first_colliding = k;
        break;
      }
    }
    // kFirstContact finds no contact only on a rare false alarm of the
    // validity search (the finest-level queries clear the edge): no bound to
    // compare with then.
    const EdgeContact first = scenes[0]->checkEdge(m, EdgeQuery::kFirstContact);
    for (std::size_t s = 0; s < scenes.size(); ++s) {
      const EdgeContact e = scenes[s]->checkEdge(m, EdgeQuery::kLastValid);
      ASSERT_TRUE(e.collides) << "edge " << edges << ", scene " << s;
      EXPECT_LE(e.fraction, first_colliding / 1000.0) << "edge " << edges << ", scene " << s;
      if (s >= 2 && first.collides) {
        EXPECT_NEAR(e.fraction, first.fraction, 1e-9) << "edge " << edges << ", scene " << s;
      }
      sum_fraction[s] += e.fraction;
      queries[s] += e.pair_queries;
    }
  }
  ASSERT_GT(colliding, edges / 10);
  std::printf("kLastValid by level (0, %d, %d, 8): mean fraction %.4f %.4f %.4f %.4f, pair queries %ld %ld %ld %ld\n",
              kDefaultLastValidLevel, options.refinement_levels, sum_fraction[0] / colliding,
              sum_fraction[1] / colliding, sum_fraction[2] / colliding, sum_fraction[3] / colliding, queries[0],
              queries[1], queries[2], queries[3]);
  // Aggregates over the seeded sample (a finer level need not keep more of
  // every single edge: its intervals differ).
  EXPECT_GT(sum_fraction[1], sum_fraction[0]);
  EXPECT_GT(queries[1], queries[0]);
}

TEST(MddSceneRotation, ValidityTestsTheProbeStatesBeforeAnySearch) {
  // A rotating edge is first tested at its end, middle and quarters (in
  // that order): when one collides, kValidity answers with it and no
  // triple is searched; otherwise the search runs, also on edges whose
  // eighths collide (probed too until e26a0be; guarded below).
  const examples::ExampleScene& scene = testing::allScenes()[8];
  ASSERT_EQ(scene.name, "trap");
  const MddScene mdd(scene.robot, scene.world);
  testing::Rng rng(testing::seed() * 109);
  const std::array<double, 4> probes = {1.0, 0.5, 0.25, 0.75};
  int by_probe = 0, by_search = 0, at_an_eighth = 0;
  for (int e = 0; e < 1500 * testing::scale(); ++e) {
    const EdgeMotion m = randomRotatingEdge(scene, mdd, rng);
    double first_probe = kInf;
    for (const double t : probes) {
      if (mdd.collides(m.pose(t))) {
        first_probe = t;
        break;
      }
    }
    const EdgeContact any = mdd.checkEdge(m, EdgeQuery::kValidity);
    if (first_probe < kInf) {
      ++by_probe;
      EXPECT_TRUE(any.collides) << "edge " << e;
      EXPECT_EQ(any.fraction, first_probe) << "edge " << e;
      EXPECT_EQ(any.sub_edges, 0) << "edge " << e;
    } else {
      by_search += any.collides;
      EXPECT_GT(any.sub_edges, 0) << "edge " << e;
      for (const double t : {0.125, 0.375, 0.625, 0.875}) {
        if (mdd.collides(m.pose(t))) {
          ++at_an_eighth;
          break;
        }
      }
    }
  }
  // Both ways of finding a collision occur, and some edges collide at an
  // eighth but at no probe state (about 1 edge in 200: hence 1,500 edges).
  EXPECT_GT(by_probe, 10);
  EXPECT_GT(by_search, 0);
  EXPECT_GT(at_an_eighth, 0);
  std::printf("[ sample   ] by a probe state %d, by the search %d (of which an eighth collides: %d)\n", by_probe,
              by_search, at_an_eighth);
}

TEST(MddSceneTranslation, LastValidWithAToleranceBracketsTheExactContact) {
  // EdgeQuery::kLastValid on translation edges of the trap and the cubicles
  // (flat walls: many pairs touch at nearly the same distance): the verdict
  // of kValidity; the fraction in [f - tolerance, f], f the exact contact
  // of the loop over candidate pairs; marked exact only when it is f (its
  // contact then named), else a bound with no pair.
  constexpr double kTolerance = 0.05;
  int colliding = 0, bounds = 0, edges = 0, starts = 0;
  for (const int k : {7, 8}) {
    const examples::ExampleScene& scene = testing::allScenes()[static_cast<std::size_t>(k)];
    const MddScene mdd(scene.robot, scene.world);
    testing::Rng rng(testing::seed() * 107 + static_cast<std::uint64_t>(k));
    for (int e = 0; e < 150 * testing::scale(); ++e, ++edges) {
      // One edge in five starts in collision (the bound is then 0 and the
      // start must be reported as colliding).
      EdgeMotion m = randomStart(scene, mdd, rng, e % 5 == 4);
      const Eigen::Isometry3d X = m.pose(0.0);
      // The direction before the length, as GCC evaluated the product.
      const Eigen::Vector3d direction = generators::randomUnitVector(rng);
      const Eigen::Vector3d v_W = std::uniform_real_distribution<double>(0.5, 6.0)(rng) * direction;
      m.p_end = m.p_start + v_W;
      m.X_end = m.pose(1.0);
      const double exact = pairLoopSweep(mdd, 0, X, v_W, v_W.norm()) / v_W.norm();
      const EdgeContact any = mdd.checkEdge(m, EdgeQuery::kValidity);
      const EdgeContact cut = mdd.checkEdge(m, EdgeQuery::kLastValid, kTolerance);
      const std::string where = scene.name + " edge " + std::to_string(e) + " exact " + std::to_string(exact);
      ASSERT_EQ(cut.collides, any.collides) << where;
      ASSERT_EQ(cut.collides, exact <= 1.0) << where;
      if (!cut.collides) continue;
      ++colliding;
      starts += exact == 0.0;
      EXPECT_EQ(cut.start_collides, exact == 0.0) << where;
      EXPECT_LE(cut.fraction, exact + 1e-12) << where;
      EXPECT_GE(cut.fraction, exact - kTolerance - 1e-12) << where;
      if (cut.exact) {
        EXPECT_NEAR(cut.fraction, exact, 1e-12) << where;
        EXPECT_GE(cut.contact.robot_piece, 0) << where;
      } else {
        ++bounds;
        EXPECT_EQ(cut.contact.robot_piece, -1) << where;
      }
      // Tolerance 0: the exact contact.
      EXPECT_NEAR(mdd.checkEdge(m, EdgeQuery::kLastValid).fraction, exact, 1e-12) << where;
    }
  }
  // Not a degenerate sample: contacts, and searches that stopped early.
  EXPECT_GT(colliding, edges / 10);
  EXPECT_GT(bounds, colliding / 20);
  EXPECT_GE(starts, edges / 5);
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

// ---- Worlds that change ---------------------------------------------------------

/// A random rigid motion about `centre`: a rotation (about z for the planar
/// kinds) and a shift of up to `reach` (none along z for the planar kinds).
Eigen::Isometry3d randomMotionAbout(const examples::ExampleScene& scene, const Eigen::Vector3d& centre, double reach,
                                    testing::Rng& rng) {
  const bool planar = scene.kind == SpaceKind::kSE2 || scene.kind == SpaceKind::kR2;
  Eigen::Vector3d shift = reach * generators::randomUnitVector(rng);
  Eigen::Matrix3d R = generators::randomRotation(rng);
  if (planar) {
    shift.z() = 0.0;
    R = Eigen::AngleAxisd(std::uniform_real_distribution<double>(-kPi, kPi)(rng), Eigen::Vector3d::UnitZ())
            .toRotationMatrix();
  }
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = centre + shift - R * centre;
  return X;
}

/// A random edge from X: a translation of up to `reach` and, when `rotate`,
/// a rotation of up to pi about a random axis (z for the planar kinds).
EdgeMotion randomEdge(const examples::ExampleScene& scene, const Eigen::Isometry3d& X, double reach, bool rotate,
                      testing::Rng& rng) {
  const bool planar = scene.kind == SpaceKind::kSE2 || scene.kind == SpaceKind::kR2;
  EdgeMotion m;
  m.p_start = X.translation();
  m.q_start = Eigen::Quaterniond(X.linear());
  m.R_start = X.linear();
  Eigen::Vector3d v = generators::randomUnitVector(rng);
  if (planar) v.z() = 0.0;
  m.p_end = m.p_start + std::uniform_real_distribution<double>(0.0, reach)(rng) * v;
  if (rotate) {
    m.axis_R = planar ? Eigen::Vector3d::UnitZ() : generators::randomUnitVector(rng);
    m.angle = std::uniform_real_distribution<double>(0.0, kPi)(rng);
  }
  m.X_end = m.pose(1.0);
  return m;
}

/// Counts of the comparisons.
struct UpdateStats {
  int states = 0, colliding = 0, sweeps = 0, sweep_hits = 0, edges = 0, edge_hits = 0, rotating = 0, rotating_hits = 0;
};

/// Every answer of `updated` against `rebuilt` (same robot, same pieces in
/// the same order, trees built from scratch) on random queries.
void expectSameAnswers(const examples::ExampleScene& scene, const MddScene& updated, const MddScene& rebuilt,
                       int queries, testing::Rng& rng, UpdateStats* stats, const std::string& where) {
  const double extent = (scene.bounds.max() - scene.bounds.min()).norm();
  for (int k = 0; k < queries; ++k) {
    const Eigen::Isometry3d X = randomPose(scene, rng);
    const bool hit = rebuilt.collides(X);
    ASSERT_EQ(updated.collides(X), hit) << where << " state " << k;
    ++stats->states;
    stats->colliding += hit;
    // Clearance (nearestPair over the static tree, its skipped leaves and
    // the overflow tree): the same minimum over the same pairs.
    const SceneDistance da = sceneDistance(updated, X);
    const SceneDistance db = sceneDistance(rebuilt, X);
    ASSERT_EQ(da.distance, db.distance) << where << " clearance " << k;
    ASSERT_GE(da.world_piece, 0) << where << " clearance " << k;
    EXPECT_EQ(hit, da.distance <= 0.0) << where << " clearance " << k;

    Eigen::Vector3d v = 0.3 * extent * generators::randomUnitVector(rng);
    if (scene.kind == SpaceKind::kSE2 || scene.kind == SpaceKind::kR2) v.z() = 0.0;
    const SweepResult sa = updated.sweep(X, v, true);
    const SweepResult sb = rebuilt.sweep(X, v, true);
    ASSERT_EQ(sa.start_collides, sb.start_collides) << where << " sweep " << k;
    ASSERT_EQ(std::isfinite(sa.distance), std::isfinite(sb.distance)) << where << " sweep " << k;
    if (std::isfinite(sb.distance)) {
      EXPECT_NEAR(sa.distance, sb.distance, 1e-12 * (1.0 + v.norm())) << where << " sweep " << k;
      ++stats->sweep_hits;
    }
    // Any contact (not necessarily the first, nor the same one): whether there is one.
    const SweepResult any = updated.sweep(X, v, false);
    EXPECT_EQ(any.start_collides || std::isfinite(any.distance), std::isfinite(sb.distance)) << where << " sweep " << k;
    ++stats->sweeps;

    // Edges: translation (exact fraction) and rotating (a lower bound).
    for (const bool rotate : {false, true}) {
      if (rotate && k % 2 != 0) continue;  // rotating edges cost more: every second query
      const EdgeMotion m = randomEdge(scene, X, 0.2 * extent, rotate, rng);
      const EdgeContact a = updated.checkEdge(m, true);
      const EdgeContact b = rebuilt.checkEdge(m, true);
      ASSERT_EQ(a.collides, b.collides) << where << (rotate ? " rotating" : " translation") << " edge " << k;
      ASSERT_EQ(a.start_collides, b.start_collides) << where << " edge " << k;
      EXPECT_EQ(updated.checkEdge(m, false).collides, a.collides) << where << " edge " << k;
      if (!rotate && b.collides) {
        EXPECT_NEAR(a.fraction, b.fraction, 1e-12) << where << " edge " << k;
      }
      if (rotate && b.collides) {
        // Both fractions are lower bounds of the first colliding state
        // (sampled), found with different trees.
        for (int s = 0; s <= 200; ++s) {
          if (!rebuilt.collides(m.pose(s / 200.0))) continue;
          EXPECT_LE(a.fraction, s / 200.0) << where << " rotating edge " << k;
          break;
        }
      }
      ++(rotate ? stats->rotating : stats->edges);
      if (b.collides) ++(rotate ? stats->rotating_hits : stats->edge_hits);
    }
  }
}

class WorldUpdates : public ::testing::TestWithParam<int> {};

TEST_P(WorldUpdates, EveryAnswerEqualsThatOfAWorldRebuiltFromScratch) {
  const examples::ExampleScene& scene = testing::allScenes()[static_cast<std::size_t>(GetParam())];
  auto mdd = std::make_shared<MddScene>(scene.robot, scene.world);
  const std::size_t given = scene.world->pieces().size();
  testing::Rng rng(testing::seed() * 53 + static_cast<std::uint64_t>(GetParam()));
  const double extent = (scene.bounds.max() - scene.bounds.min()).norm();
  std::vector<int> live;  // ids of the current pieces
  for (int j = 0; j < static_cast<int>(given); ++j) live.push_back(j);
  UpdateStats stats;
  int adds = 0, removes = 0, moves = 0;
  for (int round = 0; round < 8; ++round) {
    for (int step = 0; step < 12; ++step) {
      const int op = std::uniform_int_distribution<int>(0, 2)(rng);
      const std::size_t pick = std::uniform_int_distribution<std::size_t>(0, live.size() - 1)(rng);
      if (op == 0 || live.size() < given / 2) {
        // A copy of one of the scene's pieces, somewhere else in the bounds.
        const scene::Piece& model =
            scene.world->pieces()[std::uniform_int_distribution<std::size_t>(0, given - 1)(rng)];
        const Eigen::Isometry3d X = randomMotionAbout(scene, model.centre, 0.3 * extent, rng);
        std::vector<Eigen::Vector3d> points;
        for (const Eigen::Vector3d& p : model.polytope.vertices()) points.push_back(X * p);
        live.push_back(mdd->addWorldPiece(
            scene::Piece::make(ConvexPolytope::fromPoints(points), model.kind, "added " + std::to_string(adds))));
        ++adds;
      } else if (op == 1) {
        mdd->removeWorldPiece(live[pick]);
        live.erase(live.begin() + static_cast<std::ptrdiff_t>(pick));
        ++removes;
      } else {
        const scene::Piece& piece = mdd->world().pieces()[static_cast<std::size_t>(mdd->world().indexOf(live[pick]))];
        mdd->moveWorldPiece(live[pick], randomMotionAbout(scene, piece.centre, 0.1 * extent, rng));
        ++moves;
      }
    }
    ASSERT_EQ(mdd->world().pieces().size(), live.size());
    const auto rebuilt_world = std::make_shared<scene::World>(mdd->world().pieces(), "rebuilt");
    const MddScene rebuilt(scene.robot, rebuilt_world);
    expectSameAnswers(scene, *mdd, rebuilt, 100 * testing::scale(), rng, &stats,
                      scene.name + " round " + std::to_string(round));
    if (HasFatalFailure()) return;
  }
  EXPECT_EQ(scene.world->pieces().size(), given);  // the World given to the scene is never modified
  EXPECT_GT(mdd->worldTreeRebuilds(), 0);          // the static tree was rebuilt at least once
  std::printf(
      "%-10s %d adds, %d removes, %d moves, %d tree rebuilds; %d states (%d colliding), %d sweeps (%d hits), "
      "%d translation edges (%d colliding), %d rotating edges (%d colliding)\n",
      scene.name.c_str(), adds, removes, moves, mdd->worldTreeRebuilds(), stats.states, stats.colliding, stats.sweeps,
      stats.sweep_hits, stats.edges, stats.edge_hits, stats.rotating, stats.rotating_hits);
  EXPECT_GT(stats.colliding, 0);
  EXPECT_LT(stats.colliding, stats.states);
  EXPECT_GT(stats.edge_hits, 0);
  EXPECT_GT(stats.rotating_hits, 0);
}

INSTANTIATE_TEST_SUITE_P(CodeScenes, WorldUpdates, ::testing::Range(0, 4), testing::sceneParamName);

TEST(WorldUpdates, OtherPairsKeepTheirWarmStarts) {
  const examples::ExampleScene& scene = testing::allScenes()[3];  // blobs
  MddScene mdd(scene.robot, scene.world);
  // Fill the warm starts of every pair with a state query at each of a few poses.
  testing::Rng rng(testing::seed() * 7);
  const double extent = (scene.bounds.max() - scene.bounds.min()).norm();
  for (int k = 0; k < 100; ++k) {
    const Eigen::Isometry3d X = randomPose(scene, rng);
    mdd.collides(X);
    mdd.sweep(X, extent * generators::randomUnitVector(rng));
  }
  const auto snapshot = [&](int world_id) {
    const WarmStart* w = mdd.warmStart(0, 0, mdd.world().indexOf(world_id));
    return std::vector<int>{w->centre_a[0],  w->centre_a[1],  w->centre_b[0],  w->centre_b[1],
                            w->overlap_a[0], w->overlap_b[0], w->separating.a, w->separating.b};
  };
  const int n = static_cast<int>(scene.world->pieces().size());
  std::vector<std::vector<int>> before;
  for (int id = 0; id < n; ++id) before.push_back(snapshot(id));
  // Remove the first piece (the last one takes its index), move the second,
  // add one: every other pair's warm start is the one it had.
  mdd.removeWorldPiece(0);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() << 0.5, 0, 0;
  mdd.moveWorldPiece(1, X);
  mdd.addWorldPiece(scene.world->pieces()[2]);
  EXPECT_EQ(mdd.world().indexOf(n - 1), 0);
  int filled = 0;
  for (int id = 2; id < n; ++id) {
    EXPECT_EQ(snapshot(id), before[static_cast<std::size_t>(id)]) << "world piece id " << id;
    const std::vector<int>& w = before[static_cast<std::size_t>(id)];
    filled += std::any_of(w.begin(), w.end(), [](int x) { return x >= 0; });
  }
  EXPECT_GT(filled, 0);  // the queries did warm some pairs
}

/// Support value of a polytope's vertices in direction d.
double supportValue(const ConvexPolytope& p, const Eigen::Vector3d& d) {
  double h = -kInf;
  for (const Eigen::Vector3d& v : p.vertices()) h = std::max(h, v.dot(d));
  return h;
}

// enlargePiece must hold every point within delta of the piece (support
// function at least h_P + delta in every direction: the rotating scheme's
// soundness rests on it) and add no more than the cube's circumradius
// (sqrt(3) delta). A triangle takes the cube sum itself (support exactly
// h_P + delta' |d|_1, delta' = delta (1 + 1e-9) the margin of the scale):
// the icosahedron is not tried for triangles.
TEST(EnlargePiece, HoldsThePieceGrownByDeltaAndTakesTheCubeForTriangles) {
  testing::Rng rng(testing::seed() * 41);
  std::uniform_real_distribution<double> coord(-1.0, 1.0);
  const double delta = 0.05;
  for (int k = 0; k < 40; ++k) {
    const bool triangle = k % 2 == 0;
    generators::Points points;
    if (triangle) {
      // The last vertex first: the order GCC evaluated triangle()'s arguments
      // (C++ leaves it unspecified), kept so the seeded triangles stay.
      const Eigen::Vector3d v2 = generators::drawVector(coord, rng);
      const Eigen::Vector3d v1 = generators::drawVector(coord, rng);
      const Eigen::Vector3d v0 = generators::drawVector(coord, rng);
      points = generators::triangle(v0, v1, v2);
    } else {
      points = generators::blob(12, Eigen::Vector3d(0.5, 0.3, 0.2), rng);
    }
    const scene::Piece piece =
        scene::Piece::make(ConvexPolytope::fromPoints(points), scene::PieceKind::kConvex, "piece " + std::to_string(k));
    ASSERT_EQ(piece.polytope.numVertices() == 3, triangle) << "piece " << k;
    const scene::Piece grown = enlargePiece(piece, delta);
    for (int m = 0; m < 200; ++m) {
      const Eigen::Vector3d d = generators::randomUnitVector(rng);
      const double h = supportValue(piece.polytope, d);
      const double g = supportValue(grown.polytope, d);
      EXPECT_GE(g, h + delta - 1e-12) << "piece " << k << " direction " << d.transpose();
      EXPECT_LE(g, h + std::sqrt(3.0) * delta * (1.0 + 1e-6)) << "piece " << k << " direction " << d.transpose();
      if (triangle) {
        EXPECT_NEAR(g, h + delta * (1.0 + 1e-9) * d.lpNorm<1>(), 1e-12) << "piece " << k;
      }
    }
  }
}

TEST(EnlargePiece, AManyCorneredFlatPieceIsEnlargedAsAPrismThatHoldsItGrownByDelta) {
  // Flat convex polygons of 17 to 3,000 corners (the 5,000-gon robot took
  // 7.9 s per enlargement level as its sum with the cube; regression of the
  // hostile-input hunt), tilted, with sharp and blunt corners: the prism holds
  // every point within delta of the piece and stays within sqrt(3) delta.
  testing::Rng rng(testing::seed() * 43);
  const double delta = 0.01;
  for (int n : {17, 40, 3000}) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.7 * n, generators::randomUnitVector(rng)));
    generators::Points points;
    for (int i = 0; i < n; ++i) {
      // An ellipse squeezed to 1:20 (corners turning by about 150 degrees
      // at its ends for n = 17: three tangent segments there).
      const double a = 2.0 * kPi * i / n;
      points.push_back(q * Eigen::Vector3d(0.4 * std::cos(a), 0.02 * std::sin(a), 0.0) +
                       Eigen::Vector3d(0.1, 0.2, 0.3));
    }
    const scene::Piece piece = scene::Piece::make(ConvexPolytope::fromPoints(points), scene::PieceKind::kConvex,
                                                  "polygon " + std::to_string(n));
    ASSERT_TRUE(piece.polytope.isFlat());
    const scene::Piece grown = enlargePiece(piece, delta);
    EXPECT_FALSE(grown.polytope.isFlat());
    // A prism (ConvexPolytope::prism): two caps and one side per cap corner.
    EXPECT_EQ(grown.polytope.numFaces(), grown.polytope.numVertices() / 2 + 2) << "polygon " << n;
    for (int m = 0; m < 400; ++m) {
      const Eigen::Vector3d d = generators::randomUnitVector(rng);
      const double h = supportValue(piece.polytope, d);
      const double g = supportValue(grown.polytope, d);
      EXPECT_GE(g, h + delta - 1e-12) << "polygon " << n << " direction " << d.transpose();
      EXPECT_LE(g, h + std::sqrt(3.0) * delta) << "polygon " << n << " direction " << d.transpose();
    }
  }
}

TEST(WorldUpdates, BadUpdatesAreRefusedAndLeaveTheSceneAsItWas) {
  const examples::ExampleScene& scene = testing::allScenes()[0];  // primitives
  MddScene mdd(scene.robot, scene.world);
  const int n = static_cast<int>(scene.world->pieces().size());
  mdd.removeWorldPiece(3);
  EXPECT_THROW(mdd.removeWorldPiece(3), InvalidInputError);      // removed
  EXPECT_THROW(mdd.removeWorldPiece(n + 5), InvalidInputError);  // never given
  Eigen::Isometry3d nan = Eigen::Isometry3d::Identity();
  nan.translation().y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(mdd.moveWorldPiece(4, nan), InvalidInputError);
  EXPECT_THROW(mdd.moveWorldPiece(-1, Eigen::Isometry3d::Identity()), InvalidInputError);
  Eigen::Isometry3d scaled = Eigen::Isometry3d::Identity();
  scaled.linear() *= 2.0;  // not rigid: it would grow the piece (hostile-input hunt)
  EXPECT_THROW(mdd.moveWorldPiece(4, scaled), InvalidInputError);
  Eigen::Isometry3d mirrored = Eigen::Isometry3d::Identity();
  mirrored.linear()(0, 0) = -1.0;
  EXPECT_THROW(mdd.moveWorldPiece(4, mirrored), InvalidInputError);
  // A piece without a polytope is refused before anything changes; a valid
  // piece added after it is seen by every query (review finding: the bad
  // piece used to stay in the world and block the trees' refresh).
  EXPECT_THROW(mdd.addWorldPiece(scene::Piece{}), InvalidInputError);
  ASSERT_EQ(static_cast<int>(mdd.world().pieces().size()), n - 1);
  mdd.addWorldPiece(scene.world->pieces()[3]);
  ASSERT_EQ(static_cast<int>(mdd.world().pieces().size()), n);
  const MddScene rebuilt(scene.robot, std::make_shared<scene::World>(mdd.world().pieces(), "rebuilt"));
  testing::Rng rng(testing::seed() * 13);
  UpdateStats stats;
  expectSameAnswers(scene, mdd, rebuilt, 100, rng, &stats, "after refused updates");
}

}  // namespace
}  // namespace mddual::planning
