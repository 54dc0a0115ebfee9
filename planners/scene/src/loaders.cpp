// loadBody and loadWorld: URDF or mesh by the file's extension.
#include "mddual/scene/loaders.h"

#include "scene_detail.h"

namespace mddual::scene {
namespace {

std::vector<Piece> loadPieces(const std::filesystem::path& file, const LoadOptions& options, bool recentre,
                              std::string* name, std::vector<std::string>* warnings) {
  detail::requirePositiveTolerance(options.primitive_tolerance, detail::display(file));
  if (detail::isUrdf(file)) return detail::urdfPieces(file, options, name, warnings);
  LoadOptions mesh_options = options;
  mesh_options.recentre_mesh = recentre;
  *name = file.stem().string();
  MeshInfo info;
  std::vector<Piece> pieces =
      meshPieces(file, Eigen::Vector3d::Ones(), Eigen::Isometry3d::Identity(), mesh_options, &info);
  if (warnings != nullptr) warnings->insert(warnings->end(), info.warnings.begin(), info.warnings.end());
  return pieces;
}

}  // namespace

RigidBody loadBody(const std::filesystem::path& file, const LoadOptions& options, std::vector<std::string>* warnings) {
  std::string name;
  std::vector<Piece> pieces = loadPieces(file, options, options.recentre_mesh, &name, warnings);
  if (pieces.empty()) throw SceneError(detail::display(file) + ": the robot has no collision geometry");
  if (name.empty()) name = file.stem().string();
  return RigidBody(std::move(pieces), name);
}

World loadWorld(const std::filesystem::path& file, const LoadOptions& options, std::vector<std::string>* warnings) {
  std::string name;
  std::vector<Piece> pieces = loadPieces(file, options, false, &name, warnings);
  if (name.empty()) name = file.stem().string();
  return World(std::move(pieces), name);
}

}  // namespace mddual::scene
