// Meshes through assimp, read the way OMPL.app reads them, turned into one
// convex piece (when the mesh is its own hull) or into triangle pieces.
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cmath>
#include <system_error>

#include "mddual/scene/loaders.h"
#include "scene_detail.h"

namespace mddual::scene {
namespace {

/// OMPL.app's import flags (RigidBodyGeometry::addRobotMesh /
/// addEnvironmentMesh). GenNormals and JoinIdenticalVertices decide which
/// vertices the mesh keeps, hence its mean vertex: keep them identical.
constexpr unsigned int kAssimpFlags = aiProcess_GenNormals | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                      aiProcess_SortByPType | aiProcess_OptimizeGraph;

/// A triangle whose doubled area is below this fraction of its longest edge
/// squared (a height under 1e-10 of its length) is degenerate.
constexpr double kDegenerateRatio = 1e-10;
/// Convexity test: distances within kPlaneTolerance of the mesh's size, plus
/// kFloatTolerance of its largest coordinate (assimp stores floats), count as
/// on a plane; areas within kAreaTolerance (relative) as equal.
constexpr double kPlaneTolerance = 1e-6;
constexpr double kFloatTolerance = 5e-7;
constexpr double kAreaTolerance = 1e-5;

Eigen::Matrix4d toEigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
  return out;
}

/// Appends the vertices and triangles under `node`, with `parent` the
/// accumulated transform of its ancestors (OMPL.app's extractVerticesAux and
/// extractTrianglesAux: transform = parent * node).
void collect(const aiScene& scene, const aiNode& node, const Eigen::Matrix4d& parent, detail::MeshData* out) {
  const Eigen::Matrix4d T = parent * toEigen(node.mTransformation);
  // Node transforms are affine (the last row is 0 0 0 1).
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  const Eigen::Vector3d t = T.topRightCorner<3, 1>();
  const auto apply = [&R, &t](const aiVector3D& v) -> Eigen::Vector3d {
    return R * Eigen::Vector3d(static_cast<double>(v.x), static_cast<double>(v.y), static_cast<double>(v.z)) + t;
  };
  for (unsigned int i = 0; i < node.mNumMeshes; ++i) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[i]];
    for (unsigned int v = 0; v < mesh.mNumVertices; ++v) out->vertices.push_back(apply(mesh.mVertices[v]));
    for (unsigned int f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // lines and points are not geometry
      for (int c = 0; c < 3; ++c) out->triangles.push_back(apply(mesh.mVertices[face.mIndices[c]]));
    }
  }
  for (unsigned int c = 0; c < node.mNumChildren; ++c) collect(scene, *node.mChildren[c], T, out);
}

double triangleDoubleArea(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return (b - a).cross(c - a).norm();
}

bool degenerate(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return !(triangleDoubleArea(a, b, c) > kDegenerateRatio * longest);
}

/// Surface area of a hull (a flat hull: the area of its polygon, once).
double hullArea(const ConvexPolytope& hull) {
  double area = 0.0;
  const int faces = hull.isFlat() ? 1 : hull.numFaces();
  for (int f = 0; f < faces; ++f) {
    const IndexRange loop = hull.faceVertices(f);
    const Eigen::Vector3d& v0 = hull.vertex(loop[0]);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int i = 1; i + 1 < loop.size(); ++i) sum += (hull.vertex(loop[i]) - v0).cross(hull.vertex(loop[i + 1]) - v0);
    area += 0.5 * sum.norm();
  }
  return area;
}

/// True when the triangles (three corners each, none degenerate) cover the
/// boundary of `hull` exactly: each lies in a supporting plane of the hull
/// and their total area is the hull's.
bool equalsHull(const std::vector<Eigen::Vector3d>& tri, const ConvexPolytope& hull, double plane_tol) {
  double area = 0.0;
  int hint = -1;
  for (std::size_t t = 0; t < tri.size(); t += 3) {
    const Eigen::Vector3d& a = tri[t];
    const Eigen::Vector3d& b = tri[t + 1];
    const Eigen::Vector3d& c = tri[t + 2];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    area += 0.5 * n.norm();
    const Eigen::Vector3d u = n.normalized();
    bool on_boundary = false;
    for (const double sign : {1.0, -1.0}) {
      const Eigen::Vector3d s = sign * u;
      hint = hull.supportVertex(s, hint);
      const double h = s.dot(hull.vertex(hint));
      if (s.dot(a) >= h - plane_tol && s.dot(b) >= h - plane_tol && s.dot(c) >= h - plane_tol) {
        on_boundary = true;
        break;
      }
    }
    if (!on_boundary) return false;
  }
  const double hull_area = hullArea(hull);
  return std::abs(area - hull_area) <= kAreaTolerance * hull_area;
}

}  // namespace

