// The arms' problem sets (configs/arm7/problems and configs/panda/problems,
// scripts/arm_problems.py): six sets of MotionBenchMaker problems per robot,
// and the Panda's four in MotionBenchMaker's own scenes (scripts/mbm_panda.py);
// every problem loads, its start and goal are within the joint limits and
// free by the exact check, and its straight edge is blocked in at least some
// problems of each set (the sets are not trivial); every problem has a
// witness path (trajectoryNNNN.yaml, scripts/arm-witnesses.sh) from its start
// to its goal that the certified motion check passes, so every problem is
// solvable. And the Panda's SRDF
// (scripts/panda_configs.py): the pairs it disables beyond the adjacent ones
// touch in every sampled configuration, and every pair it checks is free in
// some.
#include <gtest/gtest.h>

#include <ompl/base/ScopedState.h>
#include <cstdio>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "arm7_dir.h"
#include "mddual/planning/arm_problem.h"

namespace mddual::planning {
namespace {

using testing::kArm7Dir;
using testing::kPandaDir;

struct ArmSets {
  std::string name;
  std::filesystem::path dir;
  std::string group;
  std::size_t problems;  ///< per set
  int blocked;           ///< at least this many blocked straight edges per set
  std::vector<std::string> sets;
};

std::ostream& operator<<(std::ostream& out, const ArmSets& s) {
  return out << s.name;
}

class ArmProblems : public ::testing::TestWithParam<ArmSets> {};

std::vector<std::string> pandaSets() {
  std::vector<std::string> sets = testing::kArmSets;
  sets.insert(sets.end(), testing::kPandaMbmSets.begin(), testing::kPandaMbmSets.end());
  return sets;
}

TEST_P(ArmProblems, EveryProblemLoadsWithAFreeStartAndGoal) {
  const ArmSets& arm = GetParam();
  const ArmRobot robot = loadArmRobot(arm.dir / (arm.name + ".urdf"), arm.dir / (arm.name + ".srdf"));
  for (const std::string& set : arm.sets) {
    const std::vector<scene::MbmProblemFiles> problems = scene::listMbmProblems(arm.dir / "problems" / set);
    EXPECT_GE(problems.size(), arm.problems) << set;
    int blocked = 0;
    for (const scene::MbmProblemFiles& files : problems) {
      // loadArmProblem throws for a start or goal out of limits or in collision.
      const ArmProblem p = loadArmProblem(robot, files);
      EXPECT_EQ(p.group, arm.group);
      EXPECT_TRUE(p.warnings.empty()) << p.name;
      EXPECT_FALSE(p.scene->collides(p.start.data())) << p.name;
      EXPECT_FALSE(p.scene->collides(p.goal.data())) << p.name;
      blocked += p.scene->checkEdge(p.start.data(), p.goal.data(), EdgeQuery::kValidity).collides ? 1 : 0;
    }
    EXPECT_GE(blocked, arm.blocked) << set << ": too few problems whose straight edge is blocked";
    std::printf("%s/%s: %zu problems, %d with the straight edge blocked\n", arm.name.c_str(), set.c_str(),
                problems.size(), blocked);
  }
}

TEST_P(ArmProblems, EveryProblemHasACertifiedWitnessPath) {
  const ArmSets& arm = GetParam();
  const ArmRobot robot = loadArmRobot(arm.dir / (arm.name + ".urdf"), arm.dir / (arm.name + ".srdf"));
  for (const std::string& set : arm.sets) {
    int edges = 0;
    for (const scene::MbmProblemFiles& files : scene::listMbmProblems(arm.dir / "problems" / set)) {
      const ArmProblem p = loadArmProblem(robot, files);
      ASSERT_FALSE(files.trajectory.empty()) << p.name << ": no witness path (run scripts/arm-witnesses.sh)";
      const std::vector<std::vector<double>> states =
          armTrajectoryStates(p, scene::loadMbmTrajectory(files.trajectory), files.trajectory.string());
      ASSERT_GE(states.size(), 2u) << p.name;
      for (int v : p.space->variables()) {
        const auto k = static_cast<std::size_t>(v);
        EXPECT_NEAR(states.front()[k], p.start[k], 1e-12) << p.name << ": the witness does not begin at the start";
        EXPECT_NEAR(states.back()[k], p.goal[k], 1e-12) << p.name << ": the witness does not end at the goal";
      }
      // Each edge as OMPL interpolates it (ArmSpace::edge), certified free.
      ompl::base::ScopedState<> s0(p.space->stateSpace()), s1(p.space->stateSpace());
      std::vector<double> q0(p.start.size()), q1(p.start.size());
      for (std::size_t i = 0; i + 1 < states.size(); ++i, ++edges) {
        p.space->setState(s0.get(), states[i].data());
        p.space->setState(s1.get(), states[i + 1].data());
        p.space->edge(s0.get(), s1.get(), q0.data(), q1.data());
        EXPECT_FALSE(p.scene->checkEdge(q0.data(), q1.data(), EdgeQuery::kValidity).collides)
            << p.name << ": witness edge " << i << " collides";
      }
    }
    std::printf("%s/%s: every witness path certified free (%d edges)\n", arm.name.c_str(), set.c_str(), edges);
  }
}

TEST(ArmWitness, BadTrajectoriesNameTheFileAndTheJoint) {
  const ArmRobot robot = loadArmRobot(kArm7Dir / "arm7.urdf", kArm7Dir / "arm7.srdf");
  const ArmProblem p = loadArmProblem(robot, scene::listMbmProblems(kArm7Dir / "problems" / "cage").front());
  const std::vector<std::string> arm = {"joint1", "joint2", "joint3", "joint4", "joint5", "joint6", "joint7"};
  const std::vector<double> zero(7, 0.0);
  auto expectError = [&](const scene::MbmTrajectory& t, const std::string& part) {
    try {
      armTrajectoryStates(p, t, "t.yaml");
      ADD_FAILURE() << "no error for " << part;
    } catch (const scene::SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  std::vector<std::string> with_finger = arm;
  with_finger.push_back("finger_left_joint");
  expectError({with_finger, {std::vector<double>(8, 0.0)}},
              "t.yaml: joint_names: joint 'finger_left_joint' is not in group 'arm'");
  expectError({{"joint1", "joint2"}, {{0.0, 0.0}}}, "t.yaml: joint_names: lacks joint 'joint3' of group 'arm'");
  std::vector<double> beyond = zero;
  beyond[3] = 0.5;  // joint4's limits are [-3, -0.07]
  expectError({arm, {beyond}}, "t.yaml: points[0]: joint 'joint4' = 0.500000 is outside its limits");
  // The joints in another order are read by name.
  std::vector<std::string> reversed(arm.rbegin(), arm.rend());
  const std::vector<double> q = {0.7, 0.6, 0.5, -0.4, 0.3, 0.2, 0.1};
  const std::vector<std::vector<double>> states = armTrajectoryStates(p, {reversed, {q}}, "t.yaml");
  const scene::MbmTrajectory back = armTrajectory(p, states);
  EXPECT_EQ(back.joint_names, arm);
  EXPECT_EQ(back.points[0], std::vector<double>(q.rbegin(), q.rend()));
}

INSTANTIATE_TEST_SUITE_P(Arms, ArmProblems,
                         ::testing::Values(ArmSets{"arm7", kArm7Dir, "arm", 20, 5, testing::kArmSets},
                                           ArmSets{"panda", kPandaDir, "panda_arm", 10, 3, pandaSets()}),
                         [](const ::testing::TestParamInfo<ArmSets>& param) { return param.param.name; });

/// Whether links k and l touch at q (the world empty, only that pair checked).
class PairCheck {
 public:
  PairCheck(const std::shared_ptr<const scene::RobotModel>& model, int k, int l) {
    scene::AllowedCollisions only(*model);
    for (int a = 0; a < model->numLinks(); ++a) {
      for (int b = 0; b < model->numLinks(); ++b) only.allow(a, b, !((a == k && b == l) || (a == l && b == k)));
    }
    scene_ = std::make_shared<ArmScene>(model, std::make_shared<const scene::World>(), only);
  }
  bool touches(const std::vector<double>& q) const { return scene_->collides(q.data()); }

 private:
  std::shared_ptr<ArmScene> scene_;
};

TEST(PandaArmModel, DisablesThePairsInContactEverywhereAndChecksTheOthers) {
  const ArmRobot robot = loadArmRobot(kPandaDir / "panda.urdf", kPandaDir / "panda.srdf");
  const scene::RobotModel& model = *robot.model;
  EXPECT_EQ(model.numVariables(), 8);  // seven arm joints and the left finger (the right one mimics it)
  const scene::AllowedCollisions srdf(model, robot.srdf);
  std::mt19937_64 rng(5);
  std::vector<std::vector<double>> samples(2000, std::vector<double>(static_cast<std::size_t>(model.numVariables())));
  for (std::vector<double>& q : samples) {
    for (const scene::Joint& j : model.joints()) {
      if (j.moves() && !j.mimic) {
        q[static_cast<std::size_t>(j.variable)] = std::uniform_real_distribution<double>(j.lower, j.upper)(rng);
      }
    }
  }
  int checked_pairs = 0;
  for (int k = 0; k < model.numLinks(); ++k) {
    for (int l = k + 1; l < model.numLinks(); ++l) {
      if (model.link(k).pieces.empty() || model.link(l).pieces.empty()) continue;
      const bool adjacent = model.link(l).parent_joint >= 0 &&
                            (model.joint(model.link(l).parent_joint).parent_link == k ||
                             (model.link(l).name == "panda_hand" && model.link(k).name == "panda_link7"));
      const PairCheck pair(robot.model, k, l);
      int touching = 0;
      for (const std::vector<double>& q : samples) touching += pair.touches(q) ? 1 : 0;
      const std::string names = model.link(k).name + " / " + model.link(l).name;
      if (touching > 0) std::printf("%s: in contact in %d of %zu samples\n", names.c_str(), touching, samples.size());
      if (srdf.allowed(k, l) && !adjacent) {
        EXPECT_EQ(touching, static_cast<int>(samples.size())) << names << ": disabled, yet free";
      } else if (!srdf.allowed(k, l)) {
        EXPECT_LT(touching, static_cast<int>(samples.size())) << names << ": checked, yet always in contact";
        ++checked_pairs;
      }
    }
  }
  EXPECT_GE(checked_pairs, 30);
}

}  // namespace
}  // namespace mddual::planning
