// Step 1 of MDD-DUAL: the centre of duality, a point c = tau u of the query
// line inside M (paper section IV-A), or the proof that the line misses M, or
// the supporting plane of M that the line lies in (a grazing line).
#pragma once

#include <Eigen/Core>

#include "pair.h"

namespace mddual::detail {

struct Centre {
  enum class Kind { kNoContact, kGrazing, kInterior };
  Kind kind = Kind::kNoContact;
  /// kInterior: the centre c_A = tau u_A, inside M.
  Eigen::Vector3d c_A = Eigen::Vector3d::Zero();
  double tau = 0.0;
  /// kInterior: points of M such that the triangle (interior point g, m1, m2)
  /// meets the line at c (m1 = m2 when c lies on a segment from g).
  Eigen::Vector3d m1_A = Eigen::Vector3d::Zero();
  Eigen::Vector3d m2_A = Eigen::Vector3d::Zero();
  /// kNoContact / kGrazing: unit w orthogonal to u with h_M(w) < -tol (the
  /// line is strictly outside the half-space of M) or |h_M(w)| <= tol (the
  /// line lies in the supporting plane); va, vb are A's and B's support
  /// vertices for w (of A in w, of B in -w).
  Eigen::Vector3d w_A = Eigen::Vector3d::Zero();
  int va = -1;
  int vb = -1;
};

/// Finds the centre for the line {t u_A} (u_A unit, A's frame). Warm-started
/// from and updating warm->centre_a/b when warm is not null.
Centre findCentre(const PairGeometry& pair, const Eigen::Vector3d& u_A, WarmStart* warm, SearchStats* stats);

}  // namespace mddual::detail
