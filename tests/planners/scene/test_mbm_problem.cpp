// MotionBenchMaker problems: scenes and requests as MotionBenchMaker writes
// them (sequences for points, primitive types by name), the map and number
// spellings MoveIt's messages also use, frames, the allowed collision
// matrix, trajectories (witness paths) read back exactly, and every
// malformed field named with its file and path.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mddual/constants.h"
#include "mddual/scene/mbm_problem.h"
#include "scene_test_util.h"

namespace mddual::scene {
namespace {

using testing::expectSceneError;
using testing::TempDir;

const std::filesystem::path kArm7Urdf = std::filesystem::path(MDDUAL_CONFIGS_DIR) / "arm7" / "arm7.urdf";

const char* kScene = R"(name: shelf
robot_state:
  joint_state:
    name: [joint1, joint2, finger_left_joint]
    position: [0.1, -0.2, 0.03]
robot_model_name: arm7
fixed_frame_transforms:
  - header: {frame_id: world}
    child_frame_id: base
    transform:
      translation: [0, 0, 0]
      rotation: [0, 0, 0, 1]
  - child_frame_id: shelf_frame
    transform:
      translation: {x: 1.0, y: 0.0, z: 0.0}
      rotation: {x: 0, y: 0, z: 0.7071067811865476, w: 0.7071067811865476}
allowed_collision_matrix:
  entry_names: [base, link1, board]
  entry_values:
    - enabled: [false, true, true]
    - enabled: [true, false, false]
    - enabled: [true, false, false]
world:
  collision_objects:
    - header: {frame_id: world}
      id: board
      primitives:
        - type: box
          dimensions: [0.4, 0.6, 0.02]
        - type: 3
          dimensions: [0.5, 0.05]
      primitive_poses:
        - position: [0.6, 0, 0.5]
          orientation: [0, 0, 0, 1]
        - position: {x: 0.6, y: 0.3, z: 0.25}
          orientation: {x: 0, y: 0, z: 0, w: 1}
    - header: {frame_id: shelf_frame}
      id: ball
      primitives:
        - type: sphere
          dimensions: [0.05]
      primitive_poses:
        - position: [0.2, 0, 0]
    - header: {frame_id: link7}
      id: tool
      primitives:
        - type: cone
          dimensions: [0.1, 0.02]
      primitive_poses:
        - position: [0, 0, 0.3]
      meshes:
        - vertices: [[0, 0, 0], [0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]
          triangles: [[0, 2, 1], [0, 1, 3], [0, 3, 2], {vertex_indices: [1, 2, 3]}]
      mesh_poses:
        - position: [0, 0, 0.5]
          orientation: [0, 0, 0, 1]
)";

const char* kRequest = R"(planner_id: RRTConnectkConfigDefault
group_name: arm
allowed_planning_time: 60
start_state:
  joint_state:
    name: [joint1, joint2, joint3, joint4, joint5, joint6, joint7]
    position: [0, 0.1, 0, -1.5, 0, 1.6, 0]
goal_constraints:
  - joint_constraints:
      - joint_name: joint1
        position: 1.0
        tolerance_above: 0.001
        tolerance_below: 0.001
        weight: 1
      - {joint_name: joint4, position: -2.0}
)";

TEST(MbmProblem, ReadsASceneAsMotionBenchMakerWritesIt) {
  TempDir dir;
  const RobotModel model = loadRobotModel(kArm7Urdf);
  const MbmScene scene = loadMbmScene(dir.write("scene0001.yaml", kScene), model);
  ASSERT_EQ(scene.pieces.size(), 5u);  // box, cylinder, sphere, cone, one convex mesh
  EXPECT_NE(scene.pieces[0].origin.find("scene0001.yaml: object 'board', primitive 0 (box)"), std::string::npos);
  EXPECT_TRUE(scene.pieces[0].box.center().isApprox(Eigen::Vector3d(0.6, 0, 0.5), 1e-12));
  EXPECT_NEAR(scene.pieces[0].box.sizes().x(), 0.4, 1e-12);
  // The cylinder: [height, radius], along z.
  EXPECT_NEAR(scene.pieces[1].box.sizes().z(), 0.5, 1e-12);
  EXPECT_NEAR(scene.pieces[1].box.sizes().x(), 0.1, 2e-3);
  // The ball in the shelf frame: turned 90 degrees about z, then 0.2 along its x.
  EXPECT_TRUE(scene.pieces[2].box.center().isApprox(Eigen::Vector3d(1.0, 0.2, 0.0), 1e-9));
  // The tool in link7's frame at the scene's robot_state.
  std::vector<double> q = model.defaultConfiguration();
  q[0] = 0.1;
  q[1] = -0.2;
  q[7] = 0.03;
  const Eigen::Isometry3d X_W7 = model.linkPoses(q)[static_cast<std::size_t>(model.linkIndex("link7"))];
  const Eigen::Vector3d apex = X_W7 * Eigen::Vector3d(0, 0, 0.35);
  double nearest = 1.0;
  for (const Eigen::Vector3d& v : scene.pieces[3].polytope.vertices()) nearest = std::min(nearest, (v - apex).norm());
  EXPECT_LT(nearest, 1e-9);
  // The matrix: the link pair (both ways), and base allowed to touch one
  // object of three, which is warned about and not honoured.
  ASSERT_EQ(scene.allowed_link_pairs.size(), 2u);
  EXPECT_TRUE(scene.links_allowed_with_world.empty());
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("link 'base' is allowed to touch some objects only"), std::string::npos);
}

