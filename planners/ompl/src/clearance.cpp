#include "mddual/planning/clearance.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "mddual/error.h"

namespace mddual::planning {

DirectedClearance directedClearance(const MddScene& scene, const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& d_W,
                                    double max_distance) {
  // Divided by its largest coordinate first, as MddScene::sweep does.
  const double largest = d_W.cwiseAbs().maxCoeff();
  if (!(largest > 0.0) || !d_W.allFinite())
    throw InvalidInputError("directedClearance: the direction is zero or not finite");
  if (!(max_distance >= 0.0)) throw InvalidInputError("directedClearance: max_distance is negative or NaN");
  const Eigen::Vector3d u = (d_W / largest).normalized();

  DirectedClearance out;
  const SweepResult sweep = scene.sweepSet(0, X_WR, u, max_distance, /*first_contact=*/true);
  out.pair_queries = sweep.pair_queries;
  if (!sweep.start_collides) {
    out.distance = sweep.distance;
    out.contact = sweep.contact;
    return out;
  }

  // The start collides: the signed MDD of every touching or overlapping pair.
  out.start_collides = true;
  out.distance = 0.0;
  out.contact = sweep.contact;
  const std::vector<scene::Piece>& pieces = scene.robot().pieces();
  const std::vector<scene::Piece>& world = scene.world().pieces();
  std::vector<int> candidates;
  bool found = false;
  for (int i = 0; i < static_cast<int>(pieces.size()); ++i) {
    const scene::Piece& piece = pieces[static_cast<std::size_t>(i)];
    candidates.clear();
    scene.world().candidates(scene::transformedBox(piece.box, X_WR), &candidates);
    for (int j : candidates) {
      const scene::Piece& obstacle = world[static_cast<std::size_t>(j)];
      IntersectInput test;
      test.a = &obstacle.polytope;
      test.b = &piece.polytope;
      test.X_WB = X_WR;
      ++out.pair_queries;
      if (!intersect(test, scene.warmStart(0, i, j)).intersecting) continue;
      DirectionalInput in;
      in.a = &obstacle.polytope;
      in.b = &piece.polytope;
      in.X_WB = X_WR;
      in.s_W = u;
      ++out.pair_queries;
      const MddResult r = mdd(in, scene.warmStart(0, i, j));
      // Tolerance mismatches (intersect says touching, mdd separated or
      // grazing) count as touching: 0.
      const double d = std::isfinite(r.distance) ? std::min(r.distance, 0.0) : 0.0;
      if (!found || d < out.distance) {
        found = true;
        out.distance = d;
        out.contact = PieceContact();
        out.contact.robot_piece = i;
        out.contact.world_piece = j;
        if (r.status != ContactStatus::kNoContact) {
          out.contact.p_WC = r.contact.point_W;
          out.contact.n_W = r.contact.normal_W;
        }
      }
    }
  }
  return out;
}

DirectedClearance directedClearance(const MddScene& scene, const PlanningSpace& space, const ompl::base::State* state,
                                    const Eigen::Vector3d& d_W, double max_distance) {
  return directedClearance(scene, space.pose(state), d_W, max_distance);
}

EdgeContact edgeContact(const MddScene& scene, const EdgeMotion& motion) {
  return scene.checkEdge(motion, true);
}

EdgeContact edgeContact(const MddScene& scene, const PlanningSpace& space, const ompl::base::State* s1,
                        const ompl::base::State* s2) {
  return scene.checkEdge(space.motion(s1, s2), true);
}

}  // namespace mddual::planning
