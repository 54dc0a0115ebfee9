// Penetration depth, width and penetration depth under a polyhedral metric
// (Agarwal, Guibas, Har-Peled, Rabinovitch, Sharir, "Penetration Depth of Two
// Convex Polytopes in 3D"; ../../../docs/algorithms.md#4-penetration-depth).
//
// Conventions (as in query.h): A is fixed, B moves, M = A - B. B translated by
// t overlaps A iff t is in the interior of M, so
//
//   PD(A, B) = min { |t| : int(A) and int(B + t) are disjoint }
//            = distance from the origin to the boundary of M   (origin inside M)
//            = min over the facets n . x <= h of M of h        (unit outward n)
//
// and 0 when the interiors are already disjoint (touching or separated). The
// minimum translation is t = PD * n for the facet of M closest to the origin:
// it points from A toward B, the direction in which B must move.
//
// Flat inputs: a flat polygon (one triangle) has no interior. A flat polygon
// against a solid still gives a full-dimensional M and a positive depth when
// the polygon pierces the solid (B must move until the polygon is out of the
// solid's interior). Two parallel flat polygons give a flat M: every
// translation leaves the (empty) interiors disjoint, so PD is 0 (status
// kTouching when they meet, kSeparated otherwise).
//
// Methods (PenetrationMethod):
//   kExact       every facet of M that can be closest: the facet-vertex and
//                vertex-facet facets (O(m + n)) and the edge-edge facets from
//                the crossings of the two Gaussian maps, found by walking each
//                arc of A across the vertex regions of -B (output-sensitive,
//                never all m x n edge pairs); candidates whose O(1) lower
//                bound cannot beat the best facet found are skipped (branch
//                and bound, usually most of them);
//   kShallow     the paper's Shallow-Penetration: approximate with delta / 4,
//                then breadth-first search over the facets of M whose planes
//                lie within (1 + delta / 2) times the estimate, starting from
//                the facets hit by the best grid directions. Same answer as
//                kExact (cheaper when few facets of M are that close);
//   kApprox      the paper's Approx-Separation: one ray shot from the origin
//                per direction of a grid covering the sphere to within angle
//                sqrt(delta); depth <= (1 + delta) PD guaranteed;
//   kBruteForce  M built explicitly (qhull on all m x n vertex differences),
//                min over its facets; the reference.
//
// Units: depths are lengths in world units (the polyhedral metric's depth is
// a multiple of K's size, see PolyhedralResult). Frames: _W quantities are in
// the world frame; X_WA and X_WB are the poses of A and B.
//
// Errors: InvalidInputError (null polytope, bad pose, delta out of range, a
// metric that is not a centrally symmetric solid), NumericalError (an
// internal limit was hit; the message carries the pair as a JSON line).
// Thread safety: the functions are pure given their inputs.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <vector>

#include "mddual/polytope.h"
#include "mddual/query.h"

