// Meshes through assimp, read the way OMPL.app reads them, turned into one
// convex piece (when the mesh is its own hull) or into triangle pieces.
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cmath>
#include <limits>
#include <sstream>
#include <system_error>

#include "mddual/defaults.h"
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
/// Convexity test: distances within the mesh_convex_tolerance of the mesh's
/// size, never less than kPlaneTolerance of it, plus kFloatTolerance of its
/// largest coordinate (assimp stores floats), count as on a plane; areas
/// within kAreaTolerance (relative) as equal.
constexpr double kPlaneTolerance = 1e-6;
constexpr double kFloatTolerance = 5e-7;
constexpr double kAreaTolerance = 1e-5;
/// assimp stores vertex coordinates as 32-bit floats: a coordinate beyond
/// this (FLT_MAX, about 3.4e38) in the file is read as infinity.
constexpr double kFloatMax = static_cast<double>(std::numeric_limits<float>::max());
/// floatRoundingWarning's threshold: a rounding above 1e-4 of the mesh's size
/// (a 1 m part rounded by more than 0.1 mm: coordinates beyond about 1,700 m;
/// a 100 m building beyond about 170 km).
constexpr double kFloatRoundingWarnRel = 1e-4;
/// Before it builds the hull, the convexity test looks for a witness of
/// non-convexity (a triangle with mesh points beyond both sides of its plane)
/// in at most this many point-plane evaluations (about 20 ms): a non-convex
/// mesh, the common case, then never reaches qhull.
constexpr std::size_t kWitnessBudget = std::size_t{1} << 24;
/// A triangle whose smallest height is below twice the plane tolerance (its
/// plane's tilt within the tolerance is above 30 degrees) is no witness.
constexpr double kMaxWitnessSlope = 0.5;
/// A triangle the hull code rejects is a sliver, skipped, when its height is
/// at most this fraction of its longest edge. The core's flatness test
/// resolves a triangle's plane only to about 1e-16 / (height / edge)^2 of its
/// size, so it rejects slivers up to a few 1e-7; skipping one moves the
/// surface by at most its height (see the triangle loop below).
constexpr double kSliverRatio = 1e-6;
/// Warnings list at most this many triangle indices.
constexpr std::size_t kMaxListedTriangles = 10;
/// A hull error quoted in a warning or an error is cut to its first line and
/// at most this many characters (qhull's reports run to kilobytes).
constexpr std::size_t kMaxReasonChars = 200;

Eigen::Matrix4d toEigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
  return out;
}

/// A vertex as assimp read it that is not finite: why, in words. `index`
/// counts the vertices in the order they are read.
std::string nonFiniteVertex(const std::filesystem::path& file, std::size_t index, const aiVector3D& v) {
  const char* axes = "xyz";
  const float coordinates[3] = {v.x, v.y, v.z};
  int axis = 0;
  while (axis < 2 && std::isfinite(coordinates[axis])) ++axis;
  const std::string where = detail::display(file) + ": vertex " + std::to_string(index) + " (as assimp numbers them)";
  if (std::isnan(coordinates[axis])) return where + ": its " + axes[axis] + " coordinate is NaN";
  std::ostringstream limit;
  limit << kFloatMax;
  return where + ": its " + axes[axis] + " coordinate overflows the 32-bit floats the mesh reader (assimp) uses " +
         "(|" + axes[axis] + "| > " + limit.str() + "), or is infinite in the file";
}

