#include "mddual/planning/scene_distance.h"

#include <vector>

#include "constants.h"
#include "mddual/bvh.h"
#include "mddual/error.h"

namespace mddual::planning {

SceneDistance sceneDistance(const MddScene& scene, const Eigen::Isometry3d& X_WR) {
  // A NaN pose would give NaN bounds (the core checks rigidity on the first
  // pair).
  requireFinitePose(X_WR, "the robot pose X_WR", "sceneDistance");
  SceneDistance out;
  const std::vector<scene::Piece>& robot = scene.robot().pieces();
  const std::vector<scene::Piece>& world = scene.world().pieces();
  if (world.empty()) return out;
  // The world's trees against the robot's, nearest node pair first
  // (nearestPair: the spheres' gap bounds the signed distance of every pair
  // below, penetration included); a pair's value is its exact signed
  // distance. The second tree only looks for pairs nearer than the first's
  // best.
  for (int t = 0; t < 2; ++t) {
    const Bvh& tree = scene.worldTreeAt(t);
    if (tree.empty()) continue;
    const auto leaf = [&](int k, int i, double) {
      const int j = scene.worldIndex(t, k);
      if (j < 0) return detail::kInf;  // a removed or moved piece's old leaf
      DistanceInput in;
      in.a = &robot[static_cast<std::size_t>(i)].polytope;
      in.X_WA = X_WR;
      in.b = &world[static_cast<std::size_t>(j)].polytope;
      const DistanceResult d = distance(in);
      ++out.pair_queries;
      if (d.distance < out.distance) {
        out.distance = d.distance;
        out.status = d.status;
        out.robot_piece = i;
        out.world_piece = j;
        out.p_W_robot = d.p_WA;
        out.p_W_world = d.p_WB;
      }
      return d.distance;
    };
    nearestPair(tree, scene.robotTree(), X_WR, leaf, out.distance);
  }
  return out;
}

}  // namespace mddual::planning
