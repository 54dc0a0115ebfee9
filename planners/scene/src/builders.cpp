// In-memory builders: the arrays are checked here, then handed to the mesh
// loader's own processing (detail::meshDataPieces) and primitive builders, so
// that memory and files give the same pieces.
#include "mddual/scene/builders.h"

#include <cmath>
#include <utility>

#include "scene_detail.h"

namespace mddual::scene {
namespace {

/// "x", "y" or "z" and why a coordinate is not finite.
std::string badCoordinate(const Eigen::Vector3d& v) {
  const char* axes[3] = {"x", "y", "z"};
  int axis = 0;
  while (axis < 2 && std::isfinite(v[axis])) ++axis;
  return std::string("its ") + axes[axis] + " coordinate is " + (std::isnan(v[axis]) ? "NaN" : "infinite");
}

/// A shape's or mesh's pose in a body: a loader's SceneError naming `where` (the
/// core's requireFinitePose is for query poses, InvalidInputError).
void requireFiniteShapePose(const Eigen::Isometry3d& X, const std::string& where) {
  if (!X.matrix().allFinite()) throw SceneError(where + ": the pose has a non-finite entry");
}

/// The arrays as the mesh loader's data: every vertex, and three corners per
/// triangle. Throws SceneError naming `where` and the bad row.
detail::MeshData meshData(const VertexArray& vertices, const TriangleArray& triangles, const std::string& where) {
  if (vertices.rows() == 0) throw SceneError(where + ": the vertex array is empty");
  if (triangles.rows() == 0) throw SceneError(where + ": the triangle array is empty");
  detail::MeshData data;
  data.vertices.reserve(static_cast<std::size_t>(vertices.rows()));
  for (Eigen::Index i = 0; i < vertices.rows(); ++i) {
    const Eigen::Vector3d v = vertices.row(i).transpose();
    if (!v.allFinite()) throw SceneError(where + ": vertex " + std::to_string(i) + ": " + badCoordinate(v));
    data.vertices.push_back(v);
  }
  data.triangles.reserve(static_cast<std::size_t>(3 * triangles.rows()));
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    for (int c = 0; c < 3; ++c) {
      const int k = triangles(t, c);
      if (k < 0 || k >= vertices.rows()) {
        throw SceneError(where + ": triangle " + std::to_string(t) + ", corner " + std::to_string(c) +
                         ": vertex index " + std::to_string(k) + " is outside [0, " + std::to_string(vertices.rows()) +
                         ")");
      }
      data.triangles.push_back(data.vertices[static_cast<std::size_t>(k)]);
    }
  }
  return data;
}

std::vector<Piece> meshPiecesOf(const VertexArray& vertices, const TriangleArray& triangles,
                                const Eigen::Isometry3d& X_OM, const LoadOptions& options, const std::string& where,
                                std::vector<std::string>* warnings) {
  MeshInfo info;
  std::vector<Piece> pieces = meshArrayPieces(vertices, triangles, X_OM, options, where, &info);
  if (warnings != nullptr) warnings->insert(warnings->end(), info.warnings.begin(), info.warnings.end());
  return pieces;
}

const char* kindName(Shape::Kind kind) {
  switch (kind) {
    case Shape::Kind::kBox: return "box";
    case Shape::Kind::kCylinder: return "cylinder";
    case Shape::Kind::kSphere: return "sphere";
    case Shape::Kind::kMesh: return "mesh";
    case Shape::Kind::kConvex: return "convex";
  }
  return "unknown";
}

std::vector<Piece> setPieces(const std::vector<std::vector<Eigen::Vector3d>>& sets, const std::string& name) {
  std::vector<Piece> pieces;
  pieces.reserve(sets.size());
  for (std::size_t i = 0; i < sets.size(); ++i) {
    pieces.push_back(convexPiece(sets[i], Eigen::Isometry3d::Identity(), name + ": piece " + std::to_string(i)));
  }
  return pieces;
}

}  // namespace

Shape Shape::box(const Eigen::Vector3d& size, const Eigen::Isometry3d& X_OS) {
  Shape s;
  s.kind = Kind::kBox;
  s.size = size;
  s.X_OS = X_OS;
  return s;
}

Shape Shape::cylinder(double radius, double length, const Eigen::Isometry3d& X_OS) {
  Shape s;
  s.kind = Kind::kCylinder;
  s.radius = radius;
  s.length = length;
  s.X_OS = X_OS;
  return s;
}

Shape Shape::sphere(double radius, const Eigen::Isometry3d& X_OS) {
  Shape s;
  s.kind = Kind::kSphere;
  s.radius = radius;
  s.X_OS = X_OS;
  return s;
}

Shape Shape::mesh(VertexArray vertices, TriangleArray triangles, const Eigen::Isometry3d& X_OS) {
  Shape s;
  s.kind = Kind::kMesh;
  s.vertices = std::move(vertices);
  s.triangles = std::move(triangles);
  s.X_OS = X_OS;
  return s;
}

