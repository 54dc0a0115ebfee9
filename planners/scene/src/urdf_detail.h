// urdfdom helpers shared by the rigid-body URDF loader (urdf_loader.cpp) and
// the robot model (robot_model.cpp). Not installed.
#pragma once

#include <urdf_model/model.h>
#include <urdf_world/types.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <string>
#include <vector>

#include "mddual/scene/loaders.h"
#include "mddual/scene/scene.h"

namespace mddual::scene::detail {

/// Parses `xml`, the text of `file` (read once, by requireShallowXml). Any
/// error urdfdom logs is a SceneError naming the file and what it said.
urdf::ModelInterfaceSharedPtr parseUrdf(const std::filesystem::path& file, std::string xml);

/// A URDF pose as an isometry (a zero quaternion reads as the identity, as
/// urdfdom leaves it when the rpy is absent).
Eigen::Isometry3d toIsometry(const urdf::Pose& pose);

/// Where the meshes of a URDF are looked up (resolveMeshPath's arguments).
struct MeshSearch {
  std::filesystem::path urdf;
  std::vector<std::filesystem::path> package_path;
  bool use_environment = true;
};

/// Appends the pieces of one collision element to `out`, in the frame in
/// which the element's link is at X_RL. `where` names the element in
/// messages and piece origins. Throws SceneError naming it.
void addCollision(const urdf::Collision& collision, const Eigen::Isometry3d& X_RL, const MeshSearch& search,
                  const LoadOptions& options, const std::string& where, std::vector<Piece>* out,
                  std::vector<std::string>* warnings, MeshCounts* counts);

}  // namespace mddual::scene::detail
