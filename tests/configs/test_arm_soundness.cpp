// The certified arm motion check on the arms' problem sets against a dense FCL
// check of the same edges (FclArmScene: FCL's collide() on the same link and
// self pairs and pieces, states at most MDDUAL_ARM_DENSE_STEP radians apart
// in every joint, 1e-3 by default): no colliding edge called free, and the
// first-contact bound (OMPL's lastValid) never after the first colliding
// sample. Edges: random pairs of configurations, short steps from the
// problem's start toward random configurations, edges from the start to the
// goal and to configurations near it, and near-contact edges: random edges
// cut one dense step before or after their first contact. False alarms
// (edges refused that the dense check passes) are counted and printed, not
// asserted.
//
// The CI sample: 24 edges per set, on its first 2 problems (arm7's sets, the
// Panda's, and the Panda's in MotionBenchMaker's scenes). The full sweep
// (docs/testing.md): MDDUAL_PLANNING_SCALE=420 MDDUAL_ARM_DENSE_STEP=1e-4
// runs 10,080 edges per set over all its problems (20 per set of arm7, 10 of
// the Panda).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "arm7_dir.h"
#include "mddual/planning/arm_checkers.h"
#include "mddual/planning/arm_problem.h"

namespace mddual::planning {
namespace {

using testing::kArm7Dir;
using testing::kPandaDir;

/// A robot's problem set.
struct ArmSet {
  std::string robot;
  std::filesystem::path dir;
  std::string set;
};

std::ostream& operator<<(std::ostream& out, const ArmSet& s) {
  return out << s.robot << "/" << s.set;
}

double envNumber(const char* name, double fallback) {
  const char* text = std::getenv(name);
  return text == nullptr ? fallback : std::atof(text);
}

/// The first colliding state of the edge by FCL, at most `step` radians per
/// joint apart (a fraction), or +infinity.
double denseFcl(const FclArmScene& fcl, const std::vector<double>& q0, const std::vector<double>& q1, double step) {
  double largest = 0.0;
  for (std::size_t v = 0; v < q0.size(); ++v) largest = std::max(largest, std::abs(q1[v] - q0[v]));
  const int steps = std::max(1, static_cast<int>(std::ceil(largest / step)));
  std::vector<double> q(q0.size());
  for (int s = 0; s <= steps; ++s) {
    const double t = static_cast<double>(s) / steps;
    for (std::size_t v = 0; v < q.size(); ++v) q[v] = q0[v] + t * (q1[v] - q0[v]);
    if (fcl.collides(q.data())) return t;
  }
  return std::numeric_limits<double>::infinity();
}

class ArmSoundness : public ::testing::TestWithParam<ArmSet> {};

TEST_P(ArmSoundness, NoMissesAndLastValidBeforeTheFirstContact) {
  const int scale = std::max(1, static_cast<int>(envNumber("MDDUAL_PLANNING_SCALE", 1)));
  const double step = envNumber("MDDUAL_ARM_DENSE_STEP", 1e-3);
  const std::uint64_t seed = static_cast<std::uint64_t>(envNumber("MDDUAL_PLANNING_SEED", 1));
  const ArmSet& arm = GetParam();
  const ArmRobot robot = loadArmRobot(arm.dir / (arm.robot + ".urdf"), arm.dir / (arm.robot + ".srdf"));
  const std::vector<scene::MbmProblemFiles> files = scene::listMbmProblems(arm.dir / "problems" / arm.set);
  // 24 edges per set times the scale: on 2 problems at scale 1, spread over
  // every problem above.
  const std::size_t problems = scale == 1 ? std::min<std::size_t>(2, files.size()) : files.size();
  const int per_problem = static_cast<int>(24 * static_cast<std::size_t>(scale) / problems);
  std::mt19937_64 rng(seed);
  int edges = 0, colliding = 0, free_edges = 0, false_alarms = 0, near_contact = 0;
  int near_false_alarms = 0;  // false alarms among the near-contact edges
  for (std::size_t k = 0; k < problems; ++k) {
    const ArmProblem p = loadArmProblem(robot, files[k]);
    const FclArmScene fcl(p.scene);
    const std::vector<int>& group = p.space->variables();
    auto randomQ = [&] {
      std::vector<double> q = p.start;
      for (int v : group) {
        const scene::Joint& j = p.space->model().joint(p.space->model().variableJoint(v));
        q[static_cast<std::size_t>(v)] = std::uniform_real_distribution<double>(j.lower, j.upper)(rng);
      }
      return q;
    };
    for (int e = 0; e < per_problem; ++e) {
      std::vector<double> q0, q1;
      bool near = false;
      switch (e % 6) {
        case 0:  // random pair
          q0 = randomQ();
          q1 = randomQ();
          break;
        case 1: {  // a short step from the start
          q0 = p.start;
          q1 = randomQ();
          for (int v : group)
            q1[std::size_t(v)] = q0[std::size_t(v)] + 0.25 * (q1[std::size_t(v)] - q0[std::size_t(v)]);
          break;
        }
        case 2:  // start to goal, then start to a random configuration
          q0 = p.start;
          q1 = e == 2 ? p.goal : randomQ();
          break;
        case 3: {  // toward the goal region from a random configuration
          q1 = p.goal;
          q0 = randomQ();
          for (int v : group) q0[std::size_t(v)] = q1[std::size_t(v)] + 0.3 * (q0[std::size_t(v)] - q1[std::size_t(v)]);
          break;
        }
        default: {  // near a contact: a random edge cut one dense step before (4) or after (5) its first
          // A free q0 and an edge from it that meets a contact (a few tries).
          double t = 0.0;
          for (int tries = 0; tries < 50 && !(t > 0.0 && t < 1.0); ++tries) {
            q0 = randomQ();
            q1 = randomQ();
            t = fcl.collides(q0.data()) ? 0.0 : denseFcl(fcl, q0, q1, step);
          }
          if (!(t > 0.0 && t < 1.0)) break;  // kept as a random pair
          ++near_contact;
          near = true;
          double largest = 0.0;
          for (int v : group) largest = std::max(largest, std::abs(q1[std::size_t(v)] - q0[std::size_t(v)]));
          const double cut = e % 6 == 4 ? std::max(0.0, t - step / largest) : std::min(1.0, t + step / largest);
          for (int v : group) q1[std::size_t(v)] = q0[std::size_t(v)] + cut * (q1[std::size_t(v)] - q0[std::size_t(v)]);
        }
      }
      ++edges;
      const double dense = denseFcl(fcl, q0, q1, step);
      const ArmEdgeResult validity = p.scene->checkEdge(q0.data(), q1.data(), EdgeQuery::kValidity);
      const ArmEdgeResult first = p.scene->checkEdge(q0.data(), q1.data(), EdgeQuery::kLastValid);
      ASSERT_EQ(validity.collides, first.collides) << p.name << " edge " << e;
      if (std::isfinite(dense)) {
        ++colliding;
        ASSERT_TRUE(validity.collides) << p.name << " edge " << e << ": missed, FCL finds a contact at " << dense;
        ASSERT_LE(first.fraction, dense) << p.name << " edge " << e << ": lastValid after FCL's first contact";
      } else {
        ++free_edges;
        false_alarms += validity.collides ? 1 : 0;
        near_false_alarms += validity.collides && near ? 1 : 0;
      }
    }
  }
  EXPECT_GE(colliding, edges / 10) << "too few colliding edges to test the check";
  EXPECT_GE(free_edges, edges / 10) << "too few free edges to test the check";
  EXPECT_GE(near_contact, edges / 4) << "too few near-contact edges (a third of them expected)";
  std::printf(
      "%s/%s: %d edges (%d near a contact), %d colliding, %d free, %d false alarms (%d near a contact) "
      "(dense step %g rad)\n",
      arm.robot.c_str(), arm.set.c_str(), edges, near_contact, colliding, free_edges, false_alarms, near_false_alarms,
      step);
}

std::vector<ArmSet> armSets() {
  std::vector<ArmSet> out;
  for (const std::string& set : testing::kArmSets) {
    out.push_back({"arm7", kArm7Dir, set});
    out.push_back({"panda", kPandaDir, set});
  }
  for (const std::string& set : testing::kPandaMbmSets) out.push_back({"panda", kPandaDir, set});
  return out;
}

INSTANTIATE_TEST_SUITE_P(Arms, ArmSoundness, ::testing::ValuesIn(armSets()),
                         [](const ::testing::TestParamInfo<ArmSet>& param) {
                           return param.param.robot + "_" + param.param.set;
                         });

}  // namespace
}  // namespace mddual::planning
