// Scene loaders: URDF files (urdfdom), meshes (assimp) and the primitive
// shapes they contain, turned into the convex pieces of scene.h.
//
// Frames: a body's pieces are in its body frame R (for a URDF, the root
// link's frame; for a mesh file, the file's frame, optionally shifted so that
// the mean vertex is the origin); a world's pieces are in the world frame W
// (a URDF world's root link frame, a mesh world's file frame). The builders
// below take the pose X_OS of the shape's own frame S in the owner frame O
// (R or W) and return pieces in O.
//
// Conventions shared with OMPL.app, so that its meshes give the same geometry:
//   - assimp reads meshes with aiProcess_GenNormals | aiProcess_Triangulate |
//     aiProcess_JoinIdenticalVertices | aiProcess_SortByPType |
//     aiProcess_OptimizeGraph, and every node's transform (accumulated from
//     the root) is applied to its meshes. For COLLADA files this includes the
//     rotation assimp puts on the root node to convert a Z_UP (or X_UP) file
//     to Y-up: a Z_UP point (x, y, z) is read as (x, z, -y).
//   - only faces with three indices are geometry (lines and points are not),
//     but the mean vertex (for recentring) is taken over every vertex of every
//     mesh the node tree references, as OMPL.app's sceneCenter does.
#pragma once

#include <Eigen/Geometry>
#include <filesystem>
#include <string>
#include <vector>

#include "mddual/scene/scene.h"

