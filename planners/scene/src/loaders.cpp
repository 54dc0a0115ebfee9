// loadBody and loadWorld: URDF or mesh by the file's extension.
#include "mddual/scene/loaders.h"

#include "scene_detail.h"

namespace mddual::scene {
namespace {

std::vector<Piece> loadPieces(const std::filesystem::path& file, const LoadOptions& options, bool recentre,
                              std::string* name, std::vector<std::string>* warnings, MeshCounts* counts) {
  detail::requirePositiveTolerance(options.primitive_tolerance, detail::display(file));
  detail::requireMeshConvexTolerance(options.mesh_convex_tolerance, detail::display(file));
  if (detail::isUrdf(file)) return detail::urdfPieces(file, options, name, warnings, counts);
  LoadOptions mesh_options = options;
  mesh_options.recentre_mesh = recentre;
  *name = file.stem().string();
  MeshInfo info;
  std::vector<Piece> pieces =
      meshPieces(file, Eigen::Vector3d::Ones(), Eigen::Isometry3d::Identity(), mesh_options, &info);
  if (warnings != nullptr) warnings->insert(warnings->end(), info.warnings.begin(), info.warnings.end());
  if (counts != nullptr) counts->add(info, mesh_options.mesh_convex_hull);
  return pieces;
}

}  // namespace

void MeshCounts::add(const MeshInfo& info, bool hull) {
  ++meshes;
  if (info.convex || hull) {
    ++convex;
  } else {
    ++soups;
    if (info.closed) ++closed_soups;
  }
}

MeshCounts& MeshCounts::operator+=(const MeshCounts& o) {
  meshes += o.meshes;
  convex += o.convex;
  soups += o.soups;
  closed_soups += o.closed_soups;
  return *this;
}

RigidBody loadBody(const std::filesystem::path& file, const LoadOptions& options, std::vector<std::string>* warnings,
                   MeshCounts* counts) {
  std::string name;
  std::vector<Piece> pieces = loadPieces(file, options, options.recentre_mesh, &name, warnings, counts);
  if (pieces.empty()) throw SceneError(detail::display(file) + ": the robot has no collision geometry");
  if (name.empty()) name = file.stem().string();
  return RigidBody(std::move(pieces), name);
}

World loadWorld(const std::filesystem::path& file, const LoadOptions& options, std::vector<std::string>* warnings,
                MeshCounts* counts) {
  std::string name;
  std::vector<Piece> pieces = loadPieces(file, options, false, &name, warnings, counts);
  if (name.empty()) name = file.stem().string();
  return World(std::move(pieces), name);
}

}  // namespace mddual::scene
