// The scene model of the planning layer: a robot is a rigid body made of
// convex pieces in its body frame; a world is a set of static convex pieces in
// the world frame with a bounding-volume tree over them (the broad phase).
// Pieces are the core's ConvexPolytope, so every query of the core applies to
// them; mesh triangles are pieces too (flat polytopes).
//
// Frames: a robot piece's polytope is in the robot's body frame R (the state
// of a planning problem is the pose X_WR of that frame); a world piece's is in
// the world frame W.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "mddual/error.h"
#include "mddual/polytope.h"

namespace mddual::scene {

/// Bad scene input: unreadable or malformed file, unsupported geometry, an
/// empty or degenerate mesh. The message names the file and the element or
/// line.
class SceneError : public InvalidInputError {
 public:
  using InvalidInputError::InvalidInputError;
};

enum class PieceKind : std::uint8_t {
  kConvex,    ///< a convex solid (a primitive, a convex mesh, a mesh's hull)
  kTriangle,  ///< one triangle of a non-convex mesh (a flat polytope)
};

/// One convex piece, in its owner's frame (robot: body frame; world: world).
struct Piece {
  ConvexPolytope polytope;
  PieceKind kind = PieceKind::kConvex;
  Eigen::AlignedBox3d box;  ///< bounding box of the polytope, same frame
  Eigen::Vector3d centre;   ///< centre of a bounding sphere, same frame
  double radius = 0.0;      ///< its radius
  std::string origin;       ///< where it came from ("robot.urdf: link 'base', collision 0 (box)")

  /// Builds the bounds from the polytope.
  static Piece make(ConvexPolytope polytope, PieceKind kind, std::string origin);
};

/// The convex hulls of groups of nearby pieces (frame of the pieces): median
/// splits of the pieces' centres along the longest side of their box, down
/// to groups of at most max_per_cluster pieces, in that order. Each hull
/// holds every point of its pieces, so a distance to it bounds the distances
/// to its pieces from below: a coarse level for bound queries on a mesh
/// loaded as triangles. Throws InvalidInputError for max_per_cluster < 1.
std::vector<ConvexPolytope> clusterHulls(const std::vector<Piece>& pieces, int max_per_cluster);

/// A static tree of axis-aligned boxes (median splits), built once.
class AabbTree {
 public:
  AabbTree() = default;
  explicit AabbTree(const std::vector<Eigen::AlignedBox3d>& boxes);
  /// Appends to `out` the index of every box that intersects `query`
  /// (closed boxes: touching counts).
  void query(const Eigen::AlignedBox3d& query, std::vector<int>* out) const;
  int size() const { return static_cast<int>(boxes_.size()); }

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    int left = -1;  ///< inner node: children (-1 for a leaf)
    int right = -1;
    int first = 0;  ///< leaf: boxes order_[first, first + count)
    int count = 0;
  };
  int build(int first, int count);
  std::vector<Eigen::AlignedBox3d> boxes_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

/// A rigid robot: convex pieces in its body frame R.
class RigidBody {
 public:
  RigidBody() = default;
  /// Throws SceneError when `pieces` is empty.
  RigidBody(std::vector<Piece> pieces, std::string name);

  const std::vector<Piece>& pieces() const { return pieces_; }
  const std::string& name() const { return name_; }
  /// Bounding box of all pieces, frame R.
  const Eigen::AlignedBox3d& box() const { return box_; }
  /// Largest distance from the body origin to a vertex: bounds how far any
  /// point of the body moves when it rotates by an angle a (at most a * radius).
  double radius() const { return radius_; }

