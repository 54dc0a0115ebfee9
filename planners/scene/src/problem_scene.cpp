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
  LoadOptions load = options;
  if (config.mesh_convex_tolerance) load.mesh_convex_tolerance = *config.mesh_convex_tolerance;
  try {
    if (detail::isUrdf(robot_file)) {
      LoadOptions o = load;
      o.recentre_mesh = false;
      scene.robot = loadBody(robot_file, o, &scene.warnings, &scene.robot_meshes);
    } else {
      // OMPL.app: the robot mesh is shifted by its mean vertex, whose z is
      // zeroed for planar problems (RigidBodyGeometry's robotShift).
      Eigen::Vector3d shift = meshMeanVertex(robot_file);
      if (planar) shift.z() = 0.0;
      LoadOptions o = load;
      o.recentre_mesh = false;
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
      X.translation() = -shift;
      MeshInfo info;
      scene.robot = RigidBody(meshPieces(robot_file, Eigen::Vector3d::Ones(), X, o, &info), robot_file.stem().string());
      scene.robot_shift = shift;
      scene.warnings = info.warnings;
      scene.robot_meshes.add(info, o.mesh_convex_hull);
    }
    scene.world = loadWorld(world_file, load, &scene.warnings, &scene.world_meshes);
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

namespace {

/// "3 pieces (1 convex, 2 triangles), 1 mesh (1 triangle soup, 1 closed: hollow)".
std::string describe(const std::vector<Piece>& pieces, const MeshCounts& meshes) {
  const auto count = [](int n, const std::string& one, const std::string& many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
  };
  int convex = 0;
  for (const Piece& p : pieces) convex += p.kind == PieceKind::kConvex ? 1 : 0;
  const int triangles = static_cast<int>(pieces.size()) - convex;
  std::string kinds;
  if (convex > 0) kinds = std::to_string(convex) + " convex";
  if (triangles > 0) kinds += (kinds.empty() ? "" : ", ") + count(triangles, "triangle", "triangles");
  std::string s = count(static_cast<int>(pieces.size()), "piece", "pieces");
  if (!kinds.empty()) s += " (" + kinds + ")";
  if (meshes.meshes == 0) return s;
  std::string parts;
  if (meshes.convex > 0) parts = std::to_string(meshes.convex) + " convex";
  if (meshes.soups > 0) parts += (parts.empty() ? "" : ", ") + count(meshes.soups, "triangle soup", "triangle soups");
  if (meshes.closed_soups > 0) parts += ", " + std::to_string(meshes.closed_soups) + " closed: hollow";
  return s + ", " + count(meshes.meshes, "mesh", "meshes") + " (" + parts + ")";
}

}  // namespace

std::string sceneSummary(const ProblemScene& scene) {
  return "robot " + detail::quote(scene.robot.name()) + ": " + describe(scene.robot.pieces(), scene.robot_meshes) +
         "; world " + detail::quote(scene.world.name()) + ": " + describe(scene.world.pieces(), scene.world_meshes);
}

}  // namespace mddual::scene
