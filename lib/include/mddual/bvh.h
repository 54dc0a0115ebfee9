// Bvh: a static bounding-volume hierarchy over a set of convex pieces, and the
// traversals the collision checkers build on (a box or oriented-box query,
// tree against tree, and a cast: branch and bound on the first contact of one
// set translating against another). No OMPL and no scene types: a piece is a
// point set (its convex hull) in the set's frame S.
//
// The tree: a binary tree built top down (median split of the pieces'
// centres along the longest axis), one piece per leaf. Every node holds three
// volumes in frame S, each fitted to the points of the pieces below it: an
// axis-aligned box (it also holds the children's boxes), an oriented box (Obb)
// and a bounding sphere; plus the largest distance of those points from the
// origin of S (what a rotation about that origin can move them). Optionally,
// inner nodes with few pieces also hold the convex hull of their pieces'
// vertices: the core's toi on a pair of hulls is a lower bound of the toi of
// every pair of pieces below (a hull contains its pieces), so a cast can prune
// with it. A leaf whose piece has exactly three points (a mesh triangle) also
// keeps them: tree-against-tree tests the triangle itself.
//
// Thread safety: a Bvh is immutable after construction; any number of threads
// may run queries on it at once.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <limits>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "mddual/polytope.h"

namespace mddual {

template <typename Signature>
class FunctionRef;

/// A non-owning reference to a callable (the callbacks of the traversals):
/// no allocation, one indirect call. It refers to the callable it was made
/// from, which must outlive it: pass a lambda directly as the argument, do not
/// store a FunctionRef made from a temporary.
template <typename R, typename... Args>
class FunctionRef<R(Args...)> {
 public:
  template <typename F, typename = std::enable_if_t<!std::is_same_v<std::decay_t<F>, FunctionRef> &&
                                                    std::is_invocable_r_v<R, F&, Args...>>>
  FunctionRef(F&& f)  // NOLINT(google-explicit-constructor): callbacks convert implicitly
      : object_(const_cast<void*>(static_cast<const void*>(&f))), call_([](void* object, Args... args) -> R {
          return (*static_cast<std::remove_reference_t<F>*>(object))(std::forward<Args>(args)...);
        }) {}
  R operator()(Args... args) const { return call_(object_, std::forward<Args>(args)...); }

 private:
  void* object_;
  R (*call_)(void*, Args...);
};

/// An oriented box in a frame F: the points centre_F + axes_F * y with
/// |y_k| <= half[k]. The columns of axes_F are orthonormal.
struct Obb {
  Eigen::Vector3d centre_F = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes_F = Eigen::Matrix3d::Identity();
  Eigen::Vector3d half = Eigen::Vector3d::Zero();

