// Arm problems: a robot (URDF and SRDF) and a MotionBenchMaker problem
// (scene and request) put together for planning: the ArmScene of the scene's
// world with the SRDF's and the scene's allowed collisions, the request's
// group as an ArmSpace, and its start and goal as full configurations,
// checked before any planner runs.
//
//   const ArmRobot robot = loadArmRobot("arm7.urdf", "arm7.srdf");
//   for (const auto& files : scene::listMbmProblems("problems/bookshelf"))
//     ArmProblem p = loadArmProblem(robot, files);
//
// Errors: scene::SceneError naming the file and the field or joint.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "mddual/planning/arm_scene.h"
#include "mddual/planning/arm_space.h"
#include "mddual/scene/mbm_problem.h"
#include "mddual/scene/robot_model.h"
#include "mddual/scene/srdf.h"

namespace mddual::planning {

/// A robot model and its SRDF, loaded once for many problems.
struct ArmRobot {
  std::shared_ptr<const scene::RobotModel> model;
  scene::Srdf srdf;
};

/// Loads the URDF (with the package path for its meshes) and the SRDF, and
/// checks the SRDF's names against the model.
ArmRobot loadArmRobot(const std::filesystem::path& urdf, const std::filesystem::path& srdf,
                      const scene::RobotLoadOptions& options = {});

/// One problem, ready for planning.
struct ArmProblem {
  std::string name;  ///< "<directory>-<number>", e.g. "bookshelf-0003"
  scene::MbmProblemFiles files;
  scene::MbmRequest request;
  std::string group;
  std::shared_ptr<const scene::World> world;
  std::shared_ptr<const ArmScene> scene;
  ArmSpacePtr space;
  std::vector<double> start;  ///< full configuration
  std::vector<double> goal;   ///< full configuration
  std::vector<std::string> warnings;
};

/// Options of loadArmProblem.
struct ArmProblemOptions {
  std::string group;  ///< overrides the request's group_name when not empty
  scene::LoadOptions load;
  ArmSceneOptions scene;
};

/// Builds a problem (see the file comment). Throws SceneError naming the file
/// and the joint for: a group the SRDF does not have or that is empty, a goal
/// joint outside the group, a start or goal value outside its joint's
/// limits, and a start or goal in collision (naming the link and the object
/// or the other link).
ArmProblem loadArmProblem(const ArmRobot& robot, const scene::MbmProblemFiles& files,
                          const ArmProblemOptions& options = {});

/// A trajectory's points as full configurations of p: p's start with the
/// trajectory's values set, one per point. Throws SceneError naming `what`
/// and the joint for a joint outside p's group, a group joint the
/// trajectory lacks, or a value outside its joint's limits.
std::vector<std::vector<double>> armTrajectoryStates(const ArmProblem& p, const scene::MbmTrajectory& trajectory,
                                                     const std::string& what);

/// Full configurations of p as a trajectory over its group's joints, in the
/// group's order.
scene::MbmTrajectory armTrajectory(const ArmProblem& p, const std::vector<std::vector<double>>& states);

}  // namespace mddual::planning
