// Steps 2-3 of MDD-DUAL: from a centre c inside M, find the face of M where
// the ray {c + s w} leaves M, by hill climbing on the faces of M without
// building M (paper sections III-IV).
//
// Objective. For a face of M on the plane n . x = h (n outward), the ray meets
// the plane at distance (h - n . c) / (n . w) from c. Its inverse
//     phi(f) = (n . w) / (h - n . c)
// is, under the polar duality centred at c (faces of M -> points n / (h - n.c)
// of the dual polytope M*), a *linear* function of the dual point: maximising
// phi over the vertices of M* is a linear program on a convex polytope, so a
// hill climb that stops at a face with no better neighbour has found the exit
// face (paper Lemma 1). The paper's signed distance d(f) = -k / (|c|(k - N.c))
// is the same function shifted and scaled when c lies on the line through the
// origin: d(f) = phi(f) - 1/|c| with w = -c / |c|.
#pragma once

#include <Eigen/Core>
#include <limits>

#include "mddual/query.h"
#include "pair.h"

namespace mddual::detail {

struct RayQuery {
  Eigen::Vector3d c_A = Eigen::Vector3d::Zero();   ///< centre, inside M
  Eigen::Vector3d w_A = Eigen::Vector3d::UnitX();  ///< unit ray direction
  FaceOfM warm;  ///< start face; kNone: cold start with the SEARCH-FV and SEARCH-VF phases
  /// Early exits: stop at the first face with phi > phi_stop (the exit is
  /// closer than 1/phi_stop), or with offset h < h_stop (a separating plane).
  double phi_stop = std::numeric_limits<double>::infinity();
  double h_stop = -std::numeric_limits<double>::infinity();
};

struct RayExit {
  FaceOfM face;
  Eigen::Vector3d n_A = Eigen::Vector3d::Zero();           ///< unit outward normal of the face
  double h = 0.0;                                          ///< offset: n . x <= h on M
  double phi = 0.0;                                        ///< objective (1 / distance from c to the exit)
  int va = -1;                                             ///< a vertex of A supporting n
  int vb = -1;                                             ///< a vertex of B supporting -n
  bool stopped = false;                                    ///< an early-exit threshold fired on this face
  double min_h = std::numeric_limits<double>::infinity();  ///< smallest offset h among the faces evaluated
};

RayExit searchRay(const PairGeometry& pair, const RayQuery& query, SearchStats* stats);

/// A point of A touched by B translated so that M's point x_A (on the face
/// with normal n_A supported by va, vb) is reached: x_A = a - b, returns a.
Eigen::Vector3d contactPointOnA(const PairGeometry& pair, const RayExit& exit, const Eigen::Vector3d& x_A);

}  // namespace mddual::detail