/// Appends the vertices and triangles of the node tree under `root` (OMPL.app's
/// extractVerticesAux and extractTrianglesAux: a node's transform is its
/// parent's times its own). Depth first with an explicit stack, so a deep node
/// tree cannot overflow the call stack. Throws SceneError for a vertex or a
/// transform that is not finite.
void collect(const aiScene& scene, const aiNode& root, const std::filesystem::path& file, detail::MeshData* out) {
  std::vector<std::pair<const aiNode*, Eigen::Matrix4d>> stack = {{&root, Eigen::Matrix4d::Identity()}};
  while (!stack.empty()) {
    const auto [node, parent] = stack.back();
    stack.pop_back();
    const Eigen::Matrix4d T = parent * toEigen(node->mTransformation);
    if (!T.allFinite()) {
      throw SceneError(detail::display(file) + ": node " + detail::quote(node->mName.C_Str()) +
                       ": its transform (composed with its parents') has a non-finite entry");
    }
    // Node transforms are affine (the last row is 0 0 0 1).
    const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
    const Eigen::Vector3d t = T.topRightCorner<3, 1>();
    const auto apply = [&R, &t](const aiVector3D& v) -> Eigen::Vector3d {
      return R * Eigen::Vector3d(static_cast<double>(v.x), static_cast<double>(v.y), static_cast<double>(v.z)) + t;
    };
    for (unsigned int i = 0; i < node->mNumMeshes; ++i) {
      const aiMesh& mesh = *scene.mMeshes[node->mMeshes[i]];
      for (unsigned int v = 0; v < mesh.mNumVertices; ++v) {
        // Checked before the transform, which would spread a NaN to every axis.
        const aiVector3D& p = mesh.mVertices[v];
        if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) {
          throw SceneError(nonFiniteVertex(file, out->vertices.size(), p));
        }
        out->vertices.push_back(apply(p));
      }
      for (unsigned int f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        if (face.mNumIndices != 3) continue;  // lines and points are not geometry
        for (int c = 0; c < 3; ++c) out->triangles.push_back(apply(mesh.mVertices[face.mIndices[c]]));
      }
    }
    // Children pushed last first, so they are visited in order.
    for (unsigned int c = node->mNumChildren; c-- > 0;) stack.emplace_back(node->mChildren[c], T);
  }
}

double triangleDoubleArea(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return (b - a).cross(c - a).norm();
}

double longestEdgeSquared(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
}

bool degenerate(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return !(triangleDoubleArea(a, b, c) > kDegenerateRatio * longestEdgeSquared(a, b, c));
}

/// The triangle's height over its longest edge (0 for coincident corners):
/// every point of the triangle is within this distance of that edge.
double heightOverLongestEdge(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double longest = std::sqrt(longestEdgeSquared(a, b, c));
  return longest > 0.0 ? triangleDoubleArea(a, b, c) / longest : 0.0;
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

/// Volume of a hull that is not flat (faces as pyramids from its centroid).
double hullVolume(const ConvexPolytope& hull) {
  double volume = 0.0;
  const Eigen::Vector3d& c = hull.centroid();
  for (int f = 0; f < hull.numFaces(); ++f) {
    const IndexRange loop = hull.faceVertices(f);
    const Eigen::Vector3d& v0 = hull.vertex(loop[0]);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int i = 1; i + 1 < loop.size(); ++i) sum += (hull.vertex(loop[i]) - v0).cross(hull.vertex(loop[i + 1]) - v0);
    volume += 0.5 * sum.norm() * (hull.faceOffset(f) - hull.faceNormal(f).dot(c)) / 3.0;
  }
  return volume;
}

/// The volume the triangles enclose, signed (positive when they wind
/// counter-clockwise seen from outside); meaningful for a closed, oriented
/// mesh. Taken about `o` (a point near the mesh) to keep round-off small.
double signedVolume(const std::vector<Eigen::Vector3d>& tri, const Eigen::Vector3d& o) {
  double six = 0.0;
  for (std::size_t t = 0; t < tri.size(); t += 3) six += (tri[t] - o).dot((tri[t + 1] - o).cross(tri[t + 2] - o));
  return six / 6.0;
}

/// True when the corners all lie within plane_tol below the plane n . x = h.
bool nearPlane(const Eigen::Vector3d* corners, const Eigen::Vector3d& n, double h, double plane_tol) {
  return n.dot(corners[0]) >= h - plane_tol && n.dot(corners[1]) >= h - plane_tol && n.dot(corners[2]) >= h - plane_tol;
}

bool lessXyz(const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
}

/// The distinct positions among `points`, sorted (lessXyz).
std::vector<Eigen::Vector3d> distinctPositions(const std::vector<Eigen::Vector3d>& points) {
  std::vector<Eigen::Vector3d> unique = points;
  std::sort(unique.begin(), unique.end(), lessXyz);
  unique.erase(std::unique(unique.begin(), unique.end()), unique.end());
  return unique;
}

/// The index of `p` in `unique` (distinctPositions), or -1.
int positionId(const std::vector<Eigen::Vector3d>& unique, const Eigen::Vector3d& p) {
  const auto it = std::lower_bound(unique.begin(), unique.end(), p, lessXyz);
  return it != unique.end() && *it == p ? static_cast<int>(it - unique.begin()) : -1;
}

