// loadProblemScene: the robot, world, poses and bounds a cfg describes.
#include "mddual/scene/problem_config.h"
#include "problem_config_detail.h"
#include "scene_detail.h"

namespace mddual::scene {

ProblemScene loadProblemScene(const ProblemConfig& config, const LoadOptions& options) {
  const std::string cfg_name = config.file.filename().string();
  const std::filesystem::path robot_file = resolvePath(config, config.robot);
  const std::filesystem::path world_file = resolvePath(config, config.world);
  const bool planar = isPlanar(config.space);

  ProblemScene scene;
  scene.space = config.space;
  try {
    if (detail::isUrdf(robot_file)) {
      LoadOptions o = options;
      o.recentre_mesh = false;
      scene.robot = loadBody(robot_file, o, &scene.warnings);
    } else {
      // OMPL.app: the robot mesh is shifted by its mean vertex, whose z is
      // zeroed for planar problems (RigidBodyGeometry's robotShift).
      Eigen::Vector3d shift = meshMeanVertex(robot_file);
      if (planar) shift.z() = 0.0;
      LoadOptions o = options;
      o.recentre_mesh = false;
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
      X.translation() = -shift;
      MeshInfo info;
      scene.robot = RigidBody(meshPieces(robot_file, Eigen::Vector3d::Ones(), X, o, &info), robot_file.stem().string());
      scene.robot_shift = shift;
      scene.warnings = info.warnings;
    }
    scene.world = loadWorld(world_file, options, &scene.warnings);
  } catch (const SceneError& e) {
    throw SceneError(cfg_name + ": " + e.what());
  }
  scene.start = toIsometry(config.start, config.space);
  scene.goal = toIsometry(config.goal, config.space);
  if (isTranslationOnly(config.space)) {
    if (!detail::sameRotation(config.start, config.goal, config.space)) {
      throw SceneError(cfg_name + ": translation_only, but the goal's rotation differs from the start's");
    }
    scene.goal.linear() = scene.start.linear();
  }

  if (config.volume) {
    scene.bounds = *config.volume;
  } else {
    scene.bounds = scene.world.box();  // empty for an empty world
    scene.bounds.extend(scene.start.translation());
    scene.bounds.extend(scene.goal.translation());
  }
  if (planar) {
    scene.bounds.min().z() = 0.0;
    scene.bounds.max().z() = 0.0;
  }
  if (scene.bounds.isEmpty()) throw SceneError(cfg_name + ": the position bounds are empty");
  return scene;
}

}  // namespace mddual::scene
