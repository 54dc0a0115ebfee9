// Meshes that are convex up to a tolerance: the
// mesh_convex_tolerance option, the closed-mesh test, the warning for a
// closed mesh loaded as a hollow triangle soup, and the counts behind the
// scene summary. The meshes are written by the tests (OBJ, full precision).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <sstream>

#include "mddual/constants.h"
#include "mddual/generators.h"
#include "mddual/scene/loaders.h"
#include "scene_detail.h"
#include "scene_test_util.h"

namespace mddual::scene {
namespace {

using testing::boxTriangles;
using testing::expectSceneError;
using testing::TempDir;

const Eigen::Isometry3d kIdentity = Eigen::Isometry3d::Identity();
const Eigen::Vector3d kOnes = Eigen::Vector3d::Ones();

/// OBJ text of triangles (three corners each), one vertex per corner, in
/// full double precision (the reader rounds them to floats).
std::string triangleObj(const std::vector<Eigen::Vector3d>& corners) {
  std::ostringstream s;
  s.precision(17);
  for (const Eigen::Vector3d& p : corners) s << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (std::size_t t = 0; t < corners.size(); t += 3) s << "f " << t + 1 << " " << t + 2 << " " << t + 3 << "\n";
  return s.str();
}

/// The unit box [0, 1]^3 (12 triangles, closed, outward-wound) with its
/// corner (1, 0, 1) moved by `move`.
std::vector<Eigen::Vector3d> movedCornerBox(const Eigen::Vector3d& move) {
  std::vector<Eigen::Vector3d> tri = boxTriangles({0, 0, 0}, {1, 1, 1});
  for (Eigen::Vector3d& p : tri) {
    if (p == Eigen::Vector3d(1, 0, 1)) p += move;
  }
  return tri;
}

/// The box with its corner (1, 0, 1) raised by `lift` along z. Its top face
/// is split along the diagonal (0,0,1)-(1,1,1), away from that corner, so the
/// top folds into a valley whose fold line lies lift / 2 below the hull
/// (whose top ridge runs from the raised corner to (0,1,1)); the sides at
/// x = 1 and y = 0 stay planar. Convex within about lift / 2, not better.
std::vector<Eigen::Vector3d> liftedBox(double lift) {
  return movedCornerBox(Eigen::Vector3d(0, 0, lift));
}

/// Box diagonal of the lifted box: the size the tolerance is relative to.
double liftedBoxSize(double lift) {
  return std::sqrt(2.0 + (1.0 + lift) * (1.0 + lift));
}

bool mentions(const std::vector<std::string>& warnings, const std::string& part) {
  for (const std::string& w : warnings) {
    if (w.find(part) != std::string::npos) return true;
  }
  return false;
}

const char* const kHollow = "loaded as a hollow triangle soup";

// The perturbed box of the issue: a corner moved by 0.1 of the default
// tolerance (of the size) loads as its hull; by 10 times it, as triangles
// with the warning that the closed mesh is hollow.
TEST(MeshConvexity, BoxWithAVertexOffByATenthOfTheToleranceIsOnePiece) {
  TempDir dir;
  const double move = 0.1 * kDefaultMeshConvexTolerance * std::sqrt(3.0);
  // Raised (the top folds into a valley), and moved along a generic outward
  // direction (three faces fold).
  const Eigen::Vector3d moves[] = {Eigen::Vector3d(0, 0, move), move * Eigen::Vector3d(2, -1, 3).normalized()};
  for (const Eigen::Vector3d& m : moves) {
    const auto file = dir.write("box.obj", triangleObj(movedCornerBox(m)));
    MeshInfo info;
    const std::vector<Piece> pieces = meshPieces(file, kOnes, kIdentity, {}, &info);
    EXPECT_TRUE(info.closed);
    EXPECT_TRUE(info.oriented);
    EXPECT_TRUE(info.convex) << m.transpose();
    ASSERT_EQ(pieces.size(), 1u);
    EXPECT_EQ(pieces[0].kind, PieceKind::kConvex);
    EXPECT_EQ(pieces[0].polytope.numVertices(), 8);
    EXPECT_TRUE(info.warnings.empty());
    // The hull holds the mesh: the moved corner is one of its vertices.
    EXPECT_NEAR(pieces[0].box.max().z(), 1.0 + m.z(), 1e-7);
    EXPECT_NEAR(pieces[0].box.max().x(), 1.0 + m.x(), 1e-7);
  }
  // Without the tolerance these meshes are not convex: the test is not vacuous.
  LoadOptions strict;
  strict.mesh_convex_tolerance = 0.0;
  for (const Eigen::Vector3d& m : moves) {
    MeshInfo info;
    meshPieces(dir.write("box.obj", triangleObj(movedCornerBox(m))), kOnes, kIdentity, strict, &info);
    EXPECT_FALSE(info.convex) << m.transpose();
  }
}

TEST(MeshConvexity, BoxWithAVertexOffByTenTolerancesIsAHollowSoupAndSaysSo) {
  TempDir dir;
  const double lift = 10.0 * kDefaultMeshConvexTolerance * liftedBoxSize(0.0);
  const auto file = dir.write("robot.obj", triangleObj(liftedBox(lift)));
  MeshInfo info;
  const std::vector<Piece> pieces = meshPieces(file, kOnes, kIdentity, {}, &info);
  EXPECT_TRUE(info.closed);
  EXPECT_FALSE(info.convex);
  ASSERT_EQ(pieces.size(), 12u);
  for (const Piece& p : pieces) EXPECT_EQ(p.kind, PieceKind::kTriangle);
  ASSERT_EQ(info.warnings.size(), 1u);
  const std::string& w = info.warnings[0];
  EXPECT_EQ(w.rfind(file.string() + ": closed mesh of 12 triangles " + kHollow, 0), 0u) << w;
  EXPECT_NE(w.find("mesh_convex_tolerance 0.0001"), std::string::npos) << w;
  EXPECT_NE(w.find("on both sides of its plane"), std::string::npos) << w;  // the witness triangle
  EXPECT_NE(w.find("a body entirely inside it does not collide"), std::string::npos) << w;
  // loadBody and loadWorld hand it on and count the mesh.
  std::vector<std::string> warnings;
  MeshCounts counts;
  loadWorld(file, {}, &warnings, &counts);
  EXPECT_EQ(warnings, info.warnings);
  EXPECT_EQ(counts.meshes, 1);
  EXPECT_EQ(counts.convex, 0);
  EXPECT_EQ(counts.soups, 1);
  EXPECT_EQ(counts.closed_soups, 1);
}

// The option decides: the same two meshes the other way round.
TEST(MeshConvexity, TheToleranceOptionChangesTheOutcome) {
  TempDir dir;
  const double size = liftedBoxSize(0.0);
  const auto coarse = dir.write("coarse.obj", triangleObj(liftedBox(10.0 * kDefaultMeshConvexTolerance * size)));
  LoadOptions loose;
  loose.mesh_convex_tolerance = 100.0 * kDefaultMeshConvexTolerance;
  MeshInfo info;
  EXPECT_EQ(meshPieces(coarse, kOnes, kIdentity, loose, &info).size(), 1u);
  EXPECT_TRUE(info.convex);
  MeshCounts counts;
  loadBody(coarse, loose, nullptr, &counts);
  EXPECT_EQ(counts.convex, 1);
  EXPECT_EQ(counts.closed_soups, 0);

  // 0 keeps only the round-off allowance (1e-6 of the size): a corner off by
  // 1.7e-5 is too much.
  const auto fine = dir.write("fine.obj", triangleObj(liftedBox(0.1 * kDefaultMeshConvexTolerance * size)));
  LoadOptions strict;
  strict.mesh_convex_tolerance = 0.0;
  EXPECT_EQ(meshPieces(fine, kOnes, kIdentity, strict, &info).size(), 12u);
  EXPECT_FALSE(info.convex);
  EXPECT_TRUE(mentions(info.warnings, kHollow));
  // An exactly planar box is convex even then.
  const auto exact = dir.write("exact.obj", triangleObj(liftedBox(0.0)));
  EXPECT_EQ(meshPieces(exact, kOnes, kIdentity, strict, &info).size(), 1u);
  EXPECT_TRUE(info.convex);
}

TEST(MeshConvexity, ToleranceOutOfRangeIsRefused) {
  TempDir dir;
  const auto file = dir.write("box.obj", triangleObj(liftedBox(0.0)));
  for (const double bad : {-1e-4, 0.5, std::nan("")}) {
    LoadOptions options;
    options.mesh_convex_tolerance = bad;
    expectSceneError([&] { meshPieces(file, kOnes, kIdentity, options); },
                     {"box.obj: mesh_convex_tolerance must be a number in [0, 0.01]", "mesh_convex_hull"});
    expectSceneError([&] { loadWorld(file, options); }, {"box.obj: mesh_convex_tolerance"});
  }
}

// An open mesh is no solid: loaded as triangles it is what it is, and no
// warning calls it hollow.
TEST(MeshConvexity, OpenMeshGetsNoHollowWarning) {
  TempDir dir;
  std::vector<Eigen::Vector3d> tri = liftedBox(10.0 * kDefaultMeshConvexTolerance * liftedBoxSize(0.0));
  tri.erase(tri.begin() + 12, tri.begin() + 18);  // the y = 0 side
  const auto file = dir.write("open.obj", triangleObj(tri));
  MeshInfo info;
  MeshCounts counts;
  const std::vector<Piece> pieces = meshPieces(file, kOnes, kIdentity, {}, &info);
  EXPECT_FALSE(info.closed);
  EXPECT_FALSE(info.convex);
  EXPECT_EQ(pieces.size(), 10u);
  EXPECT_TRUE(info.warnings.empty());
  loadWorld(file, {}, nullptr, &counts);
  EXPECT_EQ(counts.soups, 1);
  EXPECT_EQ(counts.closed_soups, 0);
  // The exact box without that side is not convex either (it does not cover its hull).
  std::vector<Eigen::Vector3d> flat_open = liftedBox(0.0);
  flat_open.erase(flat_open.begin() + 12, flat_open.begin() + 18);
  EXPECT_EQ(meshPieces(dir.write("open0.obj", triangleObj(flat_open)), kOnes, kIdentity, {}, &info).size(), 10u);
  EXPECT_FALSE(info.closed);
  EXPECT_FALSE(info.convex);
}

// The topology: closed and oriented, closed with one triangle flipped, open,
// an edge shared by four triangles; triangles with a repeated corner are
// left out, collinear ones count.
TEST(MeshConvexity, Topology) {
  std::vector<Eigen::Vector3d> box = boxTriangles({0, 0, 0}, {1, 1, 1});
  detail::MeshTopology t = detail::meshTopology(box);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.oriented);
  std::vector<Eigen::Vector3d> flipped = box;
  std::swap(flipped[1], flipped[2]);
  t = detail::meshTopology(flipped);
  EXPECT_TRUE(t.closed);
  EXPECT_FALSE(t.oriented);
  std::vector<Eigen::Vector3d> open(box.begin(), box.end() - 3);
  t = detail::meshTopology(open);
  EXPECT_FALSE(t.closed);
  EXPECT_FALSE(t.oriented);
  std::vector<Eigen::Vector3d> doubled = box;
  doubled.insert(doubled.end(), box.begin(), box.begin() + 6);  // one face twice
  EXPECT_FALSE(detail::meshTopology(doubled).closed);
  std::vector<Eigen::Vector3d> with_point = box;
  with_point.insert(with_point.end(), {{0, 0, 0}, {0, 0, 0}, {1, 1, 1}});
  EXPECT_TRUE(detail::meshTopology(with_point).oriented);
  std::vector<Eigen::Vector3d> with_needle = box;
  with_needle.insert(with_needle.end(), {{0, 0, 0}, {0.5, 0.5, 0.5}, {1, 1, 1}});
  EXPECT_FALSE(detail::meshTopology(with_needle).closed);
  EXPECT_FALSE(detail::meshTopology({}).closed);
}

// Covering the hull: a closed, oriented mesh by its volume. Eight flat,
// closed "pillows" (a triangle and its reverse) on the faces at the corners
// of a cube have the cube as hull and lie on its boundary, but enclose
// nothing: not convex.
TEST(MeshConvexity, ClosedMeshThatEnclosesNothingIsNotItsHull) {
  std::vector<Eigen::Vector3d> tri;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d c(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    const Eigen::Vector3d x((i & 1) ? -0.1 : 0.1, 0, 0);
    const Eigen::Vector3d y(0, ((i >> 1) & 1) ? -0.1 : 0.1, 0);
    tri.insert(tri.end(), {c, c + x, c + y, c, c + y, c + x});
  }
  const detail::MeshTopology topology = detail::meshTopology(tri);
  ASSERT_TRUE(topology.oriented);
  const detail::ConvexityCheck check =
      detail::checkConvexity(tri, 1e-6, &ConvexPolytope::fromPoints, topology.oriented);
  EXPECT_FALSE(check.convex);
  EXPECT_EQ(check.verdict, detail::ConvexityVerdict::kUncovered);
  // The cube itself, closed and oriented, is covered by its volume.
  const std::vector<Eigen::Vector3d> cube = boxTriangles({0, 0, 0}, {1, 1, 1});
  EXPECT_TRUE(detail::checkConvexity(cube, 1e-6, &ConvexPolytope::fromPoints, true).convex);
}

/// A random convex prism (a rock): a convex polygon of `sides` corners on the
/// unit circle, extruded over z in [0, height]. Its caps are n-gons and its
/// sides quads, so that moving its vertices folds its faces (a triangulated
/// polygon or quad stays convex only if every fold is a ridge). `vertices`
/// and `faces` receive the mesh (closed, outward-wound, shared vertices), each
/// vertex moved by `noise` in a random direction; returns its OBJ text.
std::string prismRock(std::mt19937* rng, int sides, double height, double noise, std::vector<Eigen::Vector3d>* vertices,
                      std::vector<std::array<int, 3>>* faces) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> angles;
  for (int i = 0; i < sides; ++i) angles.push_back(2.0 * kPi * (i + 0.4 * u(*rng)) / sides);
  vertices->clear();
  for (const double z : {0.0, height}) {
    for (const double a : angles) {
      const Eigen::Vector3d d = generators::drawVector(u, *rng);
      vertices->push_back(Eigen::Vector3d(std::cos(a), std::sin(a), z) + noise * d.normalized());
    }
  }
  const int n = sides;
  faces->clear();
  for (int i = 1; i + 1 < n; ++i) {
    faces->push_back({0, i + 1, i});          // bottom, seen from below
    faces->push_back({n, n + i, n + i + 1});  // top
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    faces->push_back({i, j, n + j});
    faces->push_back({i, n + j, n + i});
  }
  std::ostringstream s;
  s.precision(17);
  for (const Eigen::Vector3d& p : *vertices) s << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (const auto& f : *faces) s << "f " << f[0] + 1 << " " << f[1] + 1 << " " << f[2] + 1 << "\n";
  return s.str();
}