/// Finds, for each triangle, a supporting plane of the hull that its three
/// corners are within plane_tol of (then the triangle, which lies inside the
/// hull, is within plane_tol of the hull's boundary). Tried in turn: the
/// support planes along the triangle's normal (exact and fast for a mesh
/// whose faces are planar); the hull faces found last for triangles at the
/// same corners, and the hull faces at the corners that are hull vertices
/// (for a face made of many slightly tilted triangles, whose hull has many
/// small faces); every face of the hull (charged to kWitnessBudget). Returns
/// the index of the first triangle without one, or -1.
int firstTriangleOffHull(const std::vector<Eigen::Vector3d>& tri, const ConvexPolytope& hull, double plane_tol) {
  const std::vector<Eigen::Vector3d> unique = distinctPositions(tri);
  // The hull's vertices are input points, equal to the corners they come from.
  std::vector<int> hull_vertex(unique.size(), -1);
  for (int v = 0; v < hull.numVertices(); ++v) {
    const int id = positionId(unique, hull.vertex(v));
    if (id >= 0) hull_vertex[static_cast<std::size_t>(id)] = v;
  }
  std::vector<int> last_face(unique.size(), -1);
  const auto nearFace = [&](const Eigen::Vector3d* corners, int f) {
    return nearPlane(corners, hull.faceNormal(f), hull.faceOffset(f), plane_tol);
  };
  std::size_t budget = kWitnessBudget;
  int hint = -1;
  for (std::size_t t = 0; t < tri.size(); t += 3) {
    const Eigen::Vector3d* corners = &tri[t];
    const Eigen::Vector3d u = (corners[1] - corners[0]).cross(corners[2] - corners[0]).normalized();
    bool found = false;
    for (const double sign : {1.0, -1.0}) {
      const Eigen::Vector3d s = sign * u;
      hint = hull.supportVertex(s, hint);
      found = found || nearPlane(corners, s, s.dot(hull.vertex(hint)), plane_tol);
    }
    if (found) continue;
    if (hull.isFlat()) return static_cast<int>(t / 3);
    std::size_t ids[3];
    for (int c = 0; c < 3; ++c) ids[c] = static_cast<std::size_t>(positionId(unique, corners[c]));
    int face = -1;
    for (int c = 0; c < 3 && face < 0; ++c) {
      if (last_face[ids[c]] >= 0 && nearFace(corners, last_face[ids[c]])) face = last_face[ids[c]];
    }
    for (int c = 0; c < 3 && face < 0; ++c) {
      if (hull_vertex[ids[c]] < 0) continue;
      for (const int f : hull.vertexFaces(hull_vertex[ids[c]])) {
        if (nearFace(corners, f)) {
          face = f;
          break;
        }
      }
    }
    const auto faces = static_cast<std::size_t>(hull.numFaces());
    if (face < 0 && faces <= budget) {
      budget -= faces;
      for (int f = 0; f < hull.numFaces() && face < 0; ++f) {
        if (nearFace(corners, f)) face = f;
      }
    }
    if (face < 0) return static_cast<int>(t / 3);
    for (const std::size_t id : ids) last_face[id] = face;
  }
  return -1;
}

/// True when the triangles cover the boundary of the (built) hull: by volume
/// for a closed, oriented mesh that is not thin, else by area (see
/// meshPieces in loaders.h).
bool coversHull(const std::vector<Eigen::Vector3d>& tri, const ConvexPolytope& hull, double plane_tol, bool oriented) {
  const double hull_area = hullArea(hull);
  if (oriented && !hull.isFlat()) {
    const double volume = std::abs(signedVolume(tri, hull.centroid()));
    const double skin = plane_tol * hull_area;  // at least the volume of the hull's skin of depth plane_tol
    if (volume > skin && volume >= hullVolume(hull) - skin) return true;
  }
  double area = 0.0;
  for (std::size_t t = 0; t < tri.size(); t += 3) area += 0.5 * (tri[t + 1] - tri[t]).cross(tri[t + 2] - tri[t]).norm();
  return std::abs(area - hull_area) <= kAreaTolerance * hull_area;
}