 private:
  std::vector<Piece> pieces_;
  std::string name_;
  Eigen::AlignedBox3d box_;
  double radius_ = 0.0;
};

/// The environment: pieces in the world frame W and a broad phase.
///
/// Worlds that change: pieces can be added, removed and moved between queries.
/// pieces() always holds the current pieces, densely (indices 0 .. n-1, the
/// indices every query reports); each piece also has an id that never changes
/// while it exists and is never reused (the pieces of a constructed world have
/// ids 0 .. n-1, equal to their indices until the first removal). Removing a
/// piece moves the last piece to its index.
///
/// The broad phase is a static tree over the pieces as they were at the last
/// rebuild, plus an overflow list of the pieces added or moved since (their
/// boxes scanned one by one); removed and moved pieces are skipped in the
/// tree by their id. An update costs O(1) (O(n) to recompute box()), until
/// the overflow and the stale tree entries together exceed kOverflowLimit(n)
/// = max(16, 2 sqrt(n)): then the tree is rebuilt (O(n log n)), so an update
/// costs O(sqrt(n) log n) amortized and a query scans at most O(sqrt(n))
/// overflow boxes. Chosen over a dynamic tree (Box2D's b2DynamicTree) for its
/// simplicity: the static tree's median splits stay as good as at the build,
/// and candidates() returns exactly the pieces whose boxes meet the query,
/// whatever the history of updates.
///
/// Thread safety: const methods may run concurrently; an update must not run
/// concurrently with anything else on the same world (update between
/// planning calls, not during them).
class World {
 public:
  World() = default;
  /// An empty world is allowed (free space).
  World(std::vector<Piece> pieces, std::string name);

  const std::vector<Piece>& pieces() const { return pieces_; }
  const std::string& name() const { return name_; }
  /// Bounding box of all pieces (empty box for an empty world).
  const Eigen::AlignedBox3d& box() const { return box_; }
  /// Appends the indices of the pieces whose bounding boxes meet `query_W`
  /// (closed boxes), each once.
  void candidates(const Eigen::AlignedBox3d& query_W, std::vector<int>* out) const;

  // ---- Updates (see the class comment). Each throws InvalidInputError for
  // an unknown id and leaves the world unchanged when it throws.
  /// Adds a piece (frame W) at the end of pieces(); returns its id. Its
  /// box, centre and radius are recomputed from its polytope; a piece without
  /// a polytope (no vertices) is refused (SceneError).
  int addPiece(Piece piece);
  /// Removes piece `id`.
  void removePiece(int id);
  /// Poses piece `id` at X_WP: its geometry as it was added (or built) is
  /// moved rigidly by X_WP (the identity restores it), so repeated moves do
  /// not accumulate round-off. Throws InvalidInputError for a non-finite or
  /// non-rigid (scaled, mirrored) pose and SceneError when the moved hull
  /// cannot be built.
  void movePiece(int id, const Eigen::Isometry3d& X_WP);
  /// Whether `id` names a current piece.
  bool hasPiece(int id) const;
  /// The index in pieces() of piece `id` (throws InvalidInputError unless
  /// hasPiece(id)).
  int indexOf(int id) const;
  /// The id of pieces()[index] (index in range).
  int idOf(int index) const { return id_of_[static_cast<std::size_t>(index)]; }
  /// Every id ever given is below this.
  int idLimit() const { return static_cast<int>(index_of_.size()); }
  /// The pose last given to movePiece for `id` (identity if never moved).
  Eigen::Isometry3d piecePose(int id) const;
  /// Tree rebuilds so far (statistics and tests).
  int rebuilds() const { return rebuilds_; }

  /// Overflow plus stale tree entries that trigger a rebuild, for n pieces.
  static int overflowLimit(int n);

 private:
  void rebuild();
  void recomputeBox();
  void maybeRebuild();
  int requireId(int id, const char* what) const;

  std::vector<Piece> pieces_;
  std::string name_;
  Eigen::AlignedBox3d box_;
  AabbTree tree_;
  std::vector<int> tree_ids_;  ///< tree entry -> piece id
  std::vector<int> id_of_;     ///< index -> id
  std::vector<int> index_of_;  ///< id -> index (-1: removed)
  std::vector<char> in_tree_;  ///< id -> the tree holds its current box
  std::vector<int> overflow_;  ///< ids of pieces not in the tree (added or moved since the build)
  int stale_ = 0;              ///< tree entries of removed or moved pieces
  int rebuilds_ = 0;
  /// Moved pieces: id -> (geometry as added, current pose).
  struct Moved {
    ConvexPolytope reference;
    Eigen::Isometry3d X_WP = Eigen::Isometry3d::Identity();
  };
  std::map<int, Moved> moved_;
};

/// The axis-aligned box holding `box` (given in frame F) placed at pose X_WF.
Eigen::AlignedBox3d transformedBox(const Eigen::AlignedBox3d& box, const Eigen::Isometry3d& X_WF);

}  // namespace mddual::scene
