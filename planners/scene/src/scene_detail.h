// Helpers shared by the loaders' translation units (not installed).
#pragma once

#include <Eigen/Geometry>
#include <filesystem>
#include <string>
#include <vector>

#include "mddual/scene/loaders.h"
#include "mddual/scene/scene.h"

namespace mddual::scene::detail {

/// "'text'".
inline std::string quote(const std::string& text) {
  return "'" + text + "'";
}

/// The path as the user gave it, for messages.
inline std::string display(const std::filesystem::path& p) {
  return p.string();
}

/// Throws SceneError unless `file` is an existing regular file.
void requireFile(const std::filesystem::path& file);

/// Throws SceneError(what + ": " + reason) unless `tolerance` is finite and > 0.
void requirePositiveTolerance(double tolerance, const std::string& what);

/// The triangles and vertices of a mesh file, as OMPL.app reads them (see
/// loaders.h), in the file's frame.
struct MeshData {
  std::vector<Eigen::Vector3d> vertices;   ///< every vertex of every referenced mesh
  std::vector<Eigen::Vector3d> triangles;  ///< three corners per triangle
};

/// Reads a mesh file with assimp. Throws SceneError naming the file.
MeshData readMesh(const std::filesystem::path& file);

/// meshPieces with the pieces' origins prefixed by `origin_prefix`
/// ("<prefix>: triangle 3").
std::vector<Piece> meshPiecesWithOrigin(const std::filesystem::path& file, const Eigen::Vector3d& scale,
                                        const Eigen::Isometry3d& X_OM, const LoadOptions& options,
                                        const std::string& origin_prefix, MeshInfo* info);

/// The collision pieces of a URDF file in its root link's frame; `robot_name`
/// receives the URDF's robot name. Throws SceneError naming the file, link
/// and collision element.
std::vector<Piece> urdfPieces(const std::filesystem::path& file, const LoadOptions& options, std::string* robot_name);

/// True when `file`'s extension is .urdf (any case).
bool isUrdf(const std::filesystem::path& file);

}  // namespace mddual::scene::detail