/// The first triangle found, without a hull, to be within plane_tol of no
/// supporting plane of the hull (-1 if none is found): then the mesh is not
/// convex. Gives up (-1) once kWitnessBudget point-plane evaluations are spent.
///
/// Why it holds: let T have corners a, b, c, unit normal u and smallest height
/// H. If its corners are within e = plane_tol of a supporting plane with unit
/// normal n (every mesh point p has n . p <= n . a + e), then n = cos t u +
/// sin t w (w in T's plane) with |sin t| <= e / H, since n varies by at most e
/// across T, whose extent along any direction of its plane is at least H. On
/// the side cos t > 0, every p then has u . (p - a) <= (e + |p - a| e / H) /
/// sqrt(1 - (e / H)^2), and symmetrically for cos t < 0. Mesh points beyond
/// that bound on both sides of T's plane leave n no side. (Tilting T's plane
/// matters for a tolerance well above the round-off: a face made of small,
/// slightly tilted triangles is convex within e although its points lie
/// farther than e from the plane of one small triangle.)
int nonConvexityWitness(const std::vector<Eigen::Vector3d>& tri, double plane_tol) {
  const std::vector<Eigen::Vector3d> points = distinctPositions(tri);
  std::size_t budget = kWitnessBudget;
  for (std::size_t t = 0; t < tri.size(); t += 3) {
    const Eigen::Vector3d& a = tri[t];
    const Eigen::Vector3d cross = (tri[t + 1] - a).cross(tri[t + 2] - a);
    const double height = cross.norm() / std::sqrt(longestEdgeSquared(a, tri[t + 1], tri[t + 2]));
    const double slope = plane_tol / height;  // largest sin t
    if (!(slope < kMaxWitnessSlope)) continue;
    if (points.size() > budget) return -1;
    budget -= points.size();
    const Eigen::Vector3d u = cross.normalized();
    const double scale = 1.0 / std::sqrt(1.0 - slope * slope);
    bool above = false;
    bool below = false;
    for (const Eigen::Vector3d& p : points) {
      const double s = u.dot(p - a);
      const double bound = (plane_tol + slope * (p - a).norm()) * scale;
      above = above || s > bound;
      below = below || s < -bound;
      if (above && below) return static_cast<int>(t / 3);
    }
  }
  return -1;
}

/// "triangles 3, 17 and 2 more" style list of file indices.
std::string triangleList(const std::vector<int>& indices) {
  std::string s = indices.size() == 1 ? "triangle " : "triangles ";
  for (std::size_t i = 0; i < indices.size() && i < kMaxListedTriangles; ++i) {
    s += (i == 0 ? "" : ", ") + std::to_string(indices[i]);
  }
  if (indices.size() > kMaxListedTriangles) {
    s += " and " + std::to_string(indices.size() - kMaxListedTriangles) + " more";
  }
  return s;
}

/// How far q lies beyond the constraints of `hull`: its face planes, and for
/// a flat hull (faces +-n only) its polygon's edges in the plane; 0 inside.
/// A lower bound of q's distance from the hull, positive exactly outside it.
double beyondHull(const ConvexPolytope& hull, const Eigen::Vector3d& q) {
  double by = 0.0;
  for (int f = 0; f < hull.numFaces(); ++f) by = std::max(by, hull.faceNormal(f).dot(q) - hull.faceOffset(f));
  if (!hull.isFlat() || hull.numFaces() == 0) return by;
  const IndexRange loop = hull.faceVertices(0);
  const Eigen::Vector3d& n = hull.faceNormal(0);
  for (int i = 0; i < loop.size(); ++i) {
    const Eigen::Vector3d& a = hull.vertex(loop[i]);
    const Eigen::Vector3d& b = hull.vertex(loop[(i + 1) % loop.size()]);
    Eigen::Vector3d m = (b - a).cross(n);  // in the plane, across the edge
    const double length = m.norm();
    if (!(length > 0.0)) continue;
    m /= length;
    if (m.dot(hull.centroid() - a) > 0.0) m = -m;  // outward
    by = std::max(by, m.dot(q - a));
  }
  return by;
}

std::string shortNumber(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}

}  // namespace

namespace detail {

std::string briefReason(const std::string& message) {
  std::string line = message.substr(0, message.find('\n'));
  if (line.size() > kMaxReasonChars) line = line.substr(0, kMaxReasonChars) + "...";
  return line;
}

MeshTopology meshTopology(const std::vector<Eigen::Vector3d>& corners) {
  // Vertex ids by exact position.
  const std::vector<Eigen::Vector3d> unique = distinctPositions(corners);
  std::vector<std::size_t> id(corners.size());
  for (std::size_t i = 0; i < corners.size(); ++i) id[i] = static_cast<std::size_t>(positionId(unique, corners[i]));
  // Each edge as (lower id, higher id, 1 when it runs from lower to higher).
  struct Edge {
    std::size_t lo, hi;
    int forward;
  };
  std::vector<Edge> edges;
  edges.reserve(corners.size());
  for (std::size_t t = 0; t + 2 < corners.size(); t += 3) {
    const std::size_t v[3] = {id[t], id[t + 1], id[t + 2]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
    for (int k = 0; k < 3; ++k) {
      const std::size_t a = v[k];
      const std::size_t b = v[(k + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b), a < b ? 1 : 0});
    }
  }
  MeshTopology topology;
  if (edges.empty()) return topology;
  std::sort(edges.begin(), edges.end(),
            [](const Edge& a, const Edge& b) { return a.lo != b.lo ? a.lo < b.lo : a.hi < b.hi; });
  topology.closed = true;
  topology.oriented = true;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    int forward = 0;
    while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) forward += edges[j++].forward;
    if (j - i != 2) topology.closed = false;
    if (j - i != 2 || forward != 1) topology.oriented = false;
    i = j;
  }
  return topology;
}