/// Volume and surface area of a polytope (pyramids over its faces from its
/// centroid).
std::pair<double, double> volumeAndArea(const ConvexPolytope& P) {
  double volume = 0.0;
  double area = 0.0;
  for (int f = 0; f < P.numFaces(); ++f) {
    const IndexRange loop = P.faceVertices(f);
    Eigen::Vector3d twice = Eigen::Vector3d::Zero();
    for (int i = 1; i + 1 < loop.size(); ++i) {
      twice += (P.vertex(loop[i]) - P.vertex(loop[0])).cross(P.vertex(loop[i + 1]) - P.vertex(loop[0]));
    }
    area += 0.5 * twice.norm();
    volume += 0.5 * twice.norm() * (P.faceOffset(f) - P.faceNormal(f).dot(P.centroid())) / 3.0;
  }
  return {volume, area};
}

// The convex_field case as a family: 40 random prism rocks whose
// vertices are moved by 0.1 of the tolerance all load as one convex piece;
// moved by 10 times it, most do not, and every one that still loads as its
// hull is its hull within e (oracle: every vertex of the mesh within e of the
// hull's boundary; the hull's volume at least the mesh's, and larger by at
// most e times the hull's area).
TEST(MeshConvexity, RandomPrismRocks) {
  TempDir dir;
  std::mt19937 rng(31);
  std::uniform_int_distribution<int> sides(4, 9);
  std::uniform_real_distribution<double> height(0.3, 2.0);
  int soups = 0;
  for (int rock = 0; rock < 40; ++rock) {
    SCOPED_TRACE("rock " + std::to_string(rock));
    const int n = sides(rng);
    const double h = height(rng);
    // The bounding box is at least 1 x 1 x h (a convex polygon around the
    // centre of the unit circle): the noise stays within the stated fraction.
    const double size = std::sqrt(2.0 + h * h);
    std::vector<Eigen::Vector3d> vertices;
    std::vector<std::array<int, 3>> faces;
    for (const double factor : {0.1, 10.0}) {
      const double noise = factor * kDefaultMeshConvexTolerance * size;
      const auto file = dir.write("rock.obj", prismRock(&rng, n, h, noise, &vertices, &faces));
      MeshInfo info;
      const std::vector<Piece> pieces = meshPieces(file, kOnes, kIdentity, {}, &info);
      ASSERT_TRUE(info.closed);
      ASSERT_TRUE(info.oriented);
      if (factor < 1.0) {
        EXPECT_TRUE(info.convex) << (info.warnings.empty() ? "" : info.warnings[0]);
      }
      if (!info.convex) {
        ++soups;
        EXPECT_EQ(pieces.size(), static_cast<std::size_t>(4 * n - 4));
        EXPECT_TRUE(mentions(info.warnings, kHollow));
        continue;
      }
      ASSERT_EQ(pieces.size(), 1u);
      const ConvexPolytope& hull = pieces[0].polytope;
      const Eigen::AlignedBox3d& box = pieces[0].box;
      const double largest = std::max(box.min().cwiseAbs().maxCoeff(), box.max().cwiseAbs().maxCoeff());
      const double e = kDefaultMeshConvexTolerance * box.diagonal().norm() + 5e-7 * largest;
      // The mesh as the reader keeps it (assimp's own float parsing).
      const detail::MeshData data = detail::readMesh(file);
      double mesh_volume = 0.0;
      for (std::size_t t = 0; t < data.triangles.size(); t += 3) {
        mesh_volume += data.triangles[t].dot(data.triangles[t + 1].cross(data.triangles[t + 2])) / 6.0;
      }
      const auto [hull_volume, hull_area] = volumeAndArea(hull);
      EXPECT_GE(hull_volume, mesh_volume - 1e-12);
      EXPECT_LE(hull_volume - mesh_volume, e * hull_area);
      for (const Eigen::Vector3d& p : data.vertices) {
        double depth = std::numeric_limits<double>::infinity();
        for (int f = 0; f < hull.numFaces(); ++f)
          depth = std::min(depth, hull.faceOffset(f) - hull.faceNormal(f).dot(p));
        EXPECT_GE(depth, -1e-12);
        EXPECT_LE(depth, e);
      }
    }
  }
  EXPECT_GE(soups, 20);  // the coarse noise folds most rocks into a valley somewhere
  RecordProperty("coarse_soups", soups);
}

