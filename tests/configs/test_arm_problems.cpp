// arm7's problem sets (configs/arm7/problems, scripts/arm_problems.py): six
// sets of MotionBenchMaker problems; every problem loads, its start and goal
// are within the joint limits and free by the exact check, and its straight
// edge is blocked in at least some problems of each set (the sets are not
// trivial).
#include <gtest/gtest.h>

#include "arm7_dir.h"
#include "mddual/planning/arm_problem.h"

namespace mddual::planning {
namespace {

using testing::kArm7Dir;

TEST(ArmProblems, EveryProblemLoadsWithAFreeStartAndGoal) {
  const ArmRobot robot = loadArmRobot(kArm7Dir / "arm7.urdf", kArm7Dir / "arm7.srdf");
  const std::vector<std::string> sets = {"bookshelf_thin",   "cage",      "box", "table_pick",
                                         "table_under_pick", "table_bars"};
  for (const std::string& set : sets) {
    const std::vector<scene::MbmProblemFiles> problems = scene::listMbmProblems(kArm7Dir / "problems" / set);
    EXPECT_GE(problems.size(), 20u) << set;
    int blocked = 0;
    for (const scene::MbmProblemFiles& files : problems) {
      // loadArmProblem throws for a start or goal out of limits or in collision.
      const ArmProblem p = loadArmProblem(robot, files);
      EXPECT_EQ(p.group, "arm");
      EXPECT_TRUE(p.warnings.empty()) << p.name;
      EXPECT_FALSE(p.scene->collides(p.start.data())) << p.name;
      EXPECT_FALSE(p.scene->collides(p.goal.data())) << p.name;
      blocked += p.scene->checkEdge(p.start.data(), p.goal.data(), EdgeQuery::kValidity).collides ? 1 : 0;
    }
    EXPECT_GE(blocked, 5) << set << ": too few problems whose straight edge is blocked";
  }
}

}  // namespace
}  // namespace mddual::planning