// A cone ([height, radius], along z, centred on its pose) is circumscribed
// as the cylinders are: every point of the true cone is inside the polytope,
// and every vertex within the primitive tolerance of the true cone.
TEST(MbmProblem, ConeContainsTheTrueConeWithinTolerance) {
  TempDir dir;
  const RobotModel model = loadRobotModel(kArm7Urdf);
  const double h = 0.4, r = 0.15;
  const std::string text = std::string(R"(world:
  collision_objects:
    - header: {frame_id: world}
      id: cone
      primitives:
        - type: cone
          dimensions: [)") +
                           std::to_string(h) + ", " + std::to_string(r) + R"(]
      primitive_poses:
        - position: [0.5, -0.2, 0.8]
          orientation: [0.2, 0.3, 0.1, 0.9273618495495704]
)";
  for (const double tol : {1e-2, 1e-3}) {
    LoadOptions options;
    options.primitive_tolerance = tol;
    const MbmScene scene = loadMbmScene(dir.write("scene0001.yaml", text), model, options);
    ASSERT_EQ(scene.pieces.size(), 1u);
    const ConvexPolytope& P = scene.pieces[0].polytope;
    Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
    X_WC.linear() = Eigen::Quaterniond(0.9273618495495704, 0.2, 0.3, 0.1).normalized().toRotationMatrix();
    X_WC.translation() = Eigen::Vector3d(0.5, -0.2, 0.8);
    const auto outside = [&](const Eigen::Vector3d& p_W) {
      double worst = -std::numeric_limits<double>::infinity();
      for (int f = 0; f < P.numFaces(); ++f) worst = std::max(worst, P.faceNormal(f).dot(p_W) - P.faceOffset(f));
      return worst;
    };
    // The base circle, the slant surface and the apex.
    for (int i = 0; i < 720; ++i) {
      const double a = 2.0 * kPi * (i + 0.37) / 720.0;
      const double s = (i % 10) / 10.0;  // 0 at the base, towards 1 at the apex
      const Eigen::Vector3d rim(r * std::cos(a), r * std::sin(a), -h / 2);
      const Eigen::Vector3d slant((1 - s) * r * std::cos(a), (1 - s) * r * std::sin(a), -h / 2 + s * h);
      EXPECT_LE(outside(X_WC * rim), 1e-12) << "base circle at angle " << a << ", tolerance " << tol;
      EXPECT_LE(outside(X_WC * slant), 1e-12) << "slant surface at angle " << a << ", tolerance " << tol;
    }
    EXPECT_LE(outside(X_WC * Eigen::Vector3d(0, 0, h / 2)), 1e-12);
    // Vertices: the apex, and the base polygon within the tolerance outside the circle.
    int base = 0;
    for (const Eigen::Vector3d& v_W : P.vertices()) {
      const Eigen::Vector3d v = X_WC.inverse() * v_W;
      if (std::abs(v.z() - h / 2) < 1e-9) {
        EXPECT_LT(std::hypot(v.x(), v.y()), 1e-9);
        continue;
      }
      ++base;
      EXPECT_NEAR(v.z(), -h / 2, 1e-9);
      EXPECT_GE(std::hypot(v.x(), v.y()), r - 1e-12);
      EXPECT_LE(std::hypot(v.x(), v.y()), r + tol + 1e-12);
    }
    EXPECT_GE(base, 8);
  }
}

