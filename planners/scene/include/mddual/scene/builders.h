// Robots and worlds built in memory (no files): from vertex and triangle
// arrays, from primitive shapes and from convex point sets. The geometry is
// handled exactly as the loaders handle the same geometry read from a file
// (loaders.h): a mesh goes through the same convexity test (one kConvex piece
// when it is its own hull, else one kTriangle piece per triangle, or its hull
// with LoadOptions::mesh_convex_hull), the same degenerate-triangle rules and
// warnings; boxes, cylinders and spheres are boxPiece, cylinderPiece and
// spherePiece with LoadOptions::primitive_tolerance. So a mesh written to a
// file and loaded gives the pieces these builders give for its arrays, up to
// the loader's 32-bit float storage of coordinates, Piece::origin, and the
// shift of recentring: the mean of the array's rows here, the mean of the
// vertices assimp keeps for a file (which may repeat a corner once per face
// normal).
//
// Frames: every shape is posed at X_OS in its owner's frame O (the body frame
// R of a robot, the world frame W of a world).
//
// Errors: SceneError (an InvalidInputError) naming the owner, the shape (its
// index in the list) and the element: an empty vertex or triangle array, a
// triangle index outside the vertex array, a NaN or infinite coordinate, a
// non-positive size, an empty point set or one that spans no polytope.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "mddual/scene/loaders.h"
#include "mddual/scene/scene.h"

namespace mddual::scene {

/// Vertex array: row i is vertex i (x, y, z) in the shape's frame S.
using VertexArray = Eigen::Matrix<double, Eigen::Dynamic, 3>;
/// Triangle array: row t holds the vertex indices (from 0) of triangle t's
/// three corners.
using TriangleArray = Eigen::Matrix<int, Eigen::Dynamic, 3>;

/// One shape of a body or world built in memory.
struct Shape {
  enum class Kind : std::uint8_t {
    kBox,       ///< `size` (full side lengths), centred on the origin of S
    kCylinder,  ///< `radius`, `length` along the z axis of S, centred on its origin
    kSphere,    ///< `radius`, centred on the origin of S
    kMesh,      ///< `vertices`, `triangles` (convexity as the mesh loader)
    kConvex,    ///< the convex hull of `points` (one kConvex piece)
  };
  Kind kind = Kind::kBox;
  Eigen::Isometry3d X_OS = Eigen::Isometry3d::Identity();  ///< pose of the shape in the owner frame O
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  double radius = 0.0;
  double length = 0.0;
  VertexArray vertices;
  TriangleArray triangles;
  std::vector<Eigen::Vector3d> points;

  static Shape box(const Eigen::Vector3d& size, const Eigen::Isometry3d& X_OS = Eigen::Isometry3d::Identity());
  static Shape cylinder(double radius, double length, const Eigen::Isometry3d& X_OS = Eigen::Isometry3d::Identity());
  static Shape sphere(double radius, const Eigen::Isometry3d& X_OS = Eigen::Isometry3d::Identity());
  static Shape mesh(VertexArray vertices, TriangleArray triangles,
                    const Eigen::Isometry3d& X_OS = Eigen::Isometry3d::Identity());
  static Shape convex(std::vector<Eigen::Vector3d> points,
                      const Eigen::Isometry3d& X_OS = Eigen::Isometry3d::Identity());
};

/// The pieces of a mesh given as arrays, in the owner frame O: meshPieces
/// (loaders.h) on this geometry, with scale 1; every vertex v becomes X_OM * (v
/// - shift), shift the mean of all rows of `vertices` when
/// options.recentre_mesh, else zero. `name` names the mesh in messages and
/// prefixes the pieces' origins ("<name>: triangle 3", "<name>: convex").
/// `info` receives what meshPieces reports. Throws SceneError (see the file
/// comment, and meshPieces for the geometry it refuses).
std::vector<Piece> meshArrayPieces(const VertexArray& vertices, const TriangleArray& triangles,
                                   const Eigen::Isometry3d& X_OM, const LoadOptions& options, const std::string& name,
                                   MeshInfo* info = nullptr);

/// One kConvex piece: the convex hull of points_S posed at X_OS (a flat point
/// set gives a flat piece). Throws SceneError naming `origin` for an empty
/// set, a non-finite point or pose, or points that span no polytope (all
/// equal or collinear).
Piece convexPiece(const std::vector<Eigen::Vector3d>& points_S, const Eigen::Isometry3d& X_OS, std::string origin);

/// The pieces of the shapes, in the owner frame O, in order. Meshes are never
/// recentred here (as meshes inside a URDF). Origins: "<owner>: shape i
/// (box)", "<owner>: shape i (mesh): triangle t", ... `warnings` (if not null)
/// receives the meshes' load warnings (MeshInfo::warnings).
std::vector<Piece> shapePieces(const std::vector<Shape>& shapes, const std::string& owner,
                               const LoadOptions& options = {}, std::vector<std::string>* warnings = nullptr);

/// A robot made of the shapes (frame R). Throws SceneError for no shapes.
RigidBody buildBody(const std::vector<Shape>& shapes, const std::string& name, const LoadOptions& options = {},
                    std::vector<std::string>* warnings = nullptr);
/// A world made of the shapes (frame W); no shapes is an empty (free) world.
World buildWorld(const std::vector<Shape>& shapes, const std::string& name, const LoadOptions& options = {},
                 std::vector<std::string>* warnings = nullptr);

/// A robot from one mesh, as loadBody on a mesh file holding it (recentred
/// when options.recentre_mesh). Origins "<name>: triangle t" / "<name>: convex".
RigidBody bodyFromMesh(const VertexArray& vertices, const TriangleArray& triangles, const std::string& name,
                       const LoadOptions& options = {}, std::vector<std::string>* warnings = nullptr);
/// A world from one mesh, as loadWorld on a mesh file holding it (never
/// recentred).
World worldFromMesh(const VertexArray& vertices, const TriangleArray& triangles, const std::string& name,
                    const LoadOptions& options = {}, std::vector<std::string>* warnings = nullptr);

/// A robot whose pieces are the convex hulls of the point sets (frame R),
/// origins "<name>: piece i".
RigidBody bodyFromConvexSets(const std::vector<std::vector<Eigen::Vector3d>>& sets, const std::string& name);
/// A world whose pieces are the convex hulls of the point sets (frame W).
World worldFromConvexSets(const std::vector<std::vector<Eigen::Vector3d>>& sets, const std::string& name);

}  // namespace mddual::scene