ConvexityCheck checkConvexity(const std::vector<Eigen::Vector3d>& tri, double plane_tol, HullBuilder build_hull,
                              bool oriented) {
  ConvexityCheck check;
  check.triangle = nonConvexityWitness(tri, plane_tol);
  if (check.triangle >= 0) return check;
  // The hull here only decides whether the mesh is convex: when qhull cannot
  // build it (precision errors on large, nearly coplanar meshes, slivers),
  // the mesh is taken as non-convex, which is always correct (its triangles
  // are its exact surface), only slower to query than one convex piece.
  try {
    check.hull = build_hull(tri);
  } catch (const HullError& e) {
    check.hull_error = briefReason(e.what());
  } catch (const NumericalError& e) {
    check.hull_error = briefReason(e.what());
  } catch (const DegenerateGeometryError& e) {
    check.hull_error = briefReason(e.what());
  }
  if (!check.hull_error.empty()) {
    check.verdict = ConvexityVerdict::kHullFailed;
    return check;
  }
  check.has_hull = true;
  check.triangle = firstTriangleOffHull(tri, check.hull, plane_tol);
  if (check.triangle >= 0) {
    check.verdict = ConvexityVerdict::kOffHull;
  } else if (!coversHull(tri, check.hull, plane_tol, oriented)) {
    check.verdict = ConvexityVerdict::kUncovered;
  } else {
    check.verdict = ConvexityVerdict::kConvex;
    check.convex = true;
  }
  return check;
}

void requireFile(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw SceneError(display(file) + ": file not found");
  if (!std::filesystem::is_regular_file(file, ec)) throw SceneError(display(file) + ": not a regular file");
}

void requireMeshConvexTolerance(double tolerance, const std::string& what) {
  if (!(tolerance >= 0.0 && tolerance <= kMaxMeshConvexTolerance)) {
    std::ostringstream s;
    s << what << ": mesh_convex_tolerance must be a number in [0, " << kMaxMeshConvexTolerance << "] (got " << tolerance
      << "; for a mesh's hull whatever its shape, use mesh_convex_hull)";
    throw SceneError(s.str());
  }
}

void requirePositiveTolerance(double tolerance, const std::string& what) {
  if (!std::isfinite(tolerance) || tolerance <= 0.0) {
    throw SceneError(what + ": the primitive tolerance must be a finite number > 0 (got " + std::to_string(tolerance) +
                     ")");
  }
}

MeshData readMesh(const std::filesystem::path& file) {
  requireFile(file);
  if (isXmlMesh(file)) requireShallowXml(file);  // assimp's COLLADA reader recurses per nested node
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(file.string(), kAssimpFlags);
  if (scene == nullptr) {
    throw SceneError(display(file) + ": cannot read the mesh (assimp: " + importer.GetErrorString() + ")");
  }
  if (!scene->HasMeshes() || scene->mRootNode == nullptr) {
    throw SceneError(display(file) + ": the file contains no mesh");
  }
  MeshData data;
  collect(*scene, *scene->mRootNode, file, &data);
  for (std::size_t i = 0; i < data.vertices.size(); ++i) {
    if (!data.vertices[i].allFinite()) {
      throw SceneError(display(file) + ": vertex " + std::to_string(i) +
                       " (as assimp numbers them) is not finite once the node transforms are applied");
    }
  }
  if (data.triangles.empty()) throw SceneError(display(file) + ": the mesh has no triangles");
  return data;
}

