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

/// The static environment: pieces in the world frame W and a broad phase.
class World {
 public:
  World() = default;
  /// An empty world is allowed (free space).
  World(std::vector<Piece> pieces, std::string name);

  const std::vector<Piece>& pieces() const { return pieces_; }
  const std::string& name() const { return name_; }
  /// Bounding box of all pieces (empty box for an empty world).
  const Eigen::AlignedBox3d& box() const { return box_; }
  /// Appends the indices of the pieces whose bounding boxes meet `query_W`.
  void candidates(const Eigen::AlignedBox3d& query_W, std::vector<int>* out) const { tree_.query(query_W, out); }

 private:
  std::vector<Piece> pieces_;
  std::string name_;
  Eigen::AlignedBox3d box_;
  AabbTree tree_;
};

/// The axis-aligned box holding `box` (given in frame F) placed at pose X_WF.
Eigen::AlignedBox3d transformedBox(const Eigen::AlignedBox3d& box, const Eigen::Isometry3d& X_WF);

}  // namespace mddual::scene