namespace mddual {

enum class PenetrationMethod : std::uint8_t { kExact, kShallow, kApprox, kBruteForce };

/// Relation of the interiors of A and B.
enum class PenetrationStatus : std::uint8_t {
  kSeparated,    ///< disjoint, with a gap larger than the touch tolerance
  kTouching,     ///< the boundaries meet within tolerance, the interiors do not overlap (or one is flat)
  kPenetrating,  ///< the interiors overlap by more than the touch tolerance
};

const char* toString(PenetrationMethod method);
const char* toString(PenetrationStatus status);

/// Work done by one penetration query. Counters that a method does not use
/// stay 0.
struct PenetrationStats {
  // kExact (the brute force leaves every counter 0). The method bounds every
  // candidate from below and evaluates only those that can beat the best
  // facet found (penetration_exact.cpp), so these count evaluated planes:
  int fv_facets = 0;        ///< facet-of-A + vertex-of-B planes evaluated
  int vf_facets = 0;        ///< vertex-of-A + facet-of-B planes evaluated
  int ee_facets = 0;        ///< edge-edge planes found (crossings of the two Gaussian maps on walked arcs)
  long long arc_pairs = 0;  ///< (arc of A, arc of -B) pairs tested by the map walk
  int walk_steps = 0;       ///< vertex regions of -B entered by the map walk
  int walk_fallbacks = 0;   ///< arcs re-done by testing every edge of B (round-off; 0 on generic input)
  /// 1 when the closest plane failed its final check (its offset is not the
  /// support of M along its normal: an edge-edge crossing computed from
  /// nearly parallel edges, seen on identical bodies) and the answer was
  /// taken from the explicit M instead; feature_a / feature_b are then kNone.
  int brute_fallbacks = 0;
  int pruned = 0;            ///< candidates (facets of A, facets of B, arcs of A) skipped by their bound
  int support_vertices = 0;  ///< vertices whose support value was evaluated
  // kApprox, kShallow, polyhedral metric:
  int grid_directions = 0;  ///< directions of the grid (or vertices of K)
  int rays = 0;             ///< ray shots (MDD-DUAL searches from the origin)
  SearchStats search;       ///< totals of the ray searches
  // kShallow:
  int shallow_directions = 0;  ///< grid directions within (1 + delta / 4) of the estimate
  int shallow_facets = 0;      ///< facets of M evaluated by the breadth-first search
  int totalFacets() const { return fv_facets + vf_facets + ee_facets + shallow_facets; }
};

// ---- Penetration depth -----------------------------------------------------------

struct PenetrationInput {
  const ConvexPolytope* a = nullptr;  ///< fixed polytope A (not owned)
  Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity();
  const ConvexPolytope* b = nullptr;  ///< moving polytope B (not owned)
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  PenetrationMethod method = PenetrationMethod::kExact;
  /// kApprox / kShallow: the accuracy parameter. 0 selects the method's
  /// default (defaults::kApproxPdDelta, defaults::kShallowPdDelta); otherwise
  /// it must lie in [defaults::kMinPdDelta, defaults::kMaxPdDelta], for every
  /// method (kExact and kBruteForce do not use it: InvalidInputError for a
  /// NaN or out-of-range one all the same).
  double delta = 0.0;
};

/// Result of penetrationDepth().
///
/// | status       | depth        | translation_W       | normal_W  | facet, features |
/// |--------------|--------------|---------------------|-----------|-----------------|
/// | kSeparated   | 0            | 0                   | NaN       | kNone           |
/// | kTouching    | 0            | 0                   | NaN       | kNone           |
/// | kPenetrating | > 0 (world)  | depth * normal_W    | unit      | the facet of M  |
///
/// kPenetrating, per method:
///   - kExact, kShallow, kBruteForce: depth is PD (to round-off); normal_W is
///     the outward normal of the facet of M closest to the origin. B
///     translated by translation_W touches A (interiors disjoint).
///   - kApprox: PD <= depth <= (1 + delta) PD. depth is the smallest plane
///     offset h among the facets of M hit by the grid's rays, normal_W that
///     facet's normal; B translated by translation_W has its interior disjoint
///     from A's (it touches A, or is separated from it when the foot point
///     lies outside that facet).
/// facet names the facet of M (FaceOfM in A's and B's indices; kNone for the
/// brute force, which builds M without features). feature_a / feature_b are
/// the features of A and B that span it: FV = (face of A, vertex of B), VF =
/// (vertex of A, face of B), EE = (edge, edge).
struct PenetrationResult {
  PenetrationStatus status = PenetrationStatus::kSeparated;
  double depth = 0.0;
  Eigen::Vector3d translation_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal_W = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  FaceOfM facet;
  Feature feature_a;
  Feature feature_b;
  double delta = 0.0;  ///< the delta used (kApprox / kShallow), else 0
  PenetrationStats stats;
};

/// Penetration depth of A and B by input.method.
PenetrationResult penetrationDepth(const PenetrationInput& input);

// ---- Polyhedral metric ------------------------------------------------------------

/// A centrally symmetric convex polytope K (centred at the world origin) that
/// defines the norm |t|_K = min { lambda >= 0 : t in lambda K } on
/// translations (world frame). Built once, used by any number of queries.
class PolyhedralMetric {
 public:
  /// The hull of points_W. Throws InvalidInputError when the hull is not a
  /// solid (flat or degenerate), or not centrally symmetric about the origin
  /// (some vertex v without a vertex -v, to defaults::kMetricSymmetryRel of
  /// the hull's radius), naming the offending vertex.
  static PolyhedralMetric fromPoints(const std::vector<Eigen::Vector3d>& points_W);