  /// This box seen from frame G (X_GF: pose of F in G), every half extent
  /// grown by `margin` (the grown box contains every point within `margin` of
  /// this one).
  Obb transformed(const Eigen::Isometry3d& X_GF, double margin = 0.0) const;
  /// The eight corners.
  std::array<Eigen::Vector3d, 8> corners() const;
  /// Half extents of the axis-aligned box (same frame, same centre) that
  /// holds this box.
  Eigen::Vector3d aabbHalf() const { return axes_F.cwiseAbs() * half; }
  /// Whether p_F lies in the box grown by `tol`.
  bool contains(const Eigen::Vector3d& p_F, double tol = 0.0) const;
};

/// Slack of the volume tests, relative to the magnitude of the coordinates
/// involved (largest |centre| plus extents): a gap must exceed it to count.
/// More than the round-off of the projections, and more than the core's
/// touching tolerance (1e-10 of a pair's length scale), so that a pair the
/// core calls touching is never pruned by its volumes. Dimensionless.
inline constexpr double kBvhSlackRel = 1e-9;

/// Whether the closed boxes a and b (same frame) are disjoint: a separating
/// axis among the 15 of the separating-axis theorem (3 + 3 face normals, 9
/// edge-direction cross products), by more than kBvhSlackRel times the
/// magnitude of the boxes' coordinates. Touching boxes are not disjoint.
bool obbsDisjoint(const Obb& a, const Obb& b);
/// The same with a given slack (absolute, world units; >= 0).
bool obbsDisjoint(const Obb& a, const Obb& b, double slack);

/// The boxes `moving` translated by s u (u any direction; s in [0, max_s],
/// max_s may be +infinity) and `fixed` (same frame): returns false when they
/// are disjoint for every such s; otherwise true and [*s_lo, *s_hi], the
/// interval of s where they overlap, cut to [0, max_s] (exact up to the same
/// slack as obbsDisjoint: the 15 axes decide overlap at each s).
bool obbCastInterval(const Obb& fixed, const Obb& moving, const Eigen::Vector3d& u, double max_s, double* s_lo,
                     double* s_hi);
/// The same with a given slack (absolute; >= 0).
bool obbCastInterval(const Obb& fixed, const Obb& moving, const Eigen::Vector3d& u, double max_s, double slack,
                     double* s_lo, double* s_hi);
/// The same on the 6 face axes only (3 of each box): cheaper, and a
/// superset of obbCastInterval's interval (false only when the face axes
/// alone separate the boxes for every s).
bool obbCastIntervalFaces(const Obb& fixed, const Obb& moving, const Eigen::Vector3d& u, double max_s, double slack,
                          double* s_lo, double* s_hi);
/// obbCastInterval (with the slack), and in the same pass the face-axes
/// test of a smaller box inside `moving`: its centre and axes, half extents
/// inner_half (each <= moving.half). *inner_apart is set to whether that
/// inner box, translated by s u, is separated from `fixed` for every s in
/// [0, max_s]: when this returns true, on the 6 face axes with no slack, as
/// obbCastIntervalFaces with slack 0 would say of it; when this returns
/// false, true (the inner box lies inside `moving`). For a
/// traversal that grows a node's box (checkRotating's motion growth) and
/// asks whether the growth is what keeps two nodes from being separated: the
/// frame and speeds along the face axes are shared, so the second answer
/// costs six more radii and cuts.
bool obbCastIntervalInner(const Obb& fixed, const Obb& moving, const Eigen::Vector3d& inner_half,
                          const Eigen::Vector3d& u, double max_s, double slack, double* s_lo, double* s_hi,
                          bool* inner_apart);

/// Whether the axis-aligned box with centre c and half extents h, translated
/// by s u for s in [0, max_s] (max_s may be +infinity; u any direction, zero
/// for a box at rest), misses `box` (same frame) by more than the slack of
/// obbsDisjoint: a cheap test to run before the oriented ones.
bool sweptAabbApart(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& c, const Eigen::Vector3d& h,
                    const Eigen::Vector3d& u, double max_s);
/// The same with a given slack (absolute; >= 0).
bool sweptAabbApart(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& c, const Eigen::Vector3d& h,
                    const Eigen::Vector3d& u, double max_s, double slack);

/// Whether the sphere of centre c and radius r, swept along the segment from
/// c to c + v (v zero for a sphere at rest), misses the oriented box `box`
/// (same frame) by more than `slack` (absolute; >= 0) along one of the box's
/// 3 face axes: the segment's projection on the axis, grown by r + slack,
/// against the box's. Sound (a swept sphere that meets the box meets it on
/// every axis) and cheap: no frame between two boxes, no division. For a
/// sweep whose sphere is all that is posed yet (checkRotating's triples,
/// before the robot node's box over the interval is built) against a node of
/// large flat triangles, whose box is a thin slab inside a wide sphere.
bool sweptSphereObbApart(const Obb& box, const Eigen::Vector3d& c, double r, const Eigen::Vector3d& v, double slack);

/// Whether the triangle `tri` (its three points; a segment or a point when
/// they are collinear or coincide) and the oriented box `box` (same frame)
/// are apart by more than `slack` (absolute; >= 0) along one of the 13 axes
/// of the separating-axis theorem for a triangle and a box: the box's 3 face
/// normals, the triangle's normal and the 9 products of a box axis and a
/// triangle edge. Exact for the pair up to the slack (the box's own box
/// around the triangle is not: a large triangle fills half of it), so a
/// world leaf that is a triangle is tested with it in place of its box.
bool triangleObbApart(const std::array<Eigen::Vector3d, 3>& tri, const Obb& box, double slack);

/// The cast of `moving` (frame F), translated by s u for s in [0, max_s] (u
/// of any length, max_s may be +infinity), against the fixed triangle `tri`
/// (three points, frame F) on triangleObbApart's 13 axes: each axis keeps
/// the interval of s at which it does not separate them (by more than the
/// slack), as in obbCastInterval. Returns false when those intervals have no
/// common s (at every s some axis separates them); otherwise true with
/// [*s_lo, *s_hi] their common part: exactly the s at which
/// triangleObbApart(tri, moving at s, slack) is false. With inner_half (each
/// <= moving.half), *inner_apart is set to whether the box of moving's
/// centre and axes and those half extents is so separated from the
/// triangle, with no slack, at every s (true when this returns false), as in
/// obbCastIntervalInner; without it, to whether this returns false.
bool triangleObbCastInterval(const std::array<Eigen::Vector3d, 3>& tri, const Obb& moving, const Eigen::Vector3d& u,
                             double max_s, double slack, double* s_lo, double* s_hi,
                             const Eigen::Vector3d* inner_half = nullptr, bool* inner_apart = nullptr);

/// Options of a Bvh.
struct BvhOptions {
  /// Inner nodes with at most this many pieces also get the convex hull of
  /// their pieces' vertices (0: no hulls). A hull that cannot be built (qhull
  /// fails, collinear points) is left out; the node then has none.
  int hull_max_pieces = 0;
};

/// See the file comment.
class Bvh {
 public:
  /// One node; its volumes are in the set's frame S and hold every point of
  /// its pieces.
  struct Node {
    Eigen::AlignedBox3d box;  ///< also holds the children's boxes
    Obb obb;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< bounding sphere
    double radius = 0.0;
    double max_norm = 0.0;  ///< largest |p| over the node's points (distance from the origin of S)
    /// Magnitude of the volumes' coordinates (largest |centre| + extent):
    /// scales the round-off slack of the tests on the node.
    double scale = 0.0;
    int left = -1;  ///< inner node: children; leaves: -1
    int right = -1;
    int first = 0;  ///< the node's pieces: pieceAt(first .. first + count - 1)
    int count = 0;
    int hull = -1;  ///< index of the node's hull, -1 when it has none
    /// A leaf whose piece has exactly 3 points: index of its triangle
    /// (Bvh::triangle), -1 otherwise.
    int triangle = -1;
    bool isLeaf() const { return left < 0; }
  };

