// Directional queries between two posed convex polytopes: the signed minimum
// directional distance (mdd), the time of impact along a direction (toi) and
// the intersection test (intersect), computed with MDD-DUAL (Choi, Li, Rong,
// Wang, Cameron). Conventions (../../../docs/algorithms.md#1-definitions-and-sign-conventions):
//
//   A is fixed, B moves. M = A - B. B translated by v touches or overlaps A iff
//   v is in M. The direction s (any nonzero length) gives u = s / |s|; the line
//   {t u} meets M in the interval [t_lo, t_hi] or not at all.
//
// Units: every distance and every t below is a length in world units measured
// along u (not a multiple of |s|). Frames: _W quantities are in the world
// frame; X_WA and X_WB are the poses of A and B in the world.
//
// Thread safety: the functions are pure given their inputs; a WarmStart is
// the only thing they write, so give each thread (and each pair) its own.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <string>

#include "mddual/polytope.h"

namespace mddual {

// ---- Statuses -----------------------------------------------------------------

/// Relation of A and B along the query direction.
enum class ContactStatus : std::uint8_t {
  /// The interiors are disjoint and B touches A after a translation along the
  /// line (forward if t_lo > 0, backward if t_hi < 0).
  kSeparated,
  /// A and B touch (the origin is on the boundary of M, within tolerance).
  kTouching,
  /// The interiors overlap; the signed distance is minus the shorter of the two
  /// translations along the line that separate them.
  kPenetrating,
  /// The line misses M: no translation along it makes A and B touch.
  kNoContact,
};

/// Outcome of a time-of-impact query along +u.
enum class ToiStatus : std::uint8_t {
  /// B reaches A after moving `toi` > 0 along +u (within max_distance).
  kHit,
  /// A and B already touch or overlap: toi = 0.
  kInContact,
  /// B never touches A moving along +u (or not within max_distance).
  kNever,
};

/// Outcome of an intersection test.
enum class IntersectStatus : std::uint8_t {
  kSeparated,    ///< disjoint; separating_normal_W holds a proof
  kTouching,     ///< boundaries meet, interiors disjoint (within tolerance)
  kPenetrating,  ///< interiors overlap
};

const char* toString(ContactStatus status);
const char* toString(ToiStatus status);
const char* toString(IntersectStatus status);

// ---- Features and statistics --------------------------------------------------

enum class FeatureType : std::uint8_t { kNone, kVertex, kEdge, kFace };
const char* toString(FeatureType type);

/// A vertex, edge or face of one polytope, by its index in that polytope.
struct Feature {
  FeatureType type = FeatureType::kNone;
  int index = -1;
};

/// Work done by one query. The face counts are candidate faces of M (FV, VF
/// and EE supporting planes) evaluated by each phase, counted once per ray
/// search. On generic inputs each is a distinct face of M; on degenerate ones
/// (parallel faces of A and B, boxes in the same orientation) several
/// candidates name the same face of M, so the counts can exceed |faces of M|.
struct SearchStats {
  int centre_iterations = 0;  ///< portal refinement steps to find the centre of duality
  int fv_faces = 0;           ///< faces of M evaluated in SEARCH-FV (facet of A + vertex of B)
  int vf_faces = 0;           ///< faces of M evaluated in SEARCH-VF (vertex of A + facet of B)
  int ee_faces = 0;           ///< faces of M evaluated in SEARCH-EE (all three kinds)
  int ee_edge_faces = 0;      ///< of ee_faces, the EE (edge-edge) faces
  int steps = 0;              ///< moves of the hill climbs (all phases, all rays)
  int rays = 0;               ///< ray searches run (0 to 2)
  int support_vertices = 0;   ///< vertices whose support value was evaluated
  bool planar = false;        ///< answered by the planar path (grazing line or flat M)
  int totalFaces() const { return fv_faces + vf_faces + ee_faces; }
};

/// A contact between A and B translated by t along u. The normal is the
/// outward unit normal of the face of M that the line hits: it points from A
/// toward B, A lies in the half-space normal_W . x <= normal_W . point_W and B
/// (translated by t u) in the other one. point_W is a point of A that B
/// (translated by t u) touches, whatever the kind of contact (FV, VF, EE): it
/// is on A (to round-off), and on B within the touching tolerance
/// (defaults::kTouchRel times the pair's length scale) or, where the touching
/// faces are planar only to round-off, within twice that non-planarity (at
/// most 2 defaults::kContactTieMaxRel times the scale). When the touching
/// features are larger than a vertex on both sides (face to face, edge to
/// face, parallel edges) they meet in a patch, and point_W is some point of
/// that patch, not a particular one (not its centre). feature_a / feature_b
/// are the features of A and B that name the face of M hit (for an EE
/// contact: an edge of each); for a patch, e.g. A's face and one vertex of
/// B's touching face.
struct Contact {
  double t = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector3d normal_W = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector3d point_W = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Feature feature_a;
  Feature feature_b;
};

// ---- Warm start ---------------------------------------------------------------

/// A face of M named by its features: FV (facet of A, vertex of B), VF (vertex
/// of A, facet of B) or EE (edge of A, edge of B).
struct FaceOfM {
  enum class Kind : std::uint8_t { kNone, kFV, kVF, kEE };
  Kind kind = Kind::kNone;
  int a = -1;  ///< index into A: face (FV), vertex (VF) or edge (EE)
  int b = -1;  ///< index into B: vertex (FV), face (VF) or edge (EE)
};

/// Per-pair cache for frame coherence (paper VI-E): the queries start from the
/// faces and support vertices where the last query on this pair ended. Keep one
/// per pair of polytopes and per thread; reusing it for another pair is safe
/// (indices are range-checked) but useless.
struct WarmStart {
  /// Support vertices of A and B where the centre phase's first two supports
  /// ended (0: toward the origin, 1: across the ray), and where the overlap
  /// test's three supports ended.
  int centre_a[2] = {-1, -1};
  int centre_b[2] = {-1, -1};
  int overlap_a[3] = {-1, -1, -1};
  int overlap_b[3] = {-1, -1, -1};
  FaceOfM forward;     ///< optimal face for the entry point t_lo
  FaceOfM backward;    ///< optimal face for the exit point t_hi
  FaceOfM separating;  ///< last separating face found by intersect()
};

// ---- Queries ------------------------------------------------------------------

/// Input of mdd() and toi().
struct DirectionalInput {
  const ConvexPolytope* a = nullptr;  ///< fixed polytope A (not owned)
  Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity();
  const ConvexPolytope* b = nullptr;  ///< moving polytope B (not owned)
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  Eigen::Vector3d s_W = Eigen::Vector3d::UnitX();  ///< direction of B's motion, any nonzero length
  /// toi() only: contacts farther than this along u are reported as kNever,
  /// which lets the search stop early (a motion validator passes the edge
  /// length). mdd() ignores it.
  double max_distance = std::numeric_limits<double>::infinity();
  /// toi() only: when false, the caller only wants to know whether B touches
  /// A within max_distance (a yes/no motion check), and toi() may answer kHit
  /// before computing the first contact (see ToiResult::toi_exact). mdd()
  /// ignores it.
  bool exact_toi = true;
};

/// Result of mdd().
///
/// | status       | distance          | t_lo, t_hi                          | contact                           |
/// |--------------|-------------------|-------------------------------------|-----------------------------------|
/// | kSeparated   | t_lo > 0 or -t_hi | the near end; the far end is NaN   | at the near end                   |
/// |              |                   | (not computed: one search suffices) |                                   |
/// | kTouching    | 0                 | both                                | at t = 0                          |
/// | kPenetrating | -min(-t_lo, t_hi) | both                                | at the end that gives `distance`  |
/// | kNoContact   | NaN               | NaN                                 | all NaN, features kNone           |
///
/// "Near end": t_lo when B reaches A moving forward (t_lo > 0), t_hi when it
/// must move backward (t_hi < 0). bruteForce*() fill both ends always.
struct MddResult {
  ContactStatus status = ContactStatus::kNoContact;
  double distance = std::numeric_limits<double>::quiet_NaN();  ///< signed MDD (world units)
  double t_lo = std::numeric_limits<double>::quiet_NaN();      ///< entry of the line into M
  double t_hi = std::numeric_limits<double>::quiet_NaN();      ///< exit of the line from M
  Contact contact;
  SearchStats stats;
};

/// Result of toi(). toi is the first t >= 0 with t u in M: > 0 for kHit, 0
/// for kInContact, +infinity for kNever. contact is filled for kHit only; the
/// query does not spend work to tell touching from overlapping.
///
/// With input.exact_toi == false a hit may be decided early, from a point of
/// M on the line within [0, max_distance]: then status is kHit, toi_exact is
/// false, toi is an upper bound on the first contact (B touches or overlaps A
/// somewhere in [0, toi], possibly already at 0), and contact is all NaN.
/// kNever and kInContact are always exact.
struct ToiResult {
  ToiStatus status = ToiStatus::kNever;
  double toi = std::numeric_limits<double>::infinity();
  bool toi_exact = true;
  Contact contact;
  SearchStats stats;
};

/// Input of intersect(): no direction needed.
struct IntersectInput {
  const ConvexPolytope* a = nullptr;
  Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity();
  const ConvexPolytope* b = nullptr;
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
};

/// Result of intersect(). For kSeparated, separating_normal_W is a unit n with
/// max over A of n . x < min over B of n . x (a proof of separation); for the
/// other statuses it is NaN.
struct IntersectResult {
  IntersectStatus status = IntersectStatus::kSeparated;
  bool intersecting = false;  ///< status != kSeparated
  Eigen::Vector3d separating_normal_W = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  SearchStats stats;
};

/// Signed minimum directional distance of A and B along s (MDD-DUAL). Throws
/// InvalidInputError for a null polytope, a non-finite pose or a zero or
/// non-finite direction; NumericalError if an internal limit is hit.
MddResult mdd(const DirectionalInput& input, WarmStart* warm = nullptr);

/// How far B can translate along +s before it touches A. Computes only what
/// that needs: one ray search at most, with early exits.
ToiResult toi(const DirectionalInput& input, WarmStart* warm = nullptr);

/// Collision test with early escape (paper section V).
IntersectResult intersect(const IntersectInput& input, WarmStart* warm = nullptr);

/// The query as one line of `mddual query`'s input format: both polytopes'
/// vertices in the world frame and the direction, 17 significant digits, so
/// a failing query can be pasted into a test or piped into the CLI.
std::string toJsonLine(const DirectionalInput& input, const std::string& id = "repro");

/// Throws InvalidInputError "<query>: <what> has a non-finite translation (or
/// rotation) entry (NaN or infinity)" when X has a NaN or infinite entry in
/// its top three rows; otherwise does nothing (12 comparisons, no rigidity
/// check: the pair queries check that; no allocation unless it throws: it
/// runs on every state check). For callers that test a pose before a
/// traversal, where a NaN pose would fail every volume test and read as
/// "free": the core's hierarchy queries and the planning layer's scenes.
void requireFinitePose(const Eigen::Isometry3d& X, const char* what, const char* query);

}  // namespace mddual