/// A warning when assimp's 32-bit floats round the mesh's coordinates by
/// more than kFloatRoundingWarnRel of its size (a mesh far from its own
/// origin: a hostile-input hunt's 1e8 offset lost its shape with only a
/// slivers warning), else "".
std::string floatRoundingWarning(const MeshData& data, const std::string& file) {
  if (data.vertices.empty()) return "";
  Eigen::Vector3d lo = data.vertices[0], hi = data.vertices[0];
  for (const Eigen::Vector3d& v : data.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const double size = (hi - lo).norm();
  const double largest = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
  // Half the spacing of floats at the largest coordinate (FLT_EPSILON is the
  // spacing at 1; it is at most largest * FLT_EPSILON at `largest`).
  const double rounding = 0.5 * largest * static_cast<double>(std::numeric_limits<float>::epsilon());
  if (!(rounding > kFloatRoundingWarnRel * size)) return "";
  return file + ": coordinates up to " + shortNumber(largest) + " in a mesh " + shortNumber(size) +
         " across: the mesh reader (assimp) keeps 32-bit floats, which round them by up to " + shortNumber(rounding) +
         " (" + shortNumber(100.0 * rounding / size) + "% of its size); keep the mesh near its own origin and " +
         "place it with the URDF's or the cfg's pose";
}

std::vector<Piece> meshPiecesWithOrigin(const std::filesystem::path& file, const Eigen::Vector3d& scale,
                                        const Eigen::Isometry3d& X_OM, const LoadOptions& options,
                                        const std::string& origin_prefix, MeshInfo* info) {
  if (!scale.allFinite()) throw SceneError(display(file) + ": the mesh scale has a non-finite entry");
  // A zero entry flattens the mesh into a plane (as a zero-sized box, which
  // is refused): most triangles would be skipped as degenerate.
  if ((scale.array() == 0.0).any()) throw SceneError(display(file) + ": the mesh scale has a zero entry");
  if (!X_OM.matrix().allFinite()) throw SceneError(display(file) + ": the mesh pose has a non-finite entry");
  const MeshData data = readMesh(file);
  MeshInfo local;
  MeshInfo& out = info != nullptr ? *info : local;
  // The rounding is said whether the load succeeds (a warning) or fails (with
  // the error: a cube at 1e8 fails as "all triangles are degenerate").
  const std::string rounded = floatRoundingWarning(data, display(file));
  std::vector<Piece> pieces;
  try {
    pieces = meshDataPieces(data, file, scale, X_OM, options, origin_prefix, &out);
  } catch (const SceneError& e) {
    if (rounded.empty()) throw;
    throw SceneError(std::string(e.what()) + " (" + rounded + ")");
  }
  if (!rounded.empty()) out.warnings.push_back(rounded);
  return pieces;
}

std::vector<Piece> meshDataPieces(const MeshData& data, const std::filesystem::path& file, const Eigen::Vector3d& scale,
                                  const Eigen::Isometry3d& X_OM, const LoadOptions& options,
                                  const std::string& origin_prefix, MeshInfo* info) {
  MeshInfo local;
  MeshInfo& out = info != nullptr ? *info : local;
  out = MeshInfo{};
  out.vertices = static_cast<int>(data.vertices.size());
  out.triangles = static_cast<int>(data.triangles.size() / 3);
  requireMeshConvexTolerance(options.mesh_convex_tolerance, display(file));
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : data.vertices) mean += scale.cwiseProduct(v);
  mean /= static_cast<double>(std::max<std::size_t>(1, data.vertices.size()));
  out.mean_vertex = mean;
  out.shift = options.recentre_mesh ? mean : Eigen::Vector3d::Zero();

  // Posed triangles; the degenerate ones (zero area, repeated or collinear
  // corners) are set aside with their heights.
  std::vector<Eigen::Vector3d> tri;
  std::vector<int> tri_index;  // index of each kept triangle in the file
  std::vector<int> skipped;    // file indices of the triangles that are no piece
  double skipped_height = 0.0;
  std::vector<Eigen::Vector3d> posed;  // every triangle, the degenerate ones too (for the topology)
  posed.reserve(data.triangles.size());
  tri.reserve(data.triangles.size());
  for (std::size_t t = 0; t < data.triangles.size(); t += 3) {
    Eigen::Vector3d p[3];
    for (int c = 0; c < 3; ++c)
      p[c] = X_OM * (scale.cwiseProduct(data.triangles[t + static_cast<std::size_t>(c)]) - out.shift);
    if (!(p[0].allFinite() && p[1].allFinite() && p[2].allFinite())) {
      throw SceneError(display(file) + ": triangle " + std::to_string(t / 3) +
                       ": a corner is not finite once scaled and posed (the scale or pose is too large)");
    }
    for (int c = 0; c < 3; ++c) {
      if (p[c].cwiseAbs().maxCoeff() > defaults::kMaxCoordinate) {
        throw SceneError(display(file) + ": triangle " + std::to_string(t / 3) + ": a corner once scaled and posed (" +
                         shortNumber(p[c].cwiseAbs().maxCoeff()) + " from the origin along an axis) is beyond the " +
                         "supported range of " + shortNumber(defaults::kMaxCoordinate) +
                         " (the scale or pose is too large)");
      }
    }
    posed.insert(posed.end(), {p[0], p[1], p[2]});
    if (degenerate(p[0], p[1], p[2])) {
      ++out.degenerate_triangles;
      skipped.push_back(static_cast<int>(t / 3));
      skipped_height = std::max(skipped_height, heightOverLongestEdge(p[0], p[1], p[2]));
      continue;
    }
    tri.insert(tri.end(), {p[0], p[1], p[2]});
    tri_index.push_back(static_cast<int>(t / 3));
  }
  if (tri.empty()) {
    throw SceneError(display(file) + ": all " + std::to_string(out.triangles) + " triangles are degenerate");
  }

  const MeshTopology topology = meshTopology(posed);
  out.closed = topology.closed;
  out.oriented = topology.oriented;

  std::vector<Piece> pieces;
  if (options.mesh_convex_hull) {
    // The hull is asked for: here its failure is the load's.
    // Of every corner, the degenerate triangles' too: they are mesh points.
    ConvexPolytope hull;
    try {
      hull = ConvexPolytope::fromPoints(posed);
    } catch (const Error& e) {
      throw SceneError(display(file) + ": cannot build the convex hull of its " + std::to_string(out.triangles) +
                       " triangles (the mesh_convex_hull option): " + briefReason(e.what()));
    }
    pieces.push_back(Piece::make(std::move(hull), PieceKind::kConvex, origin_prefix + ": convex"));
    return pieces;
  }

  Eigen::AlignedBox3d box;
  box.setEmpty();
  double largest = 0.0;
  for (const Eigen::Vector3d& p : tri) {
    box.extend(p);
    largest = std::max(largest, p.cwiseAbs().maxCoeff());
  }
  const double size = box.diagonal().norm();
  const double plane_tol = std::max(options.mesh_convex_tolerance, kPlaneTolerance) * size + kFloatTolerance * largest;
  ConvexityCheck check = checkConvexity(tri, plane_tol, &ConvexPolytope::fromPoints, topology.oriented);
  out.convex = check.convex;
  if (!check.hull_error.empty()) {
    out.hull_failed = true;
    out.warnings.push_back(display(file) + ": the convex hull that decides whether the mesh is convex could not be " +
                           "built (" + check.hull_error + "); the mesh is loaded as its " +
                           std::to_string(tri.size() / 3) + " triangles, which is exact but slower if it is convex");
  }
  if (out.convex) {
    // The degenerate triangles set aside are covered by the solid hull when
    // their corners lie in it; one that leaves it (a stray segment beside a
    // convex body) is lost, and the warning names it.
    std::vector<int> outside;
    double outside_by = 0.0;
    for (const int s : skipped) {
      double by = 0.0;
      for (int c = 0; c < 3; ++c) {
        by = std::max(by, beyondHull(check.hull, posed[3 * static_cast<std::size_t>(s) + static_cast<std::size_t>(c)]));
      }
      if (by > plane_tol) {
        outside.push_back(s);
        outside_by = std::max(outside_by, by);
      }
    }
    out.skipped_triangles = outside;
    if (!outside.empty()) {
      out.warnings.push_back(display(file) + ": skipped " + std::to_string(outside.size()) + " of " +
                             std::to_string(out.triangles) + " triangles that are not polytopes (zero area, " +
                             "repeated or collinear corners) and leave the convex hull the mesh is loaded as, by at " +
                             "least " + shortNumber(outside_by) + ": " + triangleList(outside) +
                             "; a body that touches only them does not collide with the mesh");
    }
    pieces.push_back(Piece::make(std::move(check.hull), PieceKind::kConvex, origin_prefix + ": convex"));
    return pieces;
  }
  if (topology.closed) {
    std::string why;
    switch (check.verdict) {
      case ConvexityVerdict::kWitness:
        why = "triangle " + std::to_string(tri_index[static_cast<std::size_t>(check.triangle)]) +
              " has mesh points on both sides of its plane, beyond what the tolerance allows";
        break;
      case ConvexityVerdict::kOffHull:
        why = "triangle " + std::to_string(tri_index[static_cast<std::size_t>(check.triangle)]) + " is farther than " +
              shortNumber(plane_tol) + " from every supporting plane of the hull";
        break;
      case ConvexityVerdict::kUncovered: why = "the triangles do not cover the hull"; break;
      case ConvexityVerdict::kHullFailed:
      case ConvexityVerdict::kConvex: why = "its hull could not be built"; break;
    }
    out.warnings.push_back(display(file) + ": closed mesh of " + std::to_string(out.triangles) +
                           " triangles loaded as a hollow triangle soup (not convex within the mesh_convex_tolerance " +
                           shortNumber(options.mesh_convex_tolerance) + " of its size " + shortNumber(size) + ": " +
                           why + "): a body entirely inside it does not collide with it");
  }

  // One piece per triangle. A sliver the hull code cannot make a polytope of
  // (one it calls collinear, or whose plane qhull cannot resolve) is skipped
  // like a degenerate one.
  //
  // Why skipping is safe, and when it is not: a skipped triangle lies within
  // its height h of its longest edge (h below 1e-10 of that edge for a
  // degenerate one, below kSliverRatio for a sliver). In a closed or
  // well-connected mesh that edge is shared with a neighbouring triangle,
  // which is kept: any body that touches the skipped triangle comes within h
  // of the neighbour, so distances and contacts change by at most h (the
  // warning gives the largest h), and only a body thinner than h could pass
  // through the gap. A triangle whose edges are shared with no kept triangle
  // (an isolated sliver, e.g. a lone strip that models a wire) is lost
  // outright: the warning names it so that the user can check.
  //
  // A well-shaped triangle the hull code rejects (a small triangle far from
  // the origin, where the core's round-off exceeds its flatness tolerance) is
  // not skipped: that would open a hole as large as the triangle, and a
  // planner would go through it. The load fails and says so.
  pieces.reserve(tri_index.size());
  for (std::size_t i = 0; i < tri_index.size(); ++i) {
    const std::vector<Eigen::Vector3d> corners(tri.begin() + static_cast<std::ptrdiff_t>(3 * i),
                                               tri.begin() + static_cast<std::ptrdiff_t>(3 * i + 3));
    std::string error;
    try {
      pieces.push_back(Piece::make(ConvexPolytope::fromPoints(corners), PieceKind::kTriangle,
                                   origin_prefix + ": triangle " + std::to_string(tri_index[i])));
      continue;
    } catch (const DegenerateGeometryError& e) {
      error = e.what();
    } catch (const HullError& e) {
      error = e.what();
    } catch (const NumericalError& e) {
      error = e.what();
    } catch (const Error& e) {
      throw SceneError(display(file) + ": triangle " + std::to_string(tri_index[i]) +
                       ": cannot build its polytope: " + briefReason(e.what()));
    }
    const double height = heightOverLongestEdge(corners[0], corners[1], corners[2]);
    const double longest = std::sqrt(longestEdgeSquared(corners[0], corners[1], corners[2]));
    if (!(height <= kSliverRatio * longest)) {
      const double distance = std::max({corners[0].norm(), corners[1].norm(), corners[2].norm()});
      throw SceneError(
          display(file) + ": triangle " + std::to_string(tri_index[i]) +
          ": the hull code cannot make a polytope of it although it is no sliver (longest edge " +
          shortNumber(longest) + ", height " + shortNumber(height) + ", at " + shortNumber(distance) +
          " from the origin: small triangles far from the origin exceed the core's precision): " + briefReason(error));
    }
    ++out.degenerate_triangles;
    skipped.push_back(tri_index[i]);
    skipped_height = std::max(skipped_height, height);
  }
  if (pieces.empty()) {
    throw SceneError(display(file) + ": none of its " + std::to_string(out.triangles) +
                     " triangles is a polytope (all are degenerate or slivers)");
  }
  std::sort(skipped.begin(), skipped.end());
  out.skipped_triangles = skipped;
  if (!skipped.empty()) {
    out.warnings.push_back(display(file) + ": skipped " + std::to_string(skipped.size()) + " of " +
                           std::to_string(out.triangles) + " triangles that are not polytopes (zero area, " +
                           "repeated or collinear corners, or slivers): " + triangleList(skipped) +
                           "; none extends more than " + shortNumber(skipped_height) +
                           " from its longest edge, which neighbouring triangles share in a closed mesh");
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