TEST(MbmProblem, ReadsARequest) {
  TempDir dir;
  const MbmRequest r = loadMbmRequest(dir.write("request0001.yaml", kRequest));
  EXPECT_EQ(r.group, "arm");
  EXPECT_EQ(r.planner_id, "RRTConnectkConfigDefault");
  EXPECT_DOUBLE_EQ(r.allowed_planning_time, 60.0);
  ASSERT_EQ(r.start.size(), 7u);
  EXPECT_DOUBLE_EQ(r.start[3].second, -1.5);
  ASSERT_EQ(r.goal.size(), 2u);
  EXPECT_EQ(r.goal[1].joint, "joint4");
  EXPECT_DOUBLE_EQ(r.goal[1].position, -2.0);
  EXPECT_DOUBLE_EQ(r.goal[0].tolerance_above, 0.001);
}

TEST(MbmProblem, ListsTheProblemsOfADirectory) {
  TempDir dir;
  dir.write("p/scene0002.yaml", kScene);
  dir.write("p/request0002.yaml", kRequest);
  dir.write("p/scene0001.yaml", kScene);
  dir.write("p/request0001.yaml", kRequest);
  dir.write("p/trajectory0002.yaml", "joint_trajectory: {}");
  dir.write("p/notes.txt", "other files are ignored");
  const std::vector<MbmProblemFiles> problems = listMbmProblems(dir.path() / "p");
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_EQ(problems[0].number, 1);
  EXPECT_EQ(problems[1].request.filename(), "request0002.yaml");
  EXPECT_TRUE(problems[0].trajectory.empty());
  EXPECT_EQ(problems[1].trajectory.filename(), "trajectory0002.yaml");
  dir.write("p/trajectory0007.yaml", "joint_trajectory: {}");
  expectSceneError([&] { listMbmProblems(dir.path() / "p"); }, {"trajectory0007.yaml", "no scene and request"});
  std::filesystem::remove(dir.path() / "p" / "trajectory0007.yaml");
  dir.write("p/scene0003.yaml", kScene);
  expectSceneError([&] { listMbmProblems(dir.path() / "p"); }, {"scene0003.yaml", "no request file"});
  expectSceneError([&] { listMbmProblems(dir.path() / "empty_dir_missing"); }, {"not a directory"});
  std::filesystem::create_directories(dir.path() / "none");
  expectSceneError([&] { listMbmProblems(dir.path() / "none"); }, {"no problems"});
}

