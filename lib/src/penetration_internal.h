// Internals of the penetration-depth module (penetration.h): the closest
// facet of M = A - B by each method, in A's frame, and the facet graph the
// shallow method searches. The entry points (penetration.cpp) turn these into
// results in the world frame.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <unordered_set>
#include <vector>

#include "mddual/penetration.h"
#include "pair.h"

namespace mddual::detail {

/// A supporting plane n . x <= h of M (A's frame), named by the features of
/// A and B that span it. h is the plane's distance from the origin.
struct PdPlane {
  FaceOfM face;
  Eigen::Vector3d n_A = Eigen::Vector3d::Zero();
  double h = std::numeric_limits<double>::infinity();
  int va = -1;  ///< a vertex of A on the plane
  int vb = -1;  ///< a vertex of B on the plane (b with a - b on it)
  bool found() const { return face.kind != FaceOfM::Kind::kNone; }
};

/// Keeps the plane with the smallest offset (the first one on ties).
inline void keepCloser(const PdPlane& p, PdPlane* best) {
  if (p.h < best->h) *best = p;
}

// ---- Exact (penetration_exact.cpp) ----------------------------------------------

/// The facet of M closest to the origin, by enumerating the FV, VF and EE
/// facets (the EE ones by walking the Gaussian map of A across -B's). With
/// `prune`, candidates whose lower bound (penetration_exact.cpp) is no better
/// than the best facet found are skipped; without, every facet of M is
/// enumerated (the tests count them). The origin must be inside M (every
/// facet offset positive) for the result to be the penetration depth.
PdPlane exactClosestFacet(const PairGeometry& pair, PenetrationStats* stats, bool prune = true);

// ---- Rays (penetration_rays.cpp) ---------------------------------------------

/// One ray shot from the origin along u (A's frame): the facet where it
/// leaves M, at distance r = h / (n . u).
struct RayShot {
  Eigen::Vector3d u_A = Eigen::Vector3d::Zero();
  PdPlane exit;
  double r = std::numeric_limits<double>::infinity();
};

/// Approx-Separation (paper section 3): one shot per grid direction (warm
/// started from the previous, neighbouring, direction). best: the exit facet
/// with the smallest offset h. The origin must be strictly inside M.
struct ApproxOutcome {
  PdPlane best;
  std::vector<RayShot> shots;
};
ApproxOutcome approxClosestFacet(const PairGeometry& pair, double delta, PenetrationStats* stats);

/// Shallow-Penetration (paper section 3.2): the exact closest facet by a
/// breadth-first search from the best shots of approxClosestFacet(delta / 4).
PdPlane shallowClosestFacet(const PairGeometry& pair, double delta, PenetrationStats* stats);

/// Polyhedral metric (paper Corollary 3.5): one shot per vertex k of K;
/// lambda = r(k) / |k| is how many copies of K fit along k. Returns the
/// smallest lambda, its vertex and exit facet.
struct MetricOutcome {
  PdPlane exit;
  int k_vertex = -1;
  double lambda = std::numeric_limits<double>::infinity();
};
MetricOutcome metricClosestFacet(const PairGeometry& pair, const PolyhedralMetric& metric, PenetrationStats* stats);

// ---- Facet graph (penetration_facets.cpp) ---------------------------------------

/// Facets of M evaluated on demand, with the neighbourhoods of the MDD-DUAL
/// search (search.cpp): a generic facet (its supporting features are exactly
/// the named ones) borders one facet across each of its edges (MDD-DUAL paper
/// Lemma 7); a degenerate one (ties: parallel faces of A and B, facets of M
/// merged from several feature pairs) is given every facet that shares one
/// of its vertices. Either way the facets adjacent to a facet are among its
/// neighbours, which is what a breadth-first search over M needs.
class FacetGraph {
 public:
  struct Node {
    PdPlane plane;
    bool generic = false;
  };
  struct Ref {
    FaceOfM face;
    int hint_a = -1;  ///< a vertex of A near the support (FV / VF), or -1
    int hint_b = -1;
  };

  FacetGraph(const PairGeometry& pair, PenetrationStats* stats);

  /// Evaluates the facet named by ref. False when ref names no facet of M
  /// (an edge pair whose arcs do not cross, parallel edges, a bad index).
  bool evaluate(const Ref& ref, Node* out);
  /// A lower bound on the offset of the facet named by ref, from balls inside
  /// A and B (penetration_exact.cpp, branch and bound): a facet whose bound
  /// exceeds the search radius need not be evaluated.
  double lowerBound(const FaceOfM& face) const;
  /// Appends the neighbours of node to out (see the class comment).
  void neighbours(const Node& node, std::vector<Ref>* out);
  /// A key for visited sets.
  static std::uint64_t key(const FaceOfM& f);

 private:
  struct EdgeInA {
    int id = -1;
    Eigen::Vector3d dir, wedge_left, wedge_right, p0;
  };
  /// Edge e of A, or of B expressed in A's frame (computed once per edge).
  const EdgeInA& edgeInA(int e, bool of_b);
  bool evalEE(const EdgeInA& ea, const EdgeInA& eb, Node* out) const;

  const PairGeometry& pair_;
  PenetrationStats* stats_;
  std::vector<EdgeInA> edges_b_;  ///< B's edges in A's frame, id -1 until computed
  EdgeInA edge_a_;
  Eigen::Vector3d c_B_;       ///< B's centroid in A's frame
  Eigen::Vector3d c_A_in_B_;  ///< A's centroid in B's frame
  double rho_A_ = 0.0;        ///< radius of a ball around A's centroid inside A
  double rho_B_ = 0.0;
  std::vector<int> ties_a_, ties_b_, edges_a_, edges_b_list_;  ///< scratch of neighbours()
};

// ---- Grid (penetration_grid.cpp) ----------------------------------------------------

/// Checks delta (finite, within [kMinPdDelta, kMaxPdDelta]); `what` names the
/// caller in the error.
void checkDelta(double delta, const char* what);

}  // namespace mddual::detail
