// MotionBenchMaker problems, read unchanged with yaml-cpp: a problem
// directory holds sceneNNNN.yaml (a MoveIt PlanningScene) and
// requestNNNN.yaml (a MotionPlanRequest) per problem, as MotionBenchMaker
// writes them.
//
// Read from a scene: robot_state.joint_state (names, positions),
// fixed_frame_transforms, allowed_collision_matrix (entry_names,
// entry_values[].enabled) and world.collision_objects: header.frame_id, id,
// an optional pose, primitives (box [x y z], sphere [r], cylinder [height
// radius], cone [height radius]; the type as a name or as
// shape_msgs/SolidPrimitive's number) with primitive_poses, and meshes
// (vertices, triangles) with mesh_poses. Points and vectors may be
// sequences [x, y, z] or maps {x, y, z}; quaternions [x, y, z, w] or maps.
// From a request: group_name, planner_id, allowed_planning_time,
// start_state.joint_state and goal_constraints[0].joint_constraints.
// A trajectory file (trajectoryNNNN.yaml beside a problem, such as the
// witness paths of the project's problem sets, or a path `mddual bench
// --save-paths` wrote) is a moveit_msgs/RobotTrajectory: joint_trajectory.
// joint_names and joint_trajectory.points[].positions; times and velocities
// are ignored.
// Unknown fields are ignored; a missing or malformed field is a SceneError
// naming the file and the field's path (world.collision_objects[2].
// primitives[0].dimensions).
//
// Frames: the world frame W is the planning frame ("world", "" or the
// frame the robot's root is given in). An object's header.frame_id may name
// W, a frame of fixed_frame_transforms, or a link of the robot (posed at the
// scene's robot_state).
#pragma once

#include <Eigen/Geometry>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "mddual/scene/loaders.h"
#include "mddual/scene/robot_model.h"
#include "mddual/scene/scene.h"

namespace mddual::scene {

/// One joint goal of a request (moveit_msgs/JointConstraint).
struct JointGoal {
  std::string joint;
  double position = 0.0;
  double tolerance_above = 0.0;
  double tolerance_below = 0.0;
};

/// A MotionPlanRequest.
struct MbmRequest {
  std::string group;
  std::string planner_id;                             ///< empty when absent
  double allowed_planning_time = 0.0;                 ///< seconds; 0 when absent
  std::vector<std::pair<std::string, double>> start;  ///< start_state joint values
  std::vector<JointGoal> goal;
};

/// A PlanningScene, with its world built against a robot model.
struct MbmScene {
  std::vector<std::pair<std::string, double>> robot_state;  ///< joint values
  /// The world's pieces (frame W), origins "scene0001.yaml: object 'Can1',
  /// primitive 0 (cylinder)".
  std::vector<Piece> pieces;
  /// Robot link pairs the allowed collision matrix enables (skipped by the
  /// self check), as link indices.
  std::vector<std::pair<int, int>> allowed_link_pairs;
  /// Links allowed to touch the world (their pieces are not checked against
  /// any world object): the matrix's entries between a link and an object.
  /// Only entries allowing every object are honoured; others are listed in
  /// `warnings`.
  std::vector<int> links_allowed_with_world;
  /// The root link's pose in W (a fixed_frame_transforms entry naming it, or
  /// the identity).
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  std::vector<std::string> warnings;
};

/// A joint trajectory: the values of joint_names at each point.
struct MbmTrajectory {
  std::vector<std::string> joint_names;
  std::vector<std::vector<double>> points;  ///< each as long as joint_names
};

/// One problem of a directory: its files and its number.
struct MbmProblemFiles {
  int number = 0;
  std::filesystem::path scene;
  std::filesystem::path request;
  std::filesystem::path trajectory;  ///< trajectoryNNNN.yaml; empty when there is none
};

/// The problems of a MotionBenchMaker directory (every sceneNNNN.yaml with its
/// requestNNNN.yaml and its trajectoryNNNN.yaml if any), by number. Throws
/// SceneError naming the directory when it does not exist or holds no
/// problem, and naming the file when a scene has no request or a request or
/// a trajectory no scene.
std::vector<MbmProblemFiles> listMbmProblems(const std::filesystem::path& dir);

/// Reads a request. Throws SceneError naming the file and the field.
MbmRequest loadMbmRequest(const std::filesystem::path& file);

/// Reads a trajectory. Throws SceneError naming the file and the field for a
/// missing or malformed field, no point, a point whose length is not the
/// number of names, a repeated name or a value that is not finite.
MbmTrajectory loadMbmTrajectory(const std::filesystem::path& file);

/// Writes a trajectory as loadMbmTrajectory reads it (each value in the
/// fewest digits that read back exactly), after `comment` lines
/// (each prefixed with "# "). Throws SceneError when the file cannot be
/// written.
void saveMbmTrajectory(const std::filesystem::path& file, const MbmTrajectory& trajectory,
                       const std::vector<std::string>& comment = {});

/// Reads a scene and builds its world against `model` (link frames, joint
/// names of robot_state, the matrix's link names). Throws SceneError naming
/// the file and the field for a missing or malformed field, an unknown frame,
/// an unknown joint in robot_state, or a shape that cannot be built.
MbmScene loadMbmScene(const std::filesystem::path& file, const RobotModel& model, const LoadOptions& options = {});

/// A full configuration: `base` with the named joints set. Throws SceneError
/// naming `what` and the joint for an unknown joint, a fixed one, or a value
/// that is not finite; mimic joints are skipped (their leader decides).
std::vector<double> applyJointValues(const RobotModel& model, std::vector<double> base,
                                     const std::vector<std::pair<std::string, double>>& values,
                                     const std::string& what);

}  // namespace mddual::scene
