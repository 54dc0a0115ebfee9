// Directed clearance for planning code: how far the robot can translate along
// a world direction before it touches the world, and where along an edge the
// first contact lies, each with the pieces, point and normal of the contact.
// Geometry only: the space's bounds play no part here (MddMotionValidator adds
// them). All functions are thread-safe (per-thread warm starts in MddScene).
#pragma once

#include <ompl/base/State.h>
#include <Eigen/Geometry>
#include <limits>

#include "mddual/planning/mdd_scene.h"
#include "mddual/planning/state_space.h"

namespace mddual::planning {

/// Result of directedClearance().
///
/// Let u = d_W / |d_W| and, for each pair (robot piece i at X_WR, world piece
/// j), mdd_ij its signed minimum directional distance along u (mddual::mdd).
///   - The robot touches nothing at X_WR: distance = the smallest t > 0 such
///     that the robot translated by t u touches a world piece (the first
///     contact over all pairs, mddual::toi), or +infinity when there is none
///     within max_distance. contact: that pair, the touching point of the
///     world piece and the normal from the world piece toward the robot piece.
///   - The robot touches or overlaps the world at X_WR (start_collides):
///     distance = min over the touching/overlapping pairs of min(mdd_ij, 0),
///     i.e. the signed MDD of the deepest pair: minus the shorter of the two
///     translations along +u or -u that separate that pair (0 for a pair that
///     only touches). Separating that pair does not imply separating the
///     others. contact: that pair and the mdd contact (the point and normal
///     where the pair separates; NaN when the line only grazes).
struct DirectedClearance {
  double distance = std::numeric_limits<double>::infinity();
  bool start_collides = false;
  PieceContact contact;
  int pair_queries = 0;
};

/// Directed clearance of the robot at X_WR along d_W. Throws InvalidInputError
/// for a zero or non-finite direction or a negative or NaN max_distance.
DirectedClearance directedClearance(const MddScene& scene, const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& d_W,
                                    double max_distance = std::numeric_limits<double>::infinity());
/// Same, at the pose of an OMPL state.
DirectedClearance directedClearance(const MddScene& scene, const PlanningSpace& space, const ompl::base::State* state,
                                    const Eigen::Vector3d& d_W,
                                    double max_distance = std::numeric_limits<double>::infinity());

/// The first contact on an edge under OMPL's interpolation (MddScene::checkEdge
/// with EdgeQuery::kFirstContact): fraction exact for translation edges, a lower bound
/// for rotating ones (contact: that of the enlarged robot on the failing
/// sub-edge); 0 with start_collides when the start collides (contact: the
/// colliding pair, point and normal NaN); +infinity when the edge is free.
EdgeContact edgeContact(const MddScene& scene, const EdgeMotion& motion);
EdgeContact edgeContact(const MddScene& scene, const PlanningSpace& space, const ompl::base::State* s1,
                        const ompl::base::State* s2);

}  // namespace mddual::planning
