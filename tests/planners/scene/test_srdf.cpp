// SRDF: groups (chains, joints, links, subgroups), group states, the
// collision matrix, and bad input, on configs/arm7 and files written here.
#include <gtest/gtest.h>

#include "mddual/scene/srdf.h"
#include "scene_test_util.h"

namespace mddual::scene {
namespace {

using testing::expectSceneError;
using testing::TempDir;

const std::filesystem::path kArm7Dir = std::filesystem::path(MDDUAL_CONFIGS_DIR) / "arm7";

std::vector<std::string> variableNames(const RobotModel& model, const std::vector<int>& variables) {
  std::vector<std::string> out;
  for (int v : variables) out.push_back(model.variableName(v));
  return out;
}

TEST(Srdf, ResolvesTheGroupsOfArm7) {
  const RobotModel model = loadRobotModel(kArm7Dir / "arm7.urdf");
  const Srdf srdf = loadSrdf(kArm7Dir / "arm7.srdf");
  EXPECT_EQ(srdf.robot_name, "arm7");
  ASSERT_EQ(srdf.virtual_joints.size(), 1u);
  EXPECT_EQ(srdf.virtual_joints[0].child_link, "base");
  EXPECT_EQ(variableNames(model, groupVariables(srdf, model, "arm")),
            (std::vector<std::string>{"joint1", "joint2", "joint3", "joint4", "joint5", "joint6", "joint7"}));
  // The mimic finger stands for its leader.
  EXPECT_EQ(variableNames(model, groupVariables(srdf, model, "hand")), std::vector<std::string>{"finger_left_joint"});
  EXPECT_EQ(groupVariables(srdf, model, "arm_hand").size(), 8u);
  const auto ready = groupStateValues(srdf, model, "arm", "ready");
  ASSERT_EQ(ready.size(), 7u);
  EXPECT_EQ(model.variableName(ready[3].first), "joint4");
  EXPECT_DOUBLE_EQ(ready[3].second, -1.2);

  const AllowedCollisions filter(model, srdf);
  EXPECT_TRUE(filter.allowed(model.linkIndex("link3"), model.linkIndex("link2")));
  EXPECT_TRUE(filter.allowed(model.linkIndex("hand"), model.linkIndex("finger_left")));
  EXPECT_FALSE(filter.allowed(model.linkIndex("link2"), model.linkIndex("link4")));
  EXPECT_FALSE(filter.allowed(model.linkIndex("finger_left"), model.linkIndex("finger_right")));
}

TEST(Srdf, CollisionMatrixDefaultsAndReenables) {
  TempDir dir;
  const RobotModel model = loadRobotModel(kArm7Dir / "arm7.urdf");
  const Srdf srdf = parseSrdf(R"(<robot name="arm7">
    <disable_default_collisions link="hand"/>
    <enable_collisions link1="hand" link2="link2"/>
    <disable_collisions link1="link1" link2="link5"/></robot>)",
                              "m.srdf");
  const AllowedCollisions filter(model, srdf);
  int skipped = 0;
  for (int l = 0; l < model.numLinks(); ++l) skipped += filter.allowed(model.linkIndex("hand"), l) ? 1 : 0;
  EXPECT_EQ(skipped, model.numLinks() - 1);  // all but link2
  EXPECT_FALSE(filter.allowed(model.linkIndex("link2"), model.linkIndex("hand")));
  EXPECT_TRUE(filter.allowed(model.linkIndex("link5"), model.linkIndex("link1")));
}

TEST(SrdfErrors, NameTheFileElementAndName) {
  const RobotModel model = loadRobotModel(kArm7Dir / "arm7.urdf");
  expectSceneError([] { parseSrdf("<robot><group name='a'>", "broken.srdf"); }, {"broken.srdf", "not well-formed"});
  expectSceneError([] { parseSrdf("<robots/>", "x.srdf"); }, {"x.srdf", "no <robot> root"});
  expectSceneError([] { parseSrdf("<robot>\n<group/></robot>", "x.srdf"); },
                   {"x.srdf, line 2, <group>", "missing attribute 'name'"});
  expectSceneError(
      [] {
        parseSrdf(R"(<robot><group_state name="s" group="g"><joint name="j" value="1.5x"/></group_state></robot>)",
                  "x.srdf");
      },
      {"x.srdf, line 1, <joint>", "'value' is not a finite number", "1.5x"});
  auto group = [&](const std::string& body) { return parseSrdf("<robot>" + body + "</robot>", "g.srdf"); };
  expectSceneError([&] { groupVariables(group(R"(<group name="g"><joint name="elbow"/></group>)"), model, "g"); },
                   {"g.srdf: group 'g'", "joint 'elbow' is not in robot 'arm7'"});
  expectSceneError([&] { groupVariables(group(R"(<group name="g"><link name="paw"/></group>)"), model, "g"); },
                   {"g.srdf: group 'g'", "link 'paw'"});
  expectSceneError(
      [&] {
        groupVariables(group(R"(<group name="g"><chain base_link="link5" tip_link="link2"/></group>)"), model, "g");
      },
      {"group 'g'", "chain tip 'link2' is not below its base 'link5'"});
  expectSceneError(
      [&] {
        groupVariables(group(R"(<group name="g"><group name="h"/></group><group name="h"><group name="g"/></group>)"),
                       model, "g");
      },
      {"group 'g'", "cycle"});
  expectSceneError([&] { groupVariables(group(R"(<group name="g"><link name="base"/></group>)"), model, "g"); },
                   {"group 'g'", "an empty group"});
  expectSceneError([&] { groupVariables(group(""), model, "arm"); }, {"g.srdf: no group 'arm'"});
  expectSceneError([&] { AllowedCollisions(model, group(R"(<disable_collisions link1="base" link2="paw"/>)")); },
                   {"g.srdf", "<disable_collisions>", "link 'paw'"});
  expectSceneError([&] { groupStateValues(group(""), model, "arm", "home"); }, {"no group_state 'home'"});
}

}  // namespace
}  // namespace mddual::scene
