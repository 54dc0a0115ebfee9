// RobotModel: URDF joints and links, forward kinematics against orocos KDL
// (kdl_parser on the same URDF) at random configurations of every test
// robot, the reach bound against the posed vertices, mesh look-up and bad
// input.
#include <gtest/gtest.h>
#include <kdl/jntarray.hpp>
#include <kdl/tree.hpp>
#include <kdl/treefksolverpos_recursive.hpp>
#include <kdl_parser/kdl_parser.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "mddual/scene/robot_model.h"
#include "scene_test_util.h"

namespace mddual::scene {
namespace {

using testing::expectSceneError;
using testing::TempDir;

const std::filesystem::path kArm7 = std::filesystem::path(MDDUAL_CONFIGS_DIR) / "arm7" / "arm7.urdf";
const std::filesystem::path kPanda = std::filesystem::path(MDDUAL_CONFIGS_DIR) / "panda" / "panda.urdf";

/// A tree with every joint kind: a branch, rotated and offset origins, a
/// continuous joint, a prismatic joint, a mimic of it with a multiplier and
/// offset, a mimic of that mimic, and a fixed joint.
const char* kTreeUrdf = R"(<?xml version="1.0"?>
<robot name="tree">
  <link name="root"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="a"><collision><origin xyz="0 0 0.2"/><geometry><cylinder radius="0.05" length="0.4"/></geometry></collision></link>
  <link name="b"><collision><origin xyz="0.1 0 0"/><geometry><box size="0.2 0.05 0.05"/></geometry></collision></link>
  <link name="c"><collision><geometry><sphere radius="0.04"/></geometry></collision></link>
  <link name="d"><collision><geometry><box size="0.03 0.03 0.1"/></geometry></collision></link>
  <link name="e"><collision><geometry><box size="0.03 0.03 0.1"/></geometry></collision></link>
  <link name="f"/>
  <link name="g"><collision><origin xyz="0 0.1 0" rpy="0.3 0 0"/><geometry><box size="0.05 0.2 0.05"/></geometry></collision></link>
  <joint name="j_a" type="revolute"><parent link="root"/><child link="a"/>
    <origin xyz="0.1 0 0.05" rpy="0.2 -0.1 0.4"/><axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="j_b" type="continuous"><parent link="a"/><child link="b"/>
    <origin xyz="0 0 0.4" rpy="0 1.2 0"/><axis xyz="0.6 0.8 0"/></joint>
  <joint name="j_c" type="prismatic"><parent link="b"/><child link="c"/>
    <origin xyz="0.2 0 0"/><axis xyz="1 0 0"/><limit lower="-0.05" upper="0.15" effort="1" velocity="1"/></joint>
  <joint name="j_d" type="prismatic"><parent link="c"/><child link="d"/>
    <origin xyz="0 0.05 0"/><axis xyz="0 1 0"/><limit lower="0" upper="0.5" effort="1" velocity="1"/>
    <mimic joint="j_c" multiplier="2" offset="0.1"/></joint>
  <joint name="j_e" type="prismatic"><parent link="c"/><child link="e"/>
    <origin xyz="0 -0.05 0"/><axis xyz="0 -1 0"/><limit lower="0" upper="1" effort="1" velocity="1"/>
    <mimic joint="j_d" multiplier="0.5" offset="0.02"/></joint>
  <joint name="j_f" type="fixed"><parent link="root"/><child link="f"/><origin xyz="-0.3 0 0" rpy="0 0 1"/></joint>
  <joint name="j_g" type="revolute"><parent link="f"/><child link="g"/>
    <origin xyz="0 0 0.1"/><axis xyz="1 0 0"/><limit lower="-1" upper="3" effort="1" velocity="1"/></joint>
</robot>
)";

std::string readText(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A configuration within the limits (continuous joints in [-2 pi, 2 pi]).
std::vector<double> randomConfiguration(const RobotModel& model, std::mt19937& rng) {
  std::vector<double> q(static_cast<std::size_t>(model.numVariables()));
  for (int v = 0; v < model.numVariables(); ++v) {
    const Joint& j = model.joint(model.variableJoint(v));
    const double lo = std::isfinite(j.lower) ? j.lower : -6.3;
    const double hi = std::isfinite(j.upper) ? j.upper : 6.3;
    q[static_cast<std::size_t>(v)] = std::uniform_real_distribution<double>(lo, hi)(rng);
  }
  return q;
}

/// Compares our link poses with KDL's at `samples` random configurations.
void expectKdlAgrees(const RobotModel& model, const std::string& urdf_text, int samples) {
  KDL::Tree tree;
  ASSERT_TRUE(kdl_parser::treeFromString(urdf_text, tree));
  KDL::TreeFkSolverPos_recursive fk(tree);
  std::map<std::string, unsigned> q_index;  // KDL's joint index by joint name
  for (const auto& [name, element] : tree.getSegments()) {
    const KDL::Joint& joint = GetTreeElementSegment(element).getJoint();
    if (joint.getType() != KDL::Joint::None) q_index[joint.getName()] = GetTreeElementQNr(element);
  }
  ASSERT_EQ(q_index.size(), tree.getNrOfJoints());
  std::mt19937 rng(7);
  int compared = 0;
  for (int s = 0; s < samples; ++s) {
    const std::vector<double> q = randomConfiguration(model, rng);
    KDL::JntArray kq(tree.getNrOfJoints());
    for (const Joint& j : model.joints()) {
      if (!j.moves()) continue;
      // KDL ignores <mimic>: give the mimic joint its own value.
      kq(q_index.at(j.name)) = j.value(q[static_cast<std::size_t>(j.variable)]);
    }
    const std::vector<Eigen::Isometry3d> X_BL = model.linkPoses(q);
    for (int k = 1; k < model.numLinks(); ++k) {
      KDL::Frame f;
      ASSERT_GE(fk.JntToCart(kq, f, model.link(k).name), 0) << model.link(k).name;
      for (int r = 0; r < 3; ++r) {
        EXPECT_NEAR(X_BL[static_cast<std::size_t>(k)].translation()[r], f.p(r), 1e-12) << model.link(k).name;
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(X_BL[static_cast<std::size_t>(k)].linear()(r, c), f.M(r, c), 1e-12) << model.link(k).name;
        }
      }
      ++compared;
    }
  }
  EXPECT_EQ(compared, samples * (model.numLinks() - 1));
}

TEST(RobotModel, ReadsTheJointsOfATree) {
  TempDir dir;
  const RobotModel model = loadRobotModel(dir.write("tree.urdf", kTreeUrdf));
  EXPECT_EQ(model.name(), "tree");
  EXPECT_EQ(model.numLinks(), 8);
  ASSERT_EQ(model.numVariables(), 4);  // j_a, j_b, j_c, j_g; j_d and j_e mimic j_c
  const Joint& d = model.joint(model.jointIndex("j_d"));
  EXPECT_TRUE(d.mimic);
  EXPECT_EQ(d.variable, model.variableIndex("j_c"));
  EXPECT_DOUBLE_EQ(d.multiplier, 2.0);
  // j_e mimics j_d: 0.5 (2 v + 0.1) + 0.02 = v + 0.07.
  const Joint& e = model.joint(model.jointIndex("j_e"));
  EXPECT_EQ(e.variable, model.variableIndex("j_c"));
  EXPECT_DOUBLE_EQ(e.multiplier, 1.0);
  EXPECT_NEAR(e.offset, 0.07, 1e-15);
  EXPECT_EQ(model.joint(model.jointIndex("j_b")).type, JointType::kContinuous);
  EXPECT_FALSE(std::isfinite(model.joint(model.jointIndex("j_b")).upper));
  EXPECT_EQ(model.findLink("f") >= 0 ? model.link(model.findLink("f")).pieces.size() : 99u, 0u);
  // Parents before children.
  for (const Joint& j : model.joints()) EXPECT_LT(j.parent_link, j.child_link);
  EXPECT_EQ(model.commonAncestor(model.linkIndex("d"), model.linkIndex("e")), model.linkIndex("c"));
  EXPECT_EQ(model.commonAncestor(model.linkIndex("d"), model.linkIndex("g")), 0);
}

TEST(RobotModel, ForwardKinematicsMatchesKdl) {
  TempDir dir;
  const RobotModel tree = loadRobotModel(dir.write("tree.urdf", kTreeUrdf));
  expectKdlAgrees(tree, kTreeUrdf, 200);
  const RobotModel arm = loadRobotModel(kArm7);
  EXPECT_EQ(arm.numVariables(), 8);
  expectKdlAgrees(arm, readText(kArm7), 200);
  // The Panda: rotated joint origins (rpy), a fixed flange and a turned hand.
  const RobotModel panda = loadRobotModel(kPanda);
  EXPECT_EQ(panda.numVariables(), 8);
  expectKdlAgrees(panda, readText(kPanda), 200);
  // Its flange at the ready pose, where Franka's published kinematics put it.
  const std::vector<double> values = {0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785};
  std::vector<double> ready(8, 0.0);
  for (std::size_t i = 0; i < values.size(); ++i) {
    ready[static_cast<std::size_t>(panda.variableIndex("panda_joint" + std::to_string(i + 1)))] = values[i];
  }
  const Eigen::Vector3d flange =
      panda.linkPoses(ready)[static_cast<std::size_t>(panda.linkIndex("panda_link8"))].translation();
  EXPECT_NEAR(flange.x(), 0.307, 1e-3);
  EXPECT_NEAR(flange.y(), 0.0, 1e-3);
  EXPECT_NEAR(flange.z(), 0.590, 1e-3);
}

TEST(RobotModel, ReachBoundsEveryVertexFromItsJoints) {
  TempDir dir;
  for (const RobotModel& model :
       {loadRobotModel(dir.write("tree.urdf", kTreeUrdf)), loadRobotModel(kArm7), loadRobotModel(kPanda)}) {
    std::mt19937 rng(11);
    int checked = 0;
    double tightest = 0.0;  // largest ratio |x - o_j| / reach seen
    for (int s = 0; s < 300; ++s) {
      const std::vector<double> q = randomConfiguration(model, rng);
      const std::vector<Eigen::Isometry3d> X_BL = model.linkPoses(q);
      for (int k = 1; k < model.numLinks(); ++k) {
        for (int j : model.jointPath(k)) {
          const Joint& joint = model.joint(j);
          const Eigen::Vector3d o_B = X_BL[static_cast<std::size_t>(joint.parent_link)] * joint.X_PJ.translation();
          const double reach = model.reach(j, k);
          for (const Piece& p : model.link(k).pieces) {
            for (const Eigen::Vector3d& v : p.polytope.vertices()) {
              const double r = (X_BL[static_cast<std::size_t>(k)] * v - o_B).norm();
              EXPECT_LE(r, reach * (1 + 1e-12)) << model.link(k).name << " from " << joint.name;
              tightest = std::max(tightest, r / reach);
              ++checked;
            }
          }
        }
      }
    }
    EXPECT_GT(checked, 10000);
    EXPECT_GT(tightest, 0.7) << "the bound is far from the vertices: the sample is not testing it";
  }
}

TEST(RobotModel, FindsPackageMeshesOnThePackagePath) {
  TempDir dir;
  const std::string urdf = R"(<robot name="r"><link name="base"/>
    <link name="l"><collision><geometry><mesh filename="package://parts/m/box.stl"/></geometry></collision></link>
    <joint name="j" type="revolute"><parent link="base"/><child link="l"/><axis xyz="0 0 1"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>)";
  const auto file = dir.write("robots/r.urdf", urdf);
  RobotLoadOptions options;
  options.use_environment = false;
  expectSceneError([&] { loadRobotModel(file, options); },
                   {"r.urdf: link 'l', collision 0: mesh 'package://parts/m/box.stl' not found; searched:",
                    (dir.path() / "robots" / "parts" / "m" / "box.stl").string(),
                    (dir.path() / "parts" / "m" / "box.stl").string()});
  dir.write("elsewhere/parts/m/box.stl",
            testing::asciiStl(testing::boxTriangles(-Eigen::Vector3d::Ones(), Eigen::Vector3d::Ones())));
  options.package_path = {dir.path() / "elsewhere"};
  const RobotModel model = loadRobotModel(file, options);
  ASSERT_EQ(model.link(model.linkIndex("l")).pieces.size(), 1u);
  EXPECT_NEAR(model.link(model.linkIndex("l")).radius, std::sqrt(3.0), 1e-9);
  // A relative path is looked up the same way.
  const auto relative = dir.write("robots/rel.urdf", std::string(urdf).replace(urdf.find("package://"), 10, ""));
  EXPECT_EQ(loadRobotModel(relative, options).link(1).pieces.size(), 1u);
}