  Bvh() = default;
  /// Builds the tree over pieces given by their points in frame S (each
  /// piece: its convex hull; any non-empty set of points, flat and degenerate
  /// ones included). An empty list gives an empty tree. Throws
  /// InvalidInputError for a piece without points or with a non-finite
  /// coordinate, naming the piece and the point.
  explicit Bvh(const std::vector<std::vector<Eigen::Vector3d>>& pieces_S, const BvhOptions& options = BvhOptions());
  /// The pieces as polytopes, piece k placed at X_SP[k] in S (identity when
  /// X_SP is empty; otherwise it must have one pose per polytope). Throws
  /// InvalidInputError for a null polytope or a pose count mismatch.
  static Bvh fromPolytopes(const std::vector<const ConvexPolytope*>& polytopes,
                           const std::vector<Eigen::Isometry3d>& X_SP = {}, const BvhOptions& options = BvhOptions());

  bool empty() const { return nodes_.empty(); }
  int numPieces() const { return static_cast<int>(order_.size()); }
  int numNodes() const { return static_cast<int>(nodes_.size()); }
  int numHulls() const { return static_cast<int>(hulls_.size()); }
  /// Index of the root (0), or -1 for an empty tree.
  int root() const { return nodes_.empty() ? -1 : 0; }
  const Node& node(int n) const { return nodes_[static_cast<std::size_t>(n)]; }
  /// The piece (index into the input) of leaf `n`.
  int leafPiece(int n) const { return order_[static_cast<std::size_t>(node(n).first)]; }
  /// The k-th piece in tree order (a node's pieces are contiguous).
  int pieceAt(int k) const { return order_[static_cast<std::size_t>(k)]; }
  /// The node's hull (frame S), or nullptr.
  const ConvexPolytope* hull(int n) const;
  /// The points of a triangle leaf (Node::triangle), frame S.
  const std::array<Eigen::Vector3d, 3>& triangle(int k) const { return triangles_[static_cast<std::size_t>(k)]; }
  /// The leaf of a piece.
  int leafOf(int piece) const { return leaf_of_[static_cast<std::size_t>(piece)]; }
  /// Longest root-to-leaf path (edges; 0 for a single leaf, -1 when empty).
  int height() const { return height_; }