// A large, nearly coplanar, closed mesh: a slab 10 x 10 x 1 whose six faces
// are grids (2 x 30 x 30 triangles on the large faces, 5,040 in all), in a
// generic orientation, every vertex moved at random by up to 0.1 of the
// tolerance (shared vertices, so the mesh stays closed). Its hull has many
// small, slightly tilted faces; the mesh still loads as one convex piece.
TEST(MeshConvexity, LargeNearlyCoplanarClosedMeshLoadsAsItsHull) {
  TempDir dir;
  const Eigen::Vector3d h(10, 10, 1);
  const double size = h.norm();
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> noise(-1.0, 1.0);
  const double amplitude = 0.1 * kDefaultMeshConvexTolerance * size / std::sqrt(3.0);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  // Shared grid vertices: a point of the slab's surface is the same vertex in
  // every face it belongs to.
  std::map<std::array<long, 3>, int> index;
  std::vector<Eigen::Vector3d> vertices;
  const int n = 30;
  const int steps[3] = {n, n, 6};
  const auto vertexAt = [&](const std::array<long, 3>& k) {
    const auto [it, inserted] = index.emplace(k, static_cast<int>(vertices.size()));
    if (inserted) {
      Eigen::Vector3d p;
      for (int a = 0; a < 3; ++a) p[a] = h[a] * static_cast<double>(k[a]) / steps[a];
      vertices.push_back(R * (p + amplitude * generators::drawVector(noise, rng)));
    }
    return it->second;
  };
  std::ostringstream faces;
  int triangles = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const int a = (axis + 1) % 3;
    const int b = (axis + 2) % 3;
    for (const int side : {0, 1}) {
      for (int i = 0; i < steps[a]; ++i) {
        for (int j = 0; j < steps[b]; ++j) {
          int q[4];
          const int di[4] = {0, 1, 1, 0};
          const int dj[4] = {0, 0, 1, 1};
          for (int c = 0; c < 4; ++c) {
            std::array<long, 3> k{};
            k[static_cast<std::size_t>(axis)] = side * steps[axis];
            k[static_cast<std::size_t>(a)] = i + di[c];
            k[static_cast<std::size_t>(b)] = j + dj[c];
            q[c] = vertexAt(k) + 1;
          }
          // Outward winding: (a, b, axis) is right-handed, so the quad turns
          // counter-clockwise seen from +axis.
          if (side == 1) {
            faces << "f " << q[0] << " " << q[1] << " " << q[2] << "\nf " << q[0] << " " << q[2] << " " << q[3] << "\n";
          } else {
            faces << "f " << q[0] << " " << q[2] << " " << q[1] << "\nf " << q[0] << " " << q[3] << " " << q[2] << "\n";
          }
          triangles += 2;
        }
      }
    }
  }
  std::ostringstream text;
  text.precision(17);
  for (const Eigen::Vector3d& p : vertices) text << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
  text << faces.str();
  const auto file = dir.write("slab.obj", text.str());
  MeshInfo info;
  std::vector<Piece> pieces;
  ASSERT_NO_THROW(pieces = meshPieces(file, kOnes, kIdentity, {}, &info));
  EXPECT_EQ(info.triangles, 5040);
  EXPECT_EQ(info.triangles, triangles);
  EXPECT_TRUE(info.closed);
  EXPECT_TRUE(info.oriented);
  EXPECT_FALSE(info.hull_failed);
  EXPECT_TRUE(info.convex) << (info.warnings.empty() ? "" : info.warnings[0]);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_TRUE(info.warnings.empty());
  // With the round-off allowance only, the same mesh is a closed soup.
  LoadOptions strict;
  strict.mesh_convex_tolerance = 0.0;
  ASSERT_NO_THROW(pieces = meshPieces(file, kOnes, kIdentity, strict, &info));
  EXPECT_FALSE(info.convex);
  EXPECT_EQ(pieces.size(), static_cast<std::size_t>(triangles));
  EXPECT_TRUE(mentions(info.warnings, kHollow));
}

}  // namespace
}  // namespace mddual::scene
