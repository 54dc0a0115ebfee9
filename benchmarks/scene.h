// The MDD-DUAL paper's benchmark protocol (docs/algorithms.md section 5, paper
// section VII): pairs of the polytopes P1..P6, random orientations, placements
// of B at prescribed signed distances from A, random query directions, and the
// exact reference answer of every query.
//
// The reference is the brute force of docs/algorithms.md section 1 (hull of all
// vertex differences, line clipped by every face plane): M0 = A - B is built
// once per orientation with mddual::MinkowskiDifference::build, and a query
// with B translated by v clips the line with the planes of M0 - v. That is the
// same computation as mddual::bruteForceMdd / bruteForceToi (same tolerances),
// without rebuilding the hull for each of the 33,600 queries of a pair;
// buildScene cross-checks it against those functions on a sample of queries.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "mddual/polytope.h"

namespace mddual::bench {

/// One pair of the protocol: A (fixed) and B (moving), by paper name.
struct PairSpec {
  std::string a;  ///< "P1".."P6"
  std::string b;
  std::string name() const { return a + "-" + b; }
};

/// The paper's ten pairs, in its order.
std::vector<PairSpec> paperPairs();

/// Counts and parameters of the protocol. Defaults are the paper's.
struct Protocol {
  int orientations = 40;  ///< random orientation pairs (R_A, R_B) per pair
  int placements = 21;    ///< signed distances evenly spaced in [min_delta, max_delta]
  int directions = 40;    ///< random directions per placement (= warm sequence length)
  double min_delta = -1.5;
  double max_delta = 1.5;
  std::uint64_t seed = 1;
  /// Warm-start sequences: after each query B translates by warm_step (world
  /// units) along a fresh random unit vector and the direction turns by
  /// warm_turn_deg about a random axis orthogonal to it.
  double warm_step = 0.01;
  double warm_turn_deg = 1.0;
  /// Queries checked against mddual::bruteForceMdd/Toi/Intersect (each one
  /// rebuilds the hull, so this is kept small).
  bool verify = true;
};

/// A query: poses of A and B in the world and B's direction of motion (unit).
struct Query {
  Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  Eigen::Vector3d s_W = Eigen::Vector3d::UnitX();
  int orientation = 0;  ///< index into PairScene::orientations
  int placement = 0;    ///< index into the deltas
};

/// Exact answer of a query (brute force, see the file comment).
struct Reference {
  bool hit = false;  ///< the line {t u} meets M
  double t_lo = std::numeric_limits<double>::quiet_NaN();
  double t_hi = std::numeric_limits<double>::quiet_NaN();
  double mdd = std::numeric_limits<double>::quiet_NaN();  ///< signed MDD (NaN: no contact)
  double toi = std::numeric_limits<double>::infinity();   ///< first t >= 0 on the line in M
  bool in_contact = false;                                ///< toi == 0 (touching or overlapping)
  bool overlapping = false;                               ///< origin strictly inside M along the line
  /// toi 0 versus "never" depends on a tolerance here: B touches A (|t_hi| or
  /// |t_lo| within 1e-6 of the scene scale) and moves away or grazes.
  bool ambiguous = false;
};

/// M0 = A - B for one orientation (B at translation 0).
struct OrientationInfo {
  Eigen::Matrix3d R_A;
  Eigen::Matrix3d R_B;
  int faces = 0;              ///< faces of M (merged coplanar facets)
  int ee_faces = 0;           ///< of those, EE faces (neither one vertex of A nor one of B)
  int fv_faces = 0;           ///< facet of A + vertex of B
  int vf_faces = 0;           ///< vertex of A + facet of B
  double centre_depth = 0.0;  ///< depth of M0's vertex centroid (must exceed -min_delta)
  double tol = 0.0;           ///< touch tolerance of the pair (as in the library)
};

/// Outcome of the self-checks of a scene.
struct SceneChecks {
  int placements_checked = 0;  ///< bruteForceIntersect sign + bruteForceMdd distance
  int placements_failed = 0;
  int references_checked = 0;  ///< own clipping versus bruteForceMdd / bruteForceToi
  int references_failed = 0;
  double centre_depth_min = std::numeric_limits<double>::infinity();
  std::vector<std::string> messages;  ///< one line per failure
};

/// Everything one pair's measurements need, built once.
struct PairScene {
  PairSpec spec;
  ConvexPolytope a;
  ConvexPolytope b;
  Protocol protocol;
  std::vector<double> deltas;  ///< signed distance of each placement
  std::vector<OrientationInfo> orientations;
  /// Cold queries, orientation-major, then placement, then direction.
  std::vector<Query> cold;
  std::vector<Reference> cold_ref;
  /// Warm sequences: one per (orientation, placement), `directions` queries
  /// each, stored contiguously; primers[k] is the untimed query that fills the
  /// WarmStart before sequence k.
  std::vector<Query> warm;
  std::vector<Reference> warm_ref;
  std::vector<Query> primers;
  SceneChecks checks;
};

/// Builds the scene of one pair: polytopes, placements, queries, references
/// and (if protocol.verify) the self-checks.
PairScene buildScene(const PairSpec& spec, const Protocol& protocol, int pair_index);

/// The query as the library's reproducer JSON (A and B world vertices and the
/// direction, 17 significant digits), ready to paste into a test.
std::string describeQuery(const PairScene& scene, const Query& q);

}  // namespace mddual::bench