TEST(RobotModel, RejectsBadJoints) {
  TempDir dir;
  auto robot = [&](const std::string& joint) {
    return dir.write("bad.urdf",
                     R"(<robot name="r"><link name="base"/><link name="l"/><link name="m"/>)" + joint + "</robot>");
  };
  expectSceneError(
      [&] {
        loadRobotModel(robot(R"(<joint name="j" type="revolute"><parent link="base"/><child link="l"/>
          <axis xyz="0 0 1"/><limit lower="1" upper="-1" effort="1" velocity="1"/></joint>
          <joint name="k" type="fixed"><parent link="l"/><child link="m"/></joint>)"));
      },
      {"bad.urdf: robot 'r': joint 'j'", "lower <= upper"});
  expectSceneError(
      [&] {
        loadRobotModel(robot(R"(<joint name="j" type="prismatic"><parent link="base"/><child link="l"/>
          <axis xyz="0 0 0"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>
          <joint name="k" type="fixed"><parent link="l"/><child link="m"/></joint>)"));
      },
      {"bad.urdf: robot 'r': joint 'j'", "axis"});
  expectSceneError(
      [&] {
        loadRobotModel(robot(R"(<joint name="j" type="continuous"><parent link="base"/><child link="l"/></joint>
          <joint name="k" type="continuous"><parent link="l"/><child link="m"/><mimic joint="nope"/></joint>)"));
      },
      {"bad.urdf: joint 'k'", "mimics 'nope', which does not exist"});
  expectSceneError(
      [&] {
        loadRobotModel(robot(R"(<joint name="j" type="fixed"><parent link="base"/><child link="l"/></joint>
          <joint name="k" type="continuous"><parent link="l"/><child link="m"/><mimic joint="j"/></joint>)"));
      },
      {"joint 'k'", "a fixed joint"});
  const RobotModel arm = loadRobotModel(kArm7);
  expectSceneError([&] { arm.jointIndex("elbow"); }, {"robot 'arm7'", "no joint 'elbow'"});
  expectSceneError([&] { arm.variableIndex("finger_right_joint"); }, {"'finger_right_joint' is a mimic joint"});
  expectSceneError([&] { arm.linkPoses(std::vector<double>(3, 0.0)); }, {"needs 8 values (got 3)"});
}

}  // namespace
}  // namespace mddual::scene