namespace mddual::scene {

/// Default of LoadOptions::mesh_convex_tolerance, relative to a mesh's
/// bounding-box diagonal. 1e-4 (0.1 mm on a 1 m part) is far above the
/// round-off of the formats meshes come in (32-bit floats: 6e-8 relative;
/// ASCII STL's six significant digits: 5e-7) and of exporters that leave
/// quads slightly non-planar (the convex_field rocks were off by up to 3e-4), and far
/// below what planning resolves (OMPL checks motions every 1e-2 of the space's
/// extent by default). The hull is never smaller than the mesh, so taking it
/// only adds a skin at most this thick: no collision is lost, while a closed
/// mesh loaded as triangles is hollow and loses every body inside it.
constexpr double kDefaultMeshConvexTolerance = 1e-4;
/// Largest LoadOptions::mesh_convex_tolerance: beyond 1% of its size a mesh is
/// not "convex up to round-off"; ask for its hull (mesh_convex_hull) instead.
constexpr double kMaxMeshConvexTolerance = 1e-2;

struct LoadOptions {
  /// Curved primitives (cylinders, spheres) become circumscribed polytopes
  /// whose surface is within this distance of the true surface (world units,
  /// > 0).
  double primitive_tolerance = 1e-3;
  /// A non-convex mesh becomes its convex hull (one piece, the hull of every
  /// corner, degenerate triangles' included) instead of its triangles.
  bool mesh_convex_hull = false;
  /// A mesh is loaded as one convex piece, its hull, when the hull differs
  /// from it by at most this fraction of its bounding-box diagonal (see
  /// meshPieces for the exact test); in [0, kMaxMeshConvexTolerance]. 0 keeps
  /// only the round-off allowance (1e-6 of the diagonal plus 5e-7 of the
  /// largest coordinate). The cfg key: mesh_convex_tolerance in [problem].
  double mesh_convex_tolerance = kDefaultMeshConvexTolerance;
  /// loadBody and meshPieces: shift a mesh so that the mean of its vertices is
  /// the origin (OMPL.app's robot convention: the state is the pose of that
  /// point). Worlds and meshes inside a URDF are never shifted.
  bool recentre_mesh = false;
};

/// What meshPieces found in a mesh file.
struct MeshInfo {
  int vertices = 0;   ///< vertices of the meshes referenced by the node tree
  int triangles = 0;  ///< triangles read
  /// Triangles that are not pieces: zero area, repeated or collinear corners,
  /// or (loaded as triangles) slivers the hull code cannot make a polytope of.
  int degenerate_triangles = 0;
  bool convex = false;  ///< the mesh equals its convex hull within the tolerance (one kConvex piece)
  /// Every edge is shared by exactly two triangles (corners matched by exact
  /// position; degenerate triangles count, those with a repeated corner not):
  /// the mesh encloses a volume. Loaded as triangles, such a mesh is hollow,
  /// and `warnings` says so.
  bool closed = false;
  /// Closed, and each edge is used once in each direction (the triangles'
  /// windings agree).
  bool oriented = false;
  /// The hull that decides convexity could not be built (a qhull precision
  /// error): the mesh was loaded as triangles, and `warnings` says so.
  bool hull_failed = false;
  /// Loaded as triangles: the file indices of the triangles skipped (sorted);
  /// loaded as one convex piece because the mesh is convex: those of the
  /// skipped triangles that leave its hull (the others are inside the solid
  /// piece). Empty with mesh_convex_hull (the hull of every corner, the
  /// degenerate triangles' too).
  std::vector<int> skipped_triangles;
  /// What the user should know about the load, each naming the file: the
  /// skipped triangles (with the largest distance by which they could change
  /// the geometry), a convexity check that fell back to triangles.
  std::vector<std::string> warnings;
  /// Mean of the vertices, scaled, in the mesh file's frame (before the shift
  /// of recentring and before X_OM).
  Eigen::Vector3d mean_vertex = Eigen::Vector3d::Zero();
  /// The shift applied before X_OM (mean_vertex when recentred, else zero).
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();
};

/// How the meshes of a load went (loadBody, loadWorld; a URDF's mesh
/// elements each count).
struct MeshCounts {
  int meshes = 0;  ///< mesh files (or URDF mesh elements) loaded
  int convex = 0;  ///< loaded as one convex piece (convex within the tolerance, or mesh_convex_hull)
  int soups = 0;   ///< loaded as triangle pieces
  /// Of the soups, the closed ones (MeshInfo::closed): hollow, so a body
  /// entirely inside one does not collide with it.
  int closed_soups = 0;
  /// Counts one mesh loaded with `info` (as its hull when `hull`).
  void add(const MeshInfo& info, bool hull);
  MeshCounts& operator+=(const MeshCounts& o);
};

/// Loads a robot: a URDF (.urdf, every collision element of every link, the
/// joints taken as fixed at their origins) or a mesh file (any format assimp
/// reads: .stl .obj .dae .ply ...). Pieces are in the body frame R (the URDF's
/// root link frame, or the mesh file's frame shifted by -mean vertex when
/// options.recentre_mesh). `warnings` (if not null) receives the meshes' load
/// warnings (MeshInfo::warnings); `counts` (if not null) has the meshes
/// added. Throws SceneError naming the file and the element when the file is
/// unreadable, malformed (an XML file nested deeper than 256 elements
/// included), unsupported or has no collision geometry, or when an option is
/// out of range.
RigidBody loadBody(const std::filesystem::path& file, const LoadOptions& options = {},
                   std::vector<std::string>* warnings = nullptr, MeshCounts* counts = nullptr);

/// Loads a static world (URDF or mesh file, as loadBody but never recentred);
/// pieces in the world frame W. A URDF world without collision geometry is an
/// empty (free) world; a mesh file must contain triangles.
World loadWorld(const std::filesystem::path& file, const LoadOptions& options = {},
                std::vector<std::string>* warnings = nullptr, MeshCounts* counts = nullptr);

/// The pieces of a mesh file in the owner frame O: every vertex v of the file
/// (node transforms applied) becomes X_OM * (scale .* v - shift), where shift
/// is the mean of the scaled vertices when options.recentre_mesh, else zero.
///
/// A mesh equal to its convex hull H up to e = t * D + 5e-7 * M (t =
/// max(options.mesh_convex_tolerance, 1e-6), D the bounding-box diagonal of
/// its triangles, M their largest coordinate: assimp stores floats) is one
/// kConvex piece, H; any other mesh is one kTriangle piece per triangle, or H
/// when options.mesh_convex_hull. Piece::origin is "<file name>: triangle i"
/// (i counts the file's triangles from 0) or "<file name>: convex". The test:
///   1. every triangle has its three corners within e of one supporting plane
///      of H (a plane of H's faces, or H's support plane along the triangle's
///      normal): the triangle, inside H, is within e of H's boundary;
///   2. the triangles cover H's boundary: either the mesh is closed and
///      consistently oriented (MeshInfo::oriented) and the volume it encloses
///      is more than e times H's surface area A (at least the volume of H's
///      skin of depth e) and at least H's volume minus e * A; or their total
///      area is A within a relative 1e-5 (meshes whose faces are split with
///      T-junctions, which are not closed by shared edges, and bodies thinner
///      than about 2e).
/// H always holds the mesh. When 2 holds by volume, every point of H that the
/// mesh does not enclose is within e of H's boundary: by 1 the mesh does not
/// reach H's points deeper than e, which form one convex region, so they are
/// all inside the mesh or all outside, and the enclosed volume, larger than
/// the skin's, puts them inside. By area, the mesh's surface is as large as
/// H's and lies within e of it (a hole would show as missing area).
/// A closed mesh (MeshInfo::closed) loaded as triangles is hollow: a warning
/// names the file and says so.
///
/// Never a failed load for geometry that OMPL.app accepts:
///   - a triangle that is not a polytope (height below 1e-10 of its longest
///     edge: zero area, repeated or collinear corners; or a sliver, height at
///     most 1e-6 of its longest edge, that the hull code rejects) is skipped,
///     counted in MeshInfo::degenerate_triangles and, when the mesh is loaded
///     as triangles, listed in a warning with its index and the largest
///     distance a skipped triangle extends from its longest edge; when it is
///     loaded as one convex piece because it is convex, a skipped triangle
///     inside the piece is covered by it, and one that leaves it is listed in
///     a warning with a lower bound of the distance by which it does;
///   - when the hull that only decides convexity cannot be built (qhull's
///     precision errors on large, nearly coplanar meshes), the mesh is loaded
///     as triangles (exact, only slower if it was convex) and a warning says
///     so. A mesh with a triangle that has corners beyond both sides of its
///     plane is not convex, which is found without a hull.
///
/// Throws SceneError naming the file (and the step: the assimp error, the
/// vertex, the triangle, the hull) for a missing, unreadable or unsupported
/// file, a scale with a non-finite or zero entry, a corner scaled and posed
/// beyond defaults::kMaxCoordinate, a COLLADA file nested deeper than 256 elements, a vertex that is NaN
/// or overflows assimp's 32-bit floats (|x| > 3.4e38), a file without
/// triangles or none of whose triangles is a polytope, a triangle that is no
/// sliver but that the hull code rejects (a small triangle far from the
/// origin: skipping it would open a hole), a hull asked for by
/// options.mesh_convex_hull that cannot be built, and a
/// mesh_convex_tolerance that is not a number in [0, kMaxMeshConvexTolerance].
std::vector<Piece> meshPieces(const std::filesystem::path& file, const Eigen::Vector3d& scale,
                              const Eigen::Isometry3d& X_OM, const LoadOptions& options, MeshInfo* info = nullptr);

/// The mean of a mesh file's vertices in its own frame (node transforms
/// applied, no scale): OMPL.app's robot centre. Throws as meshPieces.
Eigen::Vector3d meshMeanVertex(const std::filesystem::path& file);

/// A box with full side lengths `size` (all > 0), centred on the origin of
/// its frame B, posed at X_OB: one kConvex piece with 8 vertices, frame O.
Piece boxPiece(const Eigen::Vector3d& size, const Eigen::Isometry3d& X_OB, std::string origin);

/// A cylinder of `radius` along the z axis of its frame C, from z = -length/2
/// to +length/2, posed at X_OC. Circumscribed: a prism over the regular
/// k-gon whose edges touch the circle (vertices at radius / cos(pi/k)), with
/// the fewest k >= 8 such that radius / cos(pi/k) - radius <= tolerance. The
/// caps are exact. One kConvex piece (2k vertices), frame O.
Piece cylinderPiece(double radius, double length, const Eigen::Isometry3d& X_OC, double tolerance, std::string origin);

/// A sphere of `radius` centred on the origin of its frame S, posed at X_OS.
/// Circumscribed: a geodesic polyhedron (each icosahedron face cut into n^2
/// triangles, points projected to the unit sphere), scaled by radius / d, d
/// the smallest distance from the centre to a face plane of its hull, so that
/// every face plane is at distance >= radius; n is the smallest frequency for
/// which the vertices (at radius / d) are within `tolerance` of the sphere.
/// One kConvex piece (10 n^2 + 2 vertices), frame O.
Piece spherePiece(double radius, const Eigen::Isometry3d& X_OS, double tolerance, std::string origin);

/// Sides k of cylinderPiece's prism for this radius and tolerance (throws
/// SceneError above 20000: the tolerance is too small for the radius).
int cylinderSides(double radius, double tolerance);

}  // namespace mddual::scene