namespace detail {

void requireFile(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw SceneError(display(file) + ": file not found");
  if (!std::filesystem::is_regular_file(file, ec)) throw SceneError(display(file) + ": not a regular file");
}

void requirePositiveTolerance(double tolerance, const std::string& what) {
  if (!std::isfinite(tolerance) || tolerance <= 0.0) {
    throw SceneError(what + ": the primitive tolerance must be a finite number > 0 (got " + std::to_string(tolerance) +
                     ")");
  }
}

MeshData readMesh(const std::filesystem::path& file) {
  requireFile(file);
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(file.string(), kAssimpFlags);
  if (scene == nullptr) {
    throw SceneError(display(file) + ": cannot read the mesh (assimp: " + importer.GetErrorString() + ")");
  }
  if (!scene->HasMeshes() || scene->mRootNode == nullptr) {
    throw SceneError(display(file) + ": the file contains no mesh");
  }
  MeshData data;
  collect(*scene, *scene->mRootNode, Eigen::Matrix4d::Identity(), &data);
  for (const Eigen::Vector3d& v : data.vertices) {
    if (!v.allFinite()) throw SceneError(display(file) + ": a vertex has a non-finite coordinate");
  }
  if (data.triangles.empty()) throw SceneError(display(file) + ": the mesh has no triangles");
  return data;
}

std::vector<Piece> meshPiecesWithOrigin(const std::filesystem::path& file, const Eigen::Vector3d& scale,
                                        const Eigen::Isometry3d& X_OM, const LoadOptions& options,
                                        const std::string& origin_prefix, MeshInfo* info) {
  if (!scale.allFinite()) throw SceneError(display(file) + ": the mesh scale has a non-finite entry");
  if (!X_OM.matrix().allFinite()) throw SceneError(display(file) + ": the mesh pose has a non-finite entry");
  MeshData data = readMesh(file);
  MeshInfo local;
  MeshInfo& out = info != nullptr ? *info : local;
  out = MeshInfo{};
  out.vertices = static_cast<int>(data.vertices.size());
  out.triangles = static_cast<int>(data.triangles.size() / 3);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : data.vertices) mean += scale.cwiseProduct(v);
  mean /= static_cast<double>(std::max<std::size_t>(1, data.vertices.size()));
  out.mean_vertex = mean;
  out.shift = options.recentre_mesh ? mean : Eigen::Vector3d::Zero();

  // Posed, non-degenerate triangles.
  std::vector<Eigen::Vector3d> tri;
  std::vector<int> tri_index;  // index of each kept triangle in the file
  tri.reserve(data.triangles.size());
  for (std::size_t t = 0; t < data.triangles.size(); t += 3) {
    Eigen::Vector3d p[3];
    for (int c = 0; c < 3; ++c)
      p[c] = X_OM * (scale.cwiseProduct(data.triangles[t + static_cast<std::size_t>(c)]) - out.shift);
    if (degenerate(p[0], p[1], p[2])) {
      ++out.degenerate_triangles;
      continue;
    }
    tri.insert(tri.end(), {p[0], p[1], p[2]});
    tri_index.push_back(static_cast<int>(t / 3));
  }
  if (tri.empty()) {
    throw SceneError(display(file) + ": all " + std::to_string(out.triangles) + " triangles are degenerate");
  }

  ConvexPolytope hull;
  try {
    hull = ConvexPolytope::fromPoints(tri);
  } catch (const Error& e) {
    throw SceneError(display(file) + ": cannot build the hull of the mesh: " + e.what());
  }
  Eigen::AlignedBox3d box;
  box.setEmpty();
  double largest = 0.0;
  for (const Eigen::Vector3d& p : tri) {
    box.extend(p);
    largest = std::max(largest, p.cwiseAbs().maxCoeff());
  }
  const double plane_tol = kPlaneTolerance * box.diagonal().norm() + kFloatTolerance * largest;
  out.convex = equalsHull(tri, hull, plane_tol);

  std::vector<Piece> pieces;
  if (out.convex || options.mesh_convex_hull) {
    pieces.push_back(Piece::make(std::move(hull), PieceKind::kConvex, origin_prefix + ": convex"));
    return pieces;
  }
  pieces.reserve(tri_index.size());
  for (std::size_t i = 0; i < tri_index.size(); ++i) {
    const std::vector<Eigen::Vector3d> corners(tri.begin() + static_cast<std::ptrdiff_t>(3 * i),
                                               tri.begin() + static_cast<std::ptrdiff_t>(3 * i + 3));
    try {
      pieces.push_back(Piece::make(ConvexPolytope::fromPoints(corners), PieceKind::kTriangle,
                                   origin_prefix + ": triangle " + std::to_string(tri_index[i])));
    } catch (const DegenerateGeometryError&) {
      ++out.degenerate_triangles;  // a sliver the hull code calls collinear
    } catch (const Error& e) {
      throw SceneError(display(file) + ": triangle " + std::to_string(tri_index[i]) + ": " + e.what());
    }
  }
  if (pieces.empty()) {
    throw SceneError(display(file) + ": all " + std::to_string(out.triangles) + " triangles are degenerate");
  }
  return pieces;
}

}  // namespace detail

std::vector<Piece> meshPieces(const std::filesystem::path& file, const Eigen::Vector3d& scale,
                              const Eigen::Isometry3d& X_OM, const LoadOptions& options, MeshInfo* info) {
  return detail::meshPiecesWithOrigin(file, scale, X_OM, options, file.filename().string(), info);
}

Eigen::Vector3d meshMeanVertex(const std::filesystem::path& file) {
  const detail::MeshData data = detail::readMesh(file);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : data.vertices) mean += v;
  return mean / static_cast<double>(data.vertices.size());
}

}  // namespace mddual::scene