Shape Shape::convex(std::vector<Eigen::Vector3d> points, const Eigen::Isometry3d& X_OS) {
  Shape s;
  s.kind = Kind::kConvex;
  s.points = std::move(points);
  s.X_OS = X_OS;
  return s;
}

std::vector<Piece> meshArrayPieces(const VertexArray& vertices, const TriangleArray& triangles,
                                   const Eigen::Isometry3d& X_OM, const LoadOptions& options, const std::string& name,
                                   MeshInfo* info) {
  requireFiniteShapePose(X_OM, name);
  const detail::MeshData data = meshData(vertices, triangles, name);
  return detail::meshDataPieces(data, name, Eigen::Vector3d::Ones(), X_OM, options, name, info);
}

Piece convexPiece(const std::vector<Eigen::Vector3d>& points_S, const Eigen::Isometry3d& X_OS, std::string origin) {
  requireFiniteShapePose(X_OS, origin);
  if (points_S.empty()) throw SceneError(origin + ": the point set is empty");
  std::vector<Eigen::Vector3d> points;
  points.reserve(points_S.size());
  for (std::size_t i = 0; i < points_S.size(); ++i) {
    if (!points_S[i].allFinite()) {
      throw SceneError(origin + ": point " + std::to_string(i) + ": " + badCoordinate(points_S[i]));
    }
    points.push_back(X_OS * points_S[i]);
  }
  ConvexPolytope hull;
  try {
    hull = ConvexPolytope::fromPoints(points);
  } catch (const Error& e) {
    throw SceneError(origin + ": cannot build the convex hull of its " + std::to_string(points.size()) +
                     " points: " + detail::briefReason(e.what()));
  }
  return Piece::make(std::move(hull), PieceKind::kConvex, std::move(origin));
}

std::vector<Piece> shapePieces(const std::vector<Shape>& shapes, const std::string& owner, const LoadOptions& options,
                               std::vector<std::string>* warnings) {
  detail::requirePositiveTolerance(options.primitive_tolerance, owner);
  LoadOptions mesh_options = options;
  mesh_options.recentre_mesh = false;
  std::vector<Piece> pieces;
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const Shape& s = shapes[i];
    const std::string where = owner + ": shape " + std::to_string(i) + " (" + kindName(s.kind) + ")";
    switch (s.kind) {
      case Shape::Kind::kBox: pieces.push_back(boxPiece(s.size, s.X_OS, where)); break;
      case Shape::Kind::kCylinder:
        pieces.push_back(cylinderPiece(s.radius, s.length, s.X_OS, options.primitive_tolerance, where));
        break;
      case Shape::Kind::kSphere:
        pieces.push_back(spherePiece(s.radius, s.X_OS, options.primitive_tolerance, where));
        break;
      case Shape::Kind::kMesh: {
        std::vector<Piece> mesh = meshPiecesOf(s.vertices, s.triangles, s.X_OS, mesh_options, where, warnings);
        for (Piece& p : mesh) pieces.push_back(std::move(p));
        break;
      }
      case Shape::Kind::kConvex: pieces.push_back(convexPiece(s.points, s.X_OS, where)); break;
    }
  }
  return pieces;
}

RigidBody buildBody(const std::vector<Shape>& shapes, const std::string& name, const LoadOptions& options,
                    std::vector<std::string>* warnings) {
  if (shapes.empty()) throw SceneError("robot '" + name + "': no shapes");
  return RigidBody(shapePieces(shapes, name, options, warnings), name);
}

World buildWorld(const std::vector<Shape>& shapes, const std::string& name, const LoadOptions& options,
                 std::vector<std::string>* warnings) {
  return World(shapePieces(shapes, name, options, warnings), name);
}

RigidBody bodyFromMesh(const VertexArray& vertices, const TriangleArray& triangles, const std::string& name,
                       const LoadOptions& options, std::vector<std::string>* warnings) {
  return RigidBody(meshPiecesOf(vertices, triangles, Eigen::Isometry3d::Identity(), options, name, warnings), name);
}

World worldFromMesh(const VertexArray& vertices, const TriangleArray& triangles, const std::string& name,
                    const LoadOptions& options, std::vector<std::string>* warnings) {
  LoadOptions world_options = options;
  world_options.recentre_mesh = false;
  return World(meshPiecesOf(vertices, triangles, Eigen::Isometry3d::Identity(), world_options, name, warnings), name);
}

RigidBody bodyFromConvexSets(const std::vector<std::vector<Eigen::Vector3d>>& sets, const std::string& name) {
  if (sets.empty()) throw SceneError("robot '" + name + "': no point sets");
  return RigidBody(setPieces(sets, name), name);
}

World worldFromConvexSets(const std::vector<std::vector<Eigen::Vector3d>>& sets, const std::string& name) {
  return World(setPieces(sets, name), name);
}

}  // namespace mddual::scene