  const ConvexPolytope& polytope() const { return k_; }
  /// Vertices of K (world frame): the ray directions of the query.
  const std::vector<Eigen::Vector3d>& vertices() const { return k_.vertices(); }
  /// |t|_K = max over the facets n . x <= h of K of (n . t) / h.
  double norm(const Eigen::Vector3d& t_W) const;

 private:
  explicit PolyhedralMetric(ConvexPolytope k) : k_(std::move(k)) {}
  ConvexPolytope k_;
};

struct PolyhedralInput {
  const ConvexPolytope* a = nullptr;
  Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity();
  const ConvexPolytope* b = nullptr;
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  const PolyhedralMetric* metric = nullptr;
  /// kExact: one ray shot per vertex of K (paper Corollary 3.5), exact;
  /// kBruteForce: min over the facets of the explicit M. Other methods are
  /// an InvalidInputError.
  PenetrationMethod method = PenetrationMethod::kExact;
};

/// Result of polyhedralPenetrationDepth(): the shortest separating translation
/// under |.|_K.
///
///   depth = PD_K = min { |t|_K : int(A) and int(B + t) are disjoint }
///         = the largest lambda with lambda K inside M
///         = min over facets n . x <= h of M of h / h_K(n),  h_K(n) = max_k n . k
///
/// (dimensionless: the number of copies of K; a length in world units when
/// K is a unit ball of a norm, e.g. the cube [-1, 1]^3 for L-infinity).
///
/// | status       | depth | translation_W             | euclidean_length | normal_W, facet, k_vertex |
/// |--------------|-------|---------------------------|------------------|---------------------------|
/// | kSeparated   | 0     | 0                         | 0                | NaN, kNone, -1            |
/// | kTouching    | 0     | 0                         | 0                | NaN, kNone, -1            |
/// | kPenetrating | PD_K  | PD_K * vertex k_vertex    | |translation_W|  | facet of M it reaches     |
///
/// translation_W is a point of the boundary of M: B translated by it touches
/// A, and no translation with a smaller K-norm separates them.
struct PolyhedralResult {
  PenetrationStatus status = PenetrationStatus::kSeparated;
  double depth = 0.0;
  Eigen::Vector3d translation_W = Eigen::Vector3d::Zero();
  double euclidean_length = 0.0;
  Eigen::Vector3d normal_W = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  FaceOfM facet;
  Feature feature_a;
  Feature feature_b;
  int k_vertex = -1;  ///< vertex of K (index into PolyhedralMetric::vertices()) along which B moves
  PenetrationStats stats;
};

PolyhedralResult polyhedralPenetrationDepth(const PolyhedralInput& input);

// ---- Width ------------------------------------------------------------------------

struct WidthInput {
  const ConvexPolytope* a = nullptr;
  /// A's pose: only the reported direction depends on it.
  Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity();
  PenetrationMethod method = PenetrationMethod::kExact;
  double delta = 0.0;  ///< as in PenetrationInput
};

/// Result of width(): width(A) = PD(A, A) (paper Proposition 2.1), the
/// smallest distance between two parallel planes enclosing A.
///
/// direction_W is a unit normal of those planes: A lies in
/// { x : c - width <= direction_W . x <= c } for c = max over A of
/// direction_W . x (for kApprox, width is the distance between the two
/// supporting planes orthogonal to direction_W, and width <= (1 + delta)
/// times the true width). A flat polygon has width 0 and direction_W its
/// plane's normal. facet, feature_a / feature_b: the facet of M = A - A and
/// the features of A on the upper (feature_a) and lower (feature_b) plane.
struct WidthResult {
  double width = 0.0;
  Eigen::Vector3d direction_W = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  FaceOfM facet;
  Feature feature_a;
  Feature feature_b;
  double delta = 0.0;
  PenetrationStats stats;
};

WidthResult width(const WidthInput& input);

// ---- Direction grid ---------------------------------------------------------------

/// The direction grid of Approx-Separation for `delta`: unit vectors such
/// that every unit vector is within angle coveringAngle(delta) of one of them
/// (see penetration_grid.cpp for the construction and the proof). Ordered so
/// that consecutive directions are neighbours (warm starts).
std::vector<Eigen::Vector3d> directionGrid(double delta);
/// min(sqrt(delta), arccos(1 / (1 + delta))): the covering angle that makes
/// 1 / cos(angle) <= 1 + delta (paper Lemma 3.1).
double coveringAngle(double delta);

}  // namespace mddual
