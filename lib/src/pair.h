// The pair (A, B) seen from A's frame: B's pose relative to A, support
// queries on M = A - B, and the length scale that makes tolerances relative.
// All vectors here are in A's frame (suffix _A) unless named otherwise.
//
// "A's frame" is A's LOCAL frame (ConvexPolytope::p_PL(): the body frame
// translated to the centre of A's points), and B's vertices enter through
// B's local frame too: the core only ever reads localVertex(),
// localFaceOffset() and localCentroid(), so that M = A - B is formed from
// coordinates of the bodies' own size, wherever they are.
#pragma once

#include <Eigen/Geometry>
#include <string>

#include "mddual/defaults.h"
#include "mddual/polytope.h"
#include "mddual/query.h"

namespace mddual::detail {

/// A point of M with the vertices of A and B it is made of: p = a - b.
struct MPoint {
  Eigen::Vector3d p_A = Eigen::Vector3d::Zero();
  int va = -1;
  int vb = -1;
};

class PairGeometry {
 public:
  /// Validates the polytopes and poses (InvalidInputError naming the bad one).
  PairGeometry(const ConvexPolytope* a, const Eigen::Isometry3d& X_WA, const ConvexPolytope* b,
               const Eigen::Isometry3d& X_WB, const char* query);

  const ConvexPolytope& a() const { return a_; }
  const ConvexPolytope& b() const { return b_; }
  /// Pose of A's local frame in the world (X_WA X_PL).
  const Eigen::Isometry3d& X_WA() const { return X_WA_; }

  /// Vertex v of B, in A's frame.
  Eigen::Vector3d bVertex(int v) const { return R_AB_ * b_.localVertex(v) + p_AB_; }
  /// A vector of B's frame expressed in A's frame.
  Eigen::Vector3d bToA(const Eigen::Vector3d& v_B) const { return R_AB_ * v_B; }
  /// A vector of A's frame expressed in B's frame.
  Eigen::Vector3d aToB(const Eigen::Vector3d& v_A) const { return R_AB_.transpose() * v_A; }
  const Eigen::Vector3d& p_AB() const { return p_AB_; }

  /// Support vertex of A in direction d_A (hill climb from hint, or cold);
  /// `gap` as in ConvexPolytope::supportVertex.
  int supportA(const Eigen::Vector3d& d_A, int hint, SearchStats* stats, double* gap = nullptr) const;
  /// Vertex of B minimising d_A . b, i.e. the support of -B in direction d_A.
  int supportMinusB(const Eigen::Vector3d& d_A, int hint, SearchStats* stats, double* gap = nullptr) const;
  /// Support point of M in direction d_A.
  MPoint supportM(const Eigen::Vector3d& d_A, int hint_a, int hint_b, SearchStats* stats) const;

  /// Interior point of M (relative interior if M is flat): centroid(A) -
  /// centroid(B). Every point of M is within radiusM() of it.
  const Eigen::Vector3d& interiorPoint() const { return g_A_; }
  double radiusM() const { return a_.radius() + b_.radius(); }

  /// Length scale L of the query (defaults.h): tolerances are multiples of it.
  double scale() const { return scale_; }
  double touchTolerance() const { return defaults::kTouchRel * scale_; }
  double tieTolerance() const { return defaults::kSupportTieRel * scale_; }

  /// True when A and B are both flat and parallel: M is then flat too.
  bool flatM() const { return flat_m_; }
  /// Unit normal of M's plane when flatM().
  const Eigen::Vector3d& flatNormal() const { return flat_normal_A_; }

  /// Expresses a point / direction of A's frame in the world.
  Eigen::Vector3d pointToWorld(const Eigen::Vector3d& p_A) const { return X_WA_ * p_A; }
  Eigen::Vector3d vectorToWorld(const Eigen::Vector3d& v_A) const { return X_WA_.linear() * v_A; }
  Eigen::Vector3d vectorToA(const Eigen::Vector3d& v_W) const { return X_WA_.linear().transpose() * v_W; }

 private:
  /// The constructor's last step, once R_AB_, p_AB_ and X_WA_ are set: g_A_, scale_, the flat case.
  void finishSetUp();
  const ConvexPolytope& a_;
  const ConvexPolytope& b_;
  Eigen::Isometry3d X_WA_;
  Eigen::Matrix3d R_AB_;
  Eigen::Vector3d p_AB_;
  Eigen::Vector3d g_A_;
  double scale_ = 1.0;
  bool flat_m_ = false;
  Eigen::Vector3d flat_normal_A_ = Eigen::Vector3d::Zero();
};

/// Checks a toi() max_distance: >= 0 (0 asks about the start only) or
/// +infinity; NaN and negative values are InvalidInputError (the same rule as
/// the planning layer's directed clearance).
void checkMaxDistance(double max_distance, const char* query);

/// Checks a direction (finite, nonzero) and returns it normalised; `query`
/// names the caller in the error.
Eigen::Vector3d unitDirection(const Eigen::Vector3d& s, const char* query);

}  // namespace mddual::detail