  /// Calls fn(piece) for every piece whose leaf box meets `box_S` (closed
  /// boxes), until fn returns false. Returns false when fn stopped it.
  bool queryBox(const Eigen::AlignedBox3d& box_S, FunctionRef<bool(int)> fn) const;
  /// Calls fn(piece) for the pieces whose leaf's oriented box and those of
  /// all its ancestors are not disjoint from `obb_S` (obbsDisjoint), until fn
  /// returns false: every piece that meets obb_S is among them. Returns false
  /// when fn stopped it.
  bool queryObb(const Obb& obb_S, FunctionRef<bool(int)> fn) const;

 private:
  int build(std::vector<std::vector<Eigen::Vector3d>>& points, std::vector<Eigen::Vector3d>& centres, int first,
            int count, int depth, const BvhOptions& options);

  std::vector<Node> nodes_;
  std::vector<int> order_;
  std::vector<int> leaf_of_;
  std::vector<std::shared_ptr<const ConvexPolytope>> hulls_;
  std::vector<std::array<Eigen::Vector3d, 3>> triangles_;
  int height_ = -1;
};

/// Work counts of a traversal (for statistics and tests, never for control).
struct BvhStats {
  int node_pairs = 0;    ///< node pairs whose volumes were tested
  int leaf_pairs = 0;    ///< leaf pairs handed to the callback
  int hull_queries = 0;  ///< core queries on node hulls (castFirst)
};

/// Tree against tree, with the set of b placed at X_AB in a's frame and b's
/// volumes grown by margin_b >= 0 (each half extent and radius; a grown
/// volume holds every point within margin_b of the volume): calls
/// fn(piece_a, piece_b) for the pairs whose volumes overlap at every pair of
/// nodes on the way down to their leaves (spheres and boxes at every pair;
/// oriented boxes at the leaves and where one is much tighter than its
/// axis-aligned box; a leaf of a that is a triangle is tested itself against
/// b's oriented box, triangleObbApart), until fn
/// returns false. These are some of the pairs whose leaf volumes overlap, and
/// they include every pair whose pieces come within margin_b of each other
/// (touching included). Returns false when fn stopped it. X_AB must be a
/// rigid transform: a non-finite entry is an InvalidInputError (it would fail
/// every volume test and report no pair); orthonormality is left to the pair
/// queries fn runs (the core's queries check it), as the full check cost a
/// quarter of a small scene's state check (callgrind on the thin wall;
/// docs/results/tuning.md).
bool forEachOverlappingPair(const Bvh& a, const Bvh& b, const Eigen::Isometry3d& X_AB, double margin_b,
                            FunctionRef<bool(int, int)> fn, BvhStats* stats = nullptr);

/// Options of castFirst().
struct CastOptions {
  /// Grows b's volumes (see forEachOverlappingPair); hulls are not queried
  /// when it is positive (they bound the pieces, not the grown pieces).
  double margin_b = 0.0;
  /// false: stop at the first leaf pair that reports a contact (any contact,
  /// not necessarily the first).
  bool first_contact = true;
  /// Query node hulls (both nodes must have one) for a tighter lower bound.
  bool use_hulls = true;
  /// With first_contact: stop once every pair left is bounded below by the
  /// best contact so far less this distance (>= 0, the units of
  /// max_distance). The first contact then lies in [CastHit::lower_bound,
  /// CastHit::distance], an interval no longer than stop_within. 0: the
  /// exact first contact (a flat contact, where many pairs touch at nearly
  /// the same distance, visits them all).
  double stop_within = 0.0;
};

/// Result of castFirst(): the first contact distance and its pair.
struct CastHit {
  double distance = std::numeric_limits<double>::infinity();  ///< +infinity: no contact within max_distance
  int piece_a = -1;
  int piece_b = -1;
  /// No pair touches before it (with first_contact): distance itself, or
  /// with stop_within > 0 at most stop_within less (the smallest bound left
  /// when the search stopped). +infinity when there is no contact.
  double lower_bound = std::numeric_limits<double>::infinity();
};

/// The contact distance of one pair of pieces for castFirst(): the distance
/// in [0, limit] at which piece_b, translating along u, first touches
/// piece_a, or any value > limit (+infinity) when it does not within limit.
using CastLeafFn = FunctionRef<double(int piece_a, int piece_b, double limit)>;

/// Branch and bound on the first contact of set b (placed at X_AB in a's
/// frame) translating by s u_A, s in [0, max_distance] (u_A nonzero; the
/// distance is measured along u_A / |u_A|; max_distance >= 0, may be
/// +infinity) against set a. Node pairs are bounded below by the first
/// distance at which their swept volumes may meet (spheres, axis-aligned
/// boxes, and the oriented boxes on their six face axes: an interval that
/// holds the exact one of obbCastInterval, for less work; without
/// first_contact, a triangle leaf of a larger than b's node on its 13 axes,
/// triangleObbCastInterval), raised to the toi
/// of their hulls when both have one, and visited nearest first by that bound
/// (depth first with first_contact = false); a pair whose bound is not below
/// the best contact so far is pruned, and the leaf function is called with
/// limit = the best contact so far (max_distance at first). Returns the
/// smallest leaf distance over all pairs whose volumes meet within
/// max_distance (the same as calling leaf on every pair when leaf reports only
/// contacts of the pieces), or with first_contact = false the first one found.
/// Throws InvalidInputError for a zero or non-finite u_A, a negative or NaN
/// max_distance or options.stop_within, and an X_AB with a non-finite entry
/// (rigidity is left to the pair queries, as in forEachOverlappingPair).
CastHit castFirst(const Bvh& a, const Bvh& b, const Eigen::Isometry3d& X_AB, const Eigen::Vector3d& u_A,
                  double max_distance, CastLeafFn leaf, const CastOptions& options = CastOptions(),
                  BvhStats* stats = nullptr);

/// Result of nearestPair(): the smallest leaf value and its pair.
struct NearestHit {
  double value = std::numeric_limits<double>::infinity();  ///< +infinity: no pair beat the upper bound
  int piece_a = -1;
  int piece_b = -1;
  int node_pairs = 0;  ///< node pairs bounded (leaves included)
};

/// The value of one pair of pieces for nearestPair(): their signed distance
/// (or any value no smaller; any value >= best when it cannot beat best).
using NearestLeafFn = FunctionRef<double(int piece_a, int piece_b, double best)>;

/// Branch and bound on the smallest signed distance between a piece of set a
/// (frame A) and a piece of set b placed at X_AB: node pairs are visited
/// nearest first by a lower bound of the signed distance of any two convex
/// pieces inside them, the larger of two (less kBvhSlackRel of their
/// coordinates' magnitude): the gap between their bounding spheres, |c_a -
/// c_b| - r_a - r_b (apart: the pieces are at least that far; overlapping:
/// translating one by r_a + r_b - |c_a - c_b| along the centres' line, or
/// any line when they coincide, separates the spheres, so the depth is at
/// most that), and the same of a's
/// axis-aligned box and the box around b's posed oriented box (apart: their
/// distance; overlapping: minus their smallest overlap along an axis, a
/// translation that separates them). A pair whose bound is not below the best value so
/// far (at first `upper`, which may be +infinity) is pruned; leaf is called
/// with best = that value, and may run another traversal (nearestPair
/// included). Returns the smallest leaf value below `upper`.
/// Throws InvalidInputError for an X_AB with a non-finite entry or a NaN
/// upper.
NearestHit nearestPair(const Bvh& a, const Bvh& b, const Eigen::Isometry3d& X_AB, NearestLeafFn leaf,
                       double upper = std::numeric_limits<double>::infinity());

}  // namespace mddual
