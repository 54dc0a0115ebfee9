// Primitive shapes as convex pieces: boxes exactly, cylinders and spheres as
// circumscribed polytopes within a tolerance of the true surface.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "mddual/scene/loaders.h"
#include "scene_detail.h"

namespace mddual::scene {
namespace {

/// Fewest sides of a cylinder's prism (coarser prisms look nothing like a
/// cylinder even when the tolerance allows them).
constexpr int kMinCylinderSides = 8;
/// More vertices than this means the tolerance is unreasonably small for the
/// shape (and the hull would be slow to build and to query).
constexpr int kMaxPrimitiveVertices = 40000;

bool finite(const Eigen::Vector3d& v) {
  return v.allFinite();
}

void requirePositive(double value, const std::string& what, const std::string& origin) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw SceneError(origin + ": " + what + " must be a finite number > 0 (got " + std::to_string(value) + ")");
  }
}

void requirePose(const Eigen::Isometry3d& X, const std::string& origin) {
  if (!X.matrix().allFinite()) throw SceneError(origin + ": the pose has a non-finite entry");
}

Piece makePiece(const std::vector<Eigen::Vector3d>& points, const std::string& origin) {
  try {
    return Piece::make(ConvexPolytope::fromPoints(points), PieceKind::kConvex, origin);
  } catch (const Error& e) {
    throw SceneError(origin + ": cannot build its polytope: " + e.what());
  }
}

