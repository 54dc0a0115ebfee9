// Separation distance between two posed convex polytopes, with witness
// points (conventions of ../../../docs/algorithms.md#separation-distance, as in query.h): A and B are
// convex polytopes posed in the world by X_WA and X_WB, M = A - B, and
//
//   distance(A, B) = min { |a - b| : a in A, b in B } = distance from the origin to M.
//
// Method: GJK on M, evaluated in A's local frame (so bodies far from the
// world origin keep every bit of their relative geometry), with the exact
// closest point of each simplex (point, segment, triangle, tetrahedron) and a
// certified stop: each GJK step's support point w of M gives the lower bound
// v . w / |v| on the distance (no point of M is nearer along v), and the
// query stops when the upper bound |v| (a point of M) is within
// defaults::kDistanceGapRel of the pair's length scale of it. If GJK cannot
// close the gap (a round-off stall, typical when the bodies nearly touch),
// the closest points are recomputed exactly (vertex-face and edge-edge
// pairs) among the features near the two supporting planes orthogonal to
// GJK's direction; those provably contain a closest pair, whatever the gap
// (distance.cpp, polish()). Overlapping bodies: the penetration depth by
// penetrationDepth(kExact) (penetration.h).
//
// Units: world units. Frames: _W quantities are in the world frame.
// Errors: InvalidInputError for a null polytope or a bad pose (naming it).
// Thread safety: pure given its inputs.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <limits>

#include "mddual/polytope.h"

namespace mddual {

/// Relation of A and B found by distance().
enum class DistanceStatus : std::uint8_t {
  kSeparated,    ///< the gap exceeds the touch tolerance (defaults::kTouchRel * L)
  kTouching,     ///< the bodies meet within the touch tolerance, interiors disjoint (or one is flat)
  kPenetrating,  ///< the interiors overlap by more than the touch tolerance
};

const char* toString(DistanceStatus status);

/// Input of distance().
struct DistanceInput {
  const ConvexPolytope* a = nullptr;  ///< polytope A (not owned)
  Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity();
  const ConvexPolytope* b = nullptr;  ///< polytope B (not owned)
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
};

/// Work done by one distance() query.
struct DistanceStats {
  int gjk_iterations = 0;    ///< GJK steps (support evaluations of M), all GJK runs of the query
  int support_vertices = 0;  ///< vertices whose support value was evaluated
  bool polished = false;     ///< GJK stalled; the closest features were evaluated exactly
  int polish_pairs = 0;      ///< feature pairs (vertex-face, edge-edge) evaluated by the polish
  bool penetration = false;  ///< penetrationDepth(kExact) was called (origin in or on M)
};

/// Result of distance(). L is the pair's length scale (max of the two radii
/// and the distance between the centroids).
///
/// | status       | distance            | p_WA, p_WB                              | normal_W             |
/// |--------------|---------------------|-----------------------------------------|----------------------|
/// | kSeparated   | |p_WB - p_WA| > 0   | closest points of A and of B            | (p_WB - p_WA) / dist |
/// | kTouching    | 0                   | a common point (|p_WB - p_WA| <= tol)   | NaN                  |
/// | kPenetrating | -PD < 0             | deepest pair: p_WA - p_WB = PD normal_W | unit, A toward B     |
///
/// kSeparated: distance is exact to kDistanceGapRel * L; lower_bound is
/// GJK's support-function lower bound (distance - lower_bound <=
/// kDistanceGapRel * L), or equals distance when the polish computed it from
/// the closest features (stats.polished).
/// kTouching: |true distance| <= kTouchRel * L. kPenetrating: PD is the
/// penetration depth (penetration.h, exact method): B translated by PD
/// normal_W touches A; p_WA is a point of A and p_WB a point of B with
/// p_WA - p_WB = PD normal_W up to the touch tolerance (B translated by PD
/// normal_W touches A at p_WA).
/// lower_bound: kSeparated as above; 0 for kTouching; distance otherwise.
struct DistanceResult {
  DistanceStatus status = DistanceStatus::kSeparated;
  double distance = std::numeric_limits<double>::quiet_NaN();  ///< signed (world units)
  double lower_bound = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector3d p_WA = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector3d p_WB = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector3d normal_W = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  DistanceStats stats;
};

/// Per-pair cache: the support vertices where the last query ended (frame
/// coherence). Reusing it for another pair is safe (indices are checked).
struct DistanceWarmStart {
  int a[4] = {-1, -1, -1, -1};
  int b[4] = {-1, -1, -1, -1};
  int size = 0;
};

/// Separation distance of A and B (see the file comment and DistanceResult).
DistanceResult distance(const DistanceInput& input, DistanceWarmStart* warm = nullptr);

/// A lower bound of the separation distance of A and B, for callers that only
/// need to know how far apart they at least are (certified motion checks):
/// GJK's certified support-function bound (a point of M is at most
/// kDistanceGapRel * L farther), or 0 when the bodies meet within the touch
/// tolerance (no depth is computed: far cheaper than distance() on
/// overlapping pairs). Never above the true distance. GJK stops as soon as
/// its bound reaches `enough` (then the answer is >= enough but may be below
/// the distance): what a nearest-pair search needs of a pair that cannot beat
/// its best so far. With `rel_gap` in [0, 1), GJK may also stop once its bound
/// is within rel_gap of its current upper bound (then the answer is at least
/// (1 - rel_gap) times the distance): what a caller that only scales a step
/// by the distance needs. Errors (also a rel_gap outside [0, 1)) and thread
/// safety as distance().
double separationLowerBound(const DistanceInput& input, DistanceWarmStart* warm = nullptr,
                            double enough = std::numeric_limits<double>::infinity(), double rel_gap = 0.0);

}  // namespace mddual
