// The exact separation distance between the robot at a pose and the world:
// the smallest mddual::distance() over every (robot piece, world piece) pair,
// found by a branch and bound of the scene's hierarchies (mddual::nearestPair
// on the world's trees and the robot's: MddScene::worldTreeAt, robotTree),
// whose spheres and boxes prune every node pair that cannot beat the best
// pair so far.
// MddStateValidityChecker::clearance() is this at the state's pose.
#pragma once

#include <Eigen/Geometry>
#include <limits>

#include "mddual/distance.h"
#include "mddual/planning/mdd_scene.h"

namespace mddual::planning {

/// Result of sceneDistance().
///
/// distance (world units), by the robot's relation to the world:
///   - free: the smallest Euclidean distance between a robot piece and a
///     world piece (> 0), exact to 1e-9 of the pair's size (distance.h);
///   - touching (some pair within the core's touch tolerance, none
///     overlapping): 0;
///   - colliding: minus the largest penetration depth over the overlapping
///     pairs (< 0; penetrationDepth(kExact) of each pair, not the depth of
///     the union);
///   - empty world: +infinity, pieces -1 and points NaN.
/// p_W_robot / p_W_world: the witness points of that pair (DistanceResult's
/// p_WA on the robot piece, p_WB on the world piece).
struct SceneDistance {
  double distance = std::numeric_limits<double>::infinity();
  DistanceStatus status = DistanceStatus::kSeparated;
  int robot_piece = -1;  ///< index into RigidBody::pieces()
  int world_piece = -1;  ///< index into World::pieces()
  Eigen::Vector3d p_W_robot = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector3d p_W_world = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  int pair_queries = 0;  ///< mddual::distance() calls
};

/// The robot of `scene` at X_WR against its world (see SceneDistance).
/// Thread-safe (no shared state is written).
SceneDistance sceneDistance(const MddScene& scene, const Eigen::Isometry3d& X_WR);

}  // namespace mddual::planning