/// The 12 vertices and 20 faces of a unit icosahedron.
void icosahedron(std::vector<Eigen::Vector3d>* vertices, std::vector<std::array<int, 3>>* faces) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  *vertices = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
               {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (Eigen::Vector3d& v : *vertices) v.normalize();
  *faces = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
            {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
            {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
}

/// The frequency-n geodesic sphere (unit radius): each icosahedron face's
/// barycentric grid of step 1/n projected to the sphere, without duplicate
/// points, and its triangles (indices into the points).
struct Geodesic {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;
};

Geodesic geodesic(int n) {
  std::vector<Eigen::Vector3d> ico;
  std::vector<std::array<int, 3>> faces;
  icosahedron(&ico, &faces);
  // Grid points are keyed by their non-zero integer barycentric weights on
  // the face's corners (sorted by corner index), so points shared by faces
  // appear once.
  std::map<std::array<int, 6>, int> seen;
  Geodesic g;
  for (const auto& face : faces) {
    std::vector<int> grid;  // (i, j) -> point index, row by row
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        const int k = n - i - j;
        std::array<std::pair<int, int>, 3> corners = {{{face[0], k}, {face[1], i}, {face[2], j}}};
        std::sort(corners.begin(), corners.end());
        std::array<int, 6> key = {-1, 0, -1, 0, -1, 0};
        int used = 0;
        for (const auto& c : corners) {
          if (c.second == 0) continue;
          key[static_cast<std::size_t>(2 * used)] = c.first;
          key[static_cast<std::size_t>(2 * used + 1)] = c.second;
          ++used;
        }
        const auto [it, inserted] = seen.emplace(key, static_cast<int>(g.points.size()));
        if (inserted) {
          const Eigen::Vector3d p = static_cast<double>(k) * ico[static_cast<std::size_t>(face[0])] +
                                    static_cast<double>(i) * ico[static_cast<std::size_t>(face[1])] +
                                    static_cast<double>(j) * ico[static_cast<std::size_t>(face[2])];
          g.points.push_back(p.normalized());
        }
        grid.push_back(it->second);
      }
    }
    // Row i starts at offset(i) = i (n + 1) - i (i - 1) / 2.
    const auto at = [n, &grid](int i, int j) {
      return grid[static_cast<std::size_t>(i * (n + 1) - i * (i - 1) / 2 + j)];
    };
    for (int i = 0; i < n; ++i) {
      for (int j = 0; i + j < n; ++j) {
        g.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j + 1 < n) g.triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
  }
  return g;
}

/// Smallest distance from the centre to the plane of one of the geodesic
/// triangles (the hull's faces when the triangulation is the hull's, which
/// spherePiece checks on the hull it builds).
double smallestTriangleDistance(const Geodesic& g) {
  double d = 1.0;
  for (const auto& t : g.triangles) {
    const Eigen::Vector3d& a = g.points[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d& b = g.points[static_cast<std::size_t>(t[1])];
    const Eigen::Vector3d& c = g.points[static_cast<std::size_t>(t[2])];
    d = std::min(d, std::abs((b - a).cross(c - a).normalized().dot(a)));
  }
  return d;
}

}  // namespace

Piece boxPiece(const Eigen::Vector3d& size, const Eigen::Isometry3d& X_OB, std::string origin) {
  if (!finite(size) || (size.array() <= 0.0).any()) {
    throw SceneError(origin + ": box sizes must be finite and > 0 (got " + std::to_string(size.x()) + " " +
                     std::to_string(size.y()) + " " + std::to_string(size.z()) + ")");
  }
  requirePose(X_OB, origin);
  const Eigen::Vector3d h = 0.5 * size;
  std::vector<Eigen::Vector3d> corners;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d c((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
    corners.push_back(X_OB * c);
  }
  return makePiece(corners, origin);
}

int cylinderSides(double radius, double tolerance) {
  requirePositive(radius, "the cylinder radius", "cylinderSides");
  detail::requirePositiveTolerance(tolerance, "cylinderSides");
  // A k-gon circumscribing the circle has its vertices at radius / cos(pi/k):
  // the smallest k with radius / cos(pi/k) <= radius + tolerance.
  const double ratio = radius / (radius + tolerance);
  const double k_real = kPi / std::acos(ratio);
  if (!(k_real < 2.0 * kMaxPrimitiveVertices)) {
    throw SceneError("a cylinder of radius " + std::to_string(radius) + " needs more than " +
                     std::to_string(kMaxPrimitiveVertices / 2) + " sides for the tolerance " +
                     std::to_string(tolerance) + ": use a larger primitive tolerance");
  }
  int k = std::max(kMinCylinderSides, static_cast<int>(std::ceil(k_real)));
  while (radius / std::cos(kPi / k) - radius > tolerance) ++k;  // round-off guard
  if (2 * k > kMaxPrimitiveVertices) {
    throw SceneError("a cylinder of radius " + std::to_string(radius) + " needs " + std::to_string(k) +
                     " sides for the tolerance " + std::to_string(tolerance) + ": use a larger primitive tolerance");
  }
  return k;
}

Piece cylinderPiece(double radius, double length, const Eigen::Isometry3d& X_OC, double tolerance, std::string origin) {
  requirePositive(radius, "the cylinder radius", origin);
  requirePositive(length, "the cylinder length", origin);
  requirePose(X_OC, origin);
  detail::requirePositiveTolerance(tolerance, origin);
  int k = 0;
  try {
    k = cylinderSides(radius, tolerance);
  } catch (const SceneError& e) {
    throw SceneError(origin + ": " + e.what());
  }
  const double r_vertex = radius / std::cos(kPi / k);
  std::vector<Eigen::Vector3d> points;
  points.reserve(static_cast<std::size_t>(2 * k));
  for (int i = 0; i < k; ++i) {
    const double a = 2.0 * kPi * i / k;
    for (const double z : {-0.5 * length, 0.5 * length}) {
      points.push_back(X_OC * Eigen::Vector3d(r_vertex * std::cos(a), r_vertex * std::sin(a), z));
    }
  }
  return makePiece(points, origin);
}

Piece spherePiece(double radius, const Eigen::Isometry3d& X_OS, double tolerance, std::string origin) {
  requirePositive(radius, "the sphere radius", origin);
  requirePose(X_OS, origin);
  detail::requirePositiveTolerance(tolerance, origin);
  // With every face plane of the unit geodesic hull at distance >= d, scaling
  // by radius / d puts the planes at >= radius (the polytope contains the
  // sphere) and the vertices at radius / d: within tolerance when
  // d >= radius / (radius + tolerance). The frequency n is the smallest for
  // which the geodesic triangles satisfy this; the hull built from the scaled
  // points is then checked (its faces are the triangles' planes unless qhull
  // triangulates differently, in which case n grows).
  const double d_needed = radius / (radius + tolerance);
  int n = 1;
  for (;;) {
    if (10 * n * n + 2 > kMaxPrimitiveVertices) {
      throw SceneError(origin + ": a sphere of radius " + std::to_string(radius) + " needs more than " +
                       std::to_string(kMaxPrimitiveVertices) + " vertices for the tolerance " +
                       std::to_string(tolerance) + ": use a larger primitive tolerance");
    }
    const Geodesic g = geodesic(n);
    const double d = smallestTriangleDistance(g);
    if (d < d_needed) {
      ++n;
      continue;
    }
    const double s = radius / d;
    std::vector<Eigen::Vector3d> points;
    points.reserve(g.points.size());
    for (const Eigen::Vector3d& p : g.points) points.push_back(X_OS * (s * p));
    Piece piece = makePiece(points, origin);
    const Eigen::Vector3d centre = X_OS.translation();
    double closest = std::numeric_limits<double>::infinity();
    for (int f = 0; f < piece.polytope.numFaces(); ++f) {
      closest = std::min(closest, piece.polytope.faceOffset(f) - piece.polytope.faceNormal(f).dot(centre));
    }
    if (closest >= radius * (1.0 - 1e-12)) return piece;
    ++n;
  }
}

}  // namespace mddual::scene
