#include "mddual/planning/scene_distance.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>
#include "constants.h"
#include "mddual/error.h"

namespace mddual::planning {
namespace {

using detail::kInf;
/// Bounding spheres are computed in floating point: their radii are inflated
/// by this relative amount before a gap between them is trusted as a lower
/// bound on a pair's distance (dimensionless; far above round-off).
constexpr double kSphereSlackRel = 1e-9;
/// The first box query of a robot piece (before any distance is known) reaches
/// this many piece radii beyond the piece's box, and grows by kGrowth until it
/// meets a world piece's box. At most kMaxGrowthSteps growths (from the
/// smallest piece to the largest coordinate the core accepts, 1e50, takes
/// fewer than 250 quadruplings).
constexpr double kFirstReachRadii = 1.0;
constexpr double kGrowth = 4.0;
constexpr int kMaxGrowthSteps = 400;

Eigen::AlignedBox3d expanded(const Eigen::AlignedBox3d& box, double r) {
  const Eigen::Vector3d d = Eigen::Vector3d::Constant(r);
  return Eigen::AlignedBox3d(box.min() - d, box.max() + d);
}

}  // namespace

SceneDistance sceneDistance(const MddScene& scene, const Eigen::Isometry3d& X_WR) {
  // A NaN pose misses every box query: it would be "infinitely far" from
  // everything (the core checks rigidity on the first pair).
  requireFinitePose(X_WR, "the robot pose X_WR", "sceneDistance");
  SceneDistance out;
  const std::vector<scene::Piece>& robot = scene.robot().pieces();
  const std::vector<scene::Piece>& world = scene.world().pieces();
  if (world.empty()) return out;
  std::vector<int> candidates;
  std::vector<std::pair<double, int>> order;  // (sphere gap: a lower bound on the distance, world piece)
  std::vector<int> done;                      // world pieces evaluated for the current robot piece
  for (int i = 0; i < static_cast<int>(robot.size()); ++i) {
    const scene::Piece& piece = robot[static_cast<std::size_t>(i)];
    const Eigen::AlignedBox3d box_W = scene::transformedBox(piece.box, X_WR);
    const Eigen::Vector3d c_W = X_WR * piece.centre;
    done.clear();
    // Pieces whose boxes miss box_W grown by r are farther than r (their
    // boxes are): a query of reach max(best, 0) holds every piece that can
    // beat the best pair. Before any pair is known, grow the reach until it
    // finds a box, then query again out to the best distance found.
    double reach = std::isfinite(out.distance) ? std::max(out.distance, 0.0) : kFirstReachRadii * piece.radius;
    for (int pass = 0; pass < 2; ++pass) {
      candidates.clear();
      scene.world().candidates(expanded(box_W, reach), &candidates);
      for (int step = 0; candidates.empty() && !std::isfinite(out.distance) && step < kMaxGrowthSteps; ++step) {
        reach = reach > 0.0 ? reach * kGrowth : 1.0;
        scene.world().candidates(expanded(box_W, reach), &candidates);
      }
      order.clear();
      for (int j : candidates) {
        if (std::binary_search(done.begin(), done.end(), j)) continue;
        const scene::Piece& obstacle = world[static_cast<std::size_t>(j)];
        const double gap = (c_W - obstacle.centre).norm() - (piece.radius + obstacle.radius) * (1.0 + kSphereSlackRel);
        order.emplace_back(gap, j);
      }
      std::sort(order.begin(), order.end());
      for (const auto& [gap, j] : order) {
        if (gap >= out.distance) break;  // sorted: no later piece can be nearer
        done.push_back(j);
        DistanceInput in;
        in.a = &piece.polytope;
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
      }
      // The reach covered every piece nearer than it; a second pass is needed
      // only when the best distance lies beyond the reach.
      if (!(out.distance > reach)) break;
      reach = out.distance;
      std::sort(done.begin(), done.end());
    }
  }
  return out;
}

}  // namespace mddual::planning