TEST(MbmProblem, TrajectoriesReadBackExactly) {
  TempDir dir;
  MbmTrajectory t;
  t.joint_names = {"joint1", "a, b: [c]"};  // a name YAML must quote in a flow list
  // 0.1 and -1.307065 need few digits; 1/3 and the smallest normal need 17.
  t.points = {{0.1, -1.307065}, {1.0 / 3.0, std::numeric_limits<double>::min()}, {-0.0, 2.0 * kPi}};
  const std::filesystem::path file = dir.path() / "trajectory0001.yaml";
  saveMbmTrajectory(file, t, {"a witness", "second line"});
  const MbmTrajectory back = loadMbmTrajectory(file);
  EXPECT_EQ(back.joint_names, t.joint_names);
  ASSERT_EQ(back.points.size(), t.points.size());
  for (std::size_t i = 0; i < t.points.size(); ++i) {
    ASSERT_EQ(back.points[i].size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) EXPECT_EQ(back.points[i][k], t.points[i][k]) << i << " " << k;
  }
  // MoveIt's own spelling, with times and velocities (ignored).
  const MbmTrajectory moveit = loadMbmTrajectory(dir.write("t.yaml", R"(joint_trajectory:
  header: {frame_id: world}
  joint_names: [joint1, joint2]
  points:
    - positions: [0, 0.5]
      velocities: [0, 0]
      time_from_start: {secs: 0, nsecs: 0}
    - positions: [1, -0.5]
multi_dof_joint_trajectory: {}
)"));
  ASSERT_EQ(moveit.points.size(), 2u);
  EXPECT_EQ(moveit.points[1][1], -0.5);
}

TEST(MbmProblemErrors, NameTheFileAndTheField) {
  TempDir dir;
  const RobotModel model = loadRobotModel(kArm7Urdf);
  auto scene = [&](const std::string& text) { return loadMbmScene(dir.write("scene0009.yaml", text), model); };
  auto replaced = [](std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  expectSceneError([&] { scene("world: [unclosed"); }, {"scene0009.yaml: not valid YAML (line"});
  expectSceneError(
      [&] { scene(replaced(kScene, "dimensions: [0.4, 0.6, 0.02]", "dimensions: [0.4, 0.6]")); },
      {"scene0009.yaml: world.collision_objects[0].primitives[0].dimensions: a box needs 3 values, got 2"});
  expectSceneError([&] { scene(replaced(kScene, "type: sphere", "type: capsule")); },
                   {"world.collision_objects[1].primitives[0].type", "unknown primitive type 'capsule'"});
  expectSceneError([&] { scene(replaced(kScene, "frame_id: link7", "frame_id: gripper_tip")); },
                   {"world.collision_objects[2].header.frame_id: unknown frame 'gripper_tip'"});
  expectSceneError([&] { scene(replaced(kScene, "name: [joint1,", "name: [elbow,")); },
                   {"scene0009.yaml: robot_state: joint 'elbow' is not in robot 'arm7'"});
  expectSceneError([&] { scene(replaced(kScene, "position: [0.1, -0.2, 0.03]", "position: [0.1, -0.2]")); },
                   {"robot_state.joint_state.position: has 2 values for 3 names"});
  expectSceneError([&] { scene(replaced(kScene, "orientation: [0, 0, 0, 1]", "orientation: [0, 0, 0, 0]")); },
                   {"primitive_poses[0].orientation: is not a rotation"});
  expectSceneError([&] { scene(replaced(kScene, "[0.6, 0, 0.5]", "[0.6, zero, 0.5]")); },
                   {"primitive_poses[0].position[1]: is not a number"});
  expectSceneError([&] { scene(replaced(kScene, "{vertex_indices: [1, 2, 3]}", "[1, 2, 7]")); },
                   {"meshes[0].triangles[3]", "vertex index 7"});
  expectSceneError([&] { scene(replaced(kScene, "- enabled: [true, false, false]\n", "- enabled: [true]\n")); },
                   {"allowed_collision_matrix.entry_values[1].enabled: needs 3 values"});
  auto request = [&](const std::string& text) { return loadMbmRequest(dir.write("request0009.yaml", text)); };
  expectSceneError([&] { request(replaced(kRequest, "group_name: arm\n", "")); },
                   {"request0009.yaml: group_name: missing"});
  expectSceneError([&] { request(replaced(kRequest, "position: 1.0", "position: .nan")); },
                   {"goal_constraints[0].joint_constraints[0].position: is not finite"});
  expectSceneError([&] { request("group_name: arm\n"); }, {"goal_constraints: missing"});
  auto trajectory = [&](const std::string& text) { return loadMbmTrajectory(dir.write("trajectory0009.yaml", text)); };
  expectSceneError([&] { trajectory("points: []\n"); }, {"trajectory0009.yaml: joint_trajectory.joint_names: missing"});
  expectSceneError([&] { trajectory("joint_trajectory: {joint_names: [a, b, a], points: [{positions: [0, 0, 0]}]}"); },
                   {"joint_trajectory.joint_names[2]: repeats joint 'a'"});
  expectSceneError([&] { trajectory("joint_trajectory: {joint_names: [a, b], points: []}"); },
                   {"joint_trajectory.points: missing (a trajectory needs at least one point)"});
  expectSceneError(
      [&] { trajectory("joint_trajectory: {joint_names: [a, b], points: [{positions: [0, 1]}, {positions: [1]}]}"); },
      {"joint_trajectory.points[1].positions: has 1 values for 2 joints"});
  expectSceneError([&] { trajectory("joint_trajectory: {joint_names: [a, b], points: [{positions: [0, .inf]}]}"); },
                   {"joint_trajectory.points[0].positions[1]: is not finite"});
  expectSceneError(
      [&] {
        applyJointValues(model, model.defaultConfiguration(), {{"wrist", 0.0}}, "x.yaml: start");
      },
      {"x.yaml: start: joint 'wrist' is not in robot 'arm7'"});
}

}  // namespace
}  // namespace mddual::scene
