// ArmScene on configs/arm7 in a world of thin plates and bars: state checks
// and clearance against a brute force over every piece pair (no hierarchy),
// and the certified edge check against a dense check of the same edges
// (states every 1/2000 of the edge, each checked exactly): never a miss, the
// first-contact bound never after the first colliding sample, false alarms
// counted. MDDUAL_PLANNING_SCALE / MDDUAL_PLANNING_SEED scale and reseed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "arm_fixture.h"
#include "mddual/distance.h"
#include "mddual/planning/arm_scene.h"
#include "mddual/query.h"
#include "mddual/scene/loaders.h"

namespace mddual::planning {
namespace {

using testing::ArmFixture;
using testing::armWorld;
using testing::denseFirstContact;
using testing::makeArm;
using testing::randomConfiguration;
using testing::Rng;

/// Every pair of pieces that must be checked, tested one by one with the core.
bool bruteCollides(const ArmScene& s, const std::vector<double>& q) {
  std::vector<Eigen::Isometry3d> X_WL;
  s.linkPoses(q.data(), &X_WL);
  const scene::RobotModel& m = s.model();
  auto piecesMeet = [](const scene::Piece& a, const Eigen::Isometry3d& X_WA, const scene::Piece& b,
                       const Eigen::Isometry3d& X_WB) {
    IntersectInput in;
    in.a = &a.polytope;
    in.X_WA = X_WA;
    in.b = &b.polytope;
    in.X_WB = X_WB;
    return intersect(in).intersecting;
  };
  for (int k = 0; k < m.numLinks(); ++k) {
    for (const scene::Piece& p : m.link(k).pieces) {
      for (const scene::Piece& w : s.world().pieces()) {
        if (piecesMeet(w, Eigen::Isometry3d::Identity(), p, X_WL[static_cast<std::size_t>(k)])) return true;
      }
    }
  }
  // Every link pair the allowed collisions do not skip (not the scene's own
  // list of self pairs: a pair it left out must show here).
  for (int k = 0; k < m.numLinks(); ++k) {
    for (int l = k + 1; l < m.numLinks(); ++l) {
      if (s.filter().allowed(k, l)) continue;
      for (const scene::Piece& a : m.link(k).pieces) {
        for (const scene::Piece& b : m.link(l).pieces) {
          if (piecesMeet(a, X_WL[static_cast<std::size_t>(k)], b, X_WL[static_cast<std::size_t>(l)])) return true;
        }
      }
    }
  }
  return false;
}

TEST(ArmScene, StateChecksMatchTheBruteForce) {
  const ArmFixture f = makeArm();
  // Every link with pieces against the world, plus the self pairs the SRDF keeps.
  EXPECT_EQ(f.scene->numPairs(), 11 + static_cast<int>(f.scene->selfPairs().size()));
  EXPECT_GT(f.scene->selfPairs().size(), 20u);
  Rng rng(testing::seed());
  int colliding = 0;
  const int n = 120 * testing::scale();
  for (int s = 0; s < n; ++s) {
    const std::vector<double> q = randomConfiguration(*f.model, rng);
    const bool expected = bruteCollides(*f.scene, q);
    ASSERT_EQ(f.scene->collides(q.data()), expected) << "sample " << s;
    colliding += expected ? 1 : 0;
    // The clearance's sign agrees (touching within round-off aside).
    const double c = f.scene->clearance(q.data());
    if (std::abs(c) > 1e-9) {
      EXPECT_EQ(c < 0.0, expected) << "sample " << s << " clearance " << c;
    }
  }
  EXPECT_GT(colliding, n / 10) << "too few colliding samples to test the check";
  EXPECT_LT(colliding, n * 9 / 10) << "too few free samples to test the check";
}

TEST(ArmScene, EdgeChecksAreCertified) {
  const ArmFixture f = makeArm();
  Rng rng(testing::seed() + 1);
  const int n = 150 * testing::scale();
  const int steps = 2000;
  int colliding = 0, free_edges = 0, false_alarms = 0, sampled = 0;
  while (sampled < n) {
    // Valid start; the end a random configuration or (one edge in two) a
    // short step, which stays near contact more often.
    const std::vector<double> q0 = randomConfiguration(*f.model, rng);
    if (f.scene->collides(q0.data())) continue;
    std::vector<double> q1 = randomConfiguration(*f.model, rng);
    if (sampled % 2 == 1) {
      for (std::size_t v = 0; v < q1.size(); ++v) q1[v] = q0[v] + 0.15 * (q1[v] - q0[v]);
    }
    ++sampled;
    const double dense = denseFirstContact(*f.scene, q0, q1, steps);
    const ArmEdgeResult validity = f.scene->checkEdge(q0.data(), q1.data(), EdgeQuery::kValidity);
    const ArmEdgeResult first = f.scene->checkEdge(q0.data(), q1.data(), EdgeQuery::kFirstContact);
    EXPECT_EQ(validity.collides, first.collides) << "edge " << sampled;
    if (std::isfinite(dense)) {
      ++colliding;
      ASSERT_TRUE(validity.collides) << "missed a colliding edge (dense contact at " << dense << ")";
      ASSERT_TRUE(first.collides);
      EXPECT_LE(first.fraction, dense) << "the first-contact bound is after a colliding state";
    } else {
      ++free_edges;
      if (validity.collides) ++false_alarms;
    }
  }
  EXPECT_GE(colliding, n / 5) << "too few colliding edges";
  EXPECT_GE(free_edges, n / 5) << "too few free edges";
  // Reported, not asserted: edges refused that the dense check passes.
  RecordProperty("false_alarms", false_alarms);
  std::printf("arm7 edges: %d colliding, %d free, %d false alarms\n", colliding, free_edges, false_alarms);
}

TEST(ArmScene, RejectsBadInput) {
  const ArmFixture f = makeArm();
  EXPECT_THROW(ArmScene(nullptr, armWorld(), scene::AllowedCollisions()), InvalidInputError);
  EXPECT_THROW(ArmScene(f.model, armWorld(), scene::AllowedCollisions()), InvalidInputError);
  ArmSceneOptions bad;
  bad.contact_distance = 0.0;
  EXPECT_THROW(ArmScene(f.model, armWorld(), scene::AllowedCollisions(*f.model), Eigen::Isometry3d::Identity(), bad),
               InvalidInputError);
  std::vector<double> q0 = f.model->defaultConfiguration();
  std::vector<double> q1 = q0;
  q1[2] = std::nan("");
  EXPECT_THROW(f.scene->checkEdge(q0.data(), q1.data(), EdgeQuery::kValidity), InvalidInputError);
}

}  // namespace
}  // namespace mddual::planning
