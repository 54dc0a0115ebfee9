// Tests of the in-memory builders (builders.h): the same geometry built from
// arrays and loaded from a file the test writes gives the same pieces; bad
// arrays give SceneErrors naming the row.
#include "mddual/scene/builders.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include "mddual/scene/loaders.h"
#include "scene_test_util.h"

namespace mddual::scene {
namespace {

using testing::expectSceneError;
using testing::TempDir;

/// Coordinates in these tests are exact in 32-bit floats (assimp's storage),
/// so file and arrays agree to the last bit; this only absorbs the printing.
constexpr double kSameTol = 1e-12;

struct Mesh {
  VertexArray vertices;
  TriangleArray triangles;
};

/// OBJ text of the mesh (1-based indices in the file).
std::string objText(const Mesh& m) {
  std::ostringstream s;
  s.precision(17);
  for (Eigen::Index i = 0; i < m.vertices.rows(); ++i) {
    s << "v " << m.vertices(i, 0) << " " << m.vertices(i, 1) << " " << m.vertices(i, 2) << "\n";
  }
  for (Eigen::Index t = 0; t < m.triangles.rows(); ++t) {
    s << "f " << m.triangles(t, 0) + 1 << " " << m.triangles(t, 1) + 1 << " " << m.triangles(t, 2) + 1 << "\n";
  }
  return s.str();
}

/// The box [lo, hi] as 8 vertices and 12 outward triangles.
Mesh boxMesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  Mesh m;
  m.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) {
    m.vertices.row(i) << ((i & 1) ? hi.x() : lo.x()), ((i & 2) ? hi.y() : lo.y()), ((i & 4) ? hi.z() : lo.z());
  }
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  m.triangles.resize(12, 3);
  for (int q = 0; q < 6; ++q) {
    m.triangles.row(2 * q) << quads[q][0], quads[q][1], quads[q][2];
    m.triangles.row(2 * q + 1) << quads[q][0], quads[q][2], quads[q][3];
  }
  return m;
}

/// An L-shaped prism (non-convex), 12 vertices and 20 triangles.
Mesh lShapeMesh() {
  const double L[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  Mesh m;
  m.vertices.resize(12, 3);
  for (int z = 0; z < 2; ++z) {
    for (int i = 0; i < 6; ++i) m.vertices.row(6 * z + i) << L[i][0], L[i][1], 0.5 * z;
  }
  std::vector<std::array<int, 3>> f;
  for (int i = 1; i < 5; ++i) {
    f.push_back({0, i + 1, i});
    f.push_back({6, 6 + i, 6 + i + 1});
  }
  for (int i = 0; i < 6; ++i) {
    const int j = (i + 1) % 6;
    f.push_back({i, j, 6 + j});
    f.push_back({i, 6 + j, 6 + i});
  }
  m.triangles.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t t = 0; t < f.size(); ++t) {
    m.triangles.row(static_cast<Eigen::Index>(t)) << f[t][0], f[t][1], f[t][2];
  }
  return m;
}

/// Same kinds, same polytopes (vertices in order) and same bounds.
void expectSamePieces(const std::vector<Piece>& a, const std::vector<Piece>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    SCOPED_TRACE("piece " + std::to_string(k) + " (" + a[k].origin + " / " + b[k].origin + ")");
    EXPECT_EQ(a[k].kind, b[k].kind);
    ASSERT_EQ(a[k].polytope.numVertices(), b[k].polytope.numVertices());
    EXPECT_EQ(a[k].polytope.numFaces(), b[k].polytope.numFaces());
    for (int v = 0; v < a[k].polytope.numVertices(); ++v) {
      EXPECT_LE((a[k].polytope.vertex(v) - b[k].polytope.vertex(v)).norm(), kSameTol) << "vertex " << v;
    }
    EXPECT_LE((a[k].box.min() - b[k].box.min()).norm(), kSameTol);
    EXPECT_LE((a[k].box.max() - b[k].box.max()).norm(), kSameTol);
  }
}

TEST(Builders, ConvexMeshArraysGiveTheLoadersPiece) {
  TempDir dir;
  const Mesh box = boxMesh({-0.5, -1.25, 0}, {1.5, 2, 0.75});
  const auto file = dir.write("box.obj", objText(box));
  MeshInfo from_file, from_arrays;
  const auto loaded = meshPieces(file, Eigen::Vector3d::Ones(), Eigen::Isometry3d::Identity(), {}, &from_file);
  const auto built =
      meshArrayPieces(box.vertices, box.triangles, Eigen::Isometry3d::Identity(), {}, "box.obj", &from_arrays);
  EXPECT_TRUE(from_file.convex);
  EXPECT_TRUE(from_arrays.convex);
  expectSamePieces(loaded, built);
  ASSERT_EQ(built.size(), 1u);
  EXPECT_EQ(built[0].origin, loaded[0].origin);  // "box.obj: convex"

  // Bodies and worlds: loadBody / loadWorld against bodyFromMesh / worldFromMesh.
  expectSamePieces(loadBody(file).pieces(), bodyFromMesh(box.vertices, box.triangles, "box").pieces());
  expectSamePieces(loadWorld(file).pieces(), worldFromMesh(box.vertices, box.triangles, "box").pieces());
}

TEST(Builders, NonConvexMeshArraysGiveTheLoadersTrianglesOrHull) {
  TempDir dir;
  const Mesh l = lShapeMesh();
  const auto file = dir.write("l.obj", objText(l));
  for (const bool hull : {false, true}) {
    SCOPED_TRACE(hull ? "mesh_convex_hull" : "triangles");
    LoadOptions options;
    options.mesh_convex_hull = hull;
    MeshInfo info;
    const auto loaded = meshPieces(file, Eigen::Vector3d::Ones(), Eigen::Isometry3d::Identity(), options);
    const auto built = meshArrayPieces(l.vertices, l.triangles, Eigen::Isometry3d::Identity(), options, "l.obj", &info);
    EXPECT_FALSE(info.convex);
    EXPECT_EQ(info.triangles, 20);
    EXPECT_EQ(built.size(), hull ? 1u : 20u);
    expectSamePieces(loaded, built);
    for (std::size_t k = 0; k < built.size(); ++k) EXPECT_EQ(built[k].origin, loaded[k].origin);
  }
}

TEST(Builders, MeshPoseAndRecentringFollowTheLoader) {
  TempDir dir;
  const Mesh l = lShapeMesh();
  const auto file = dir.write("l.obj", objText(l));
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() << 4, -2, 1;
  X.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  expectSamePieces(meshPieces(file, Eigen::Vector3d::Ones(), X, {}),
                   meshArrayPieces(l.vertices, l.triangles, X, {}, "l"));

  // Recentring shifts by the mean of the rows (every vertex, as the loader's
  // mean over the file's vertices).
  LoadOptions recentre;
  recentre.recentre_mesh = true;
  MeshInfo info;
  const auto pieces = meshArrayPieces(l.vertices, l.triangles, Eigen::Isometry3d::Identity(), recentre, "l", &info);
  const Eigen::Vector3d mean = l.vertices.colwise().mean().transpose();
  EXPECT_LE((info.shift - mean).norm(), kSameTol);
  const auto plain = meshArrayPieces(l.vertices, l.triangles, Eigen::Isometry3d::Identity(), {}, "l");
  ASSERT_EQ(pieces.size(), plain.size());
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    EXPECT_LE((pieces[k].polytope.vertex(0) - (plain[k].polytope.vertex(0) - mean)).norm(), kSameTol);
  }
  const RigidBody body = bodyFromMesh(l.vertices, l.triangles, "l", recentre);
  expectSamePieces(body.pieces(), pieces);
}

TEST(Builders, PrimitiveShapesGiveTheUrdfLoadersPieces) {
  TempDir dir;
  const auto urdf = dir.write("prims.urdf", R"(<?xml version="1.0"?>
<robot name="prims">
  <link name="base">
    <collision><origin xyz="1 0 0"/><geometry><box size="2 4 6"/></geometry></collision>
    <collision><origin xyz="0 0 5"/><geometry><sphere radius="0.5"/></geometry></collision>
    <collision><origin xyz="0 -3 0"/><geometry><cylinder radius="0.25" length="2"/></geometry></collision>
  </link>
</robot>
)");
  LoadOptions options;
  options.primitive_tolerance = 2e-3;
  const RigidBody loaded = loadBody(urdf, options);
  const auto at = [](double x, double y, double z) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() << x, y, z;
    return X;
  };
  const RigidBody built = buildBody(
      {Shape::box({2, 4, 6}, at(1, 0, 0)), Shape::sphere(0.5, at(0, 0, 5)), Shape::cylinder(0.25, 2, at(0, -3, 0))},
      "prims", options);
  expectSamePieces(loaded.pieces(), built.pieces());
  EXPECT_EQ(built.pieces()[1].origin, "prims: shape 1 (sphere)");
  const World world = buildWorld({Shape::box({2, 4, 6}, at(1, 0, 0))}, "w", options);
  expectSamePieces(world.pieces(), {loaded.pieces()[0]});
}

TEST(Builders, ShapeListsMixMeshesAndConvexSets) {
  const Mesh box = boxMesh({0, 0, 0}, {1, 1, 1});
  const Mesh l = lShapeMesh();
  const std::vector<Eigen::Vector3d> tetra = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.1, 0.1, 0.1}};
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() << 0, 0, 3;
  const World world = buildWorld(
      {Shape::mesh(box.vertices, box.triangles), Shape::mesh(l.vertices, l.triangles, X), Shape::convex(tetra, X)},
      "mixed");
  ASSERT_EQ(world.pieces().size(), 1u + 20u + 1u);
  EXPECT_EQ(world.pieces()[0].origin, "mixed: shape 0 (mesh): convex");
  EXPECT_EQ(world.pieces()[3].origin, "mixed: shape 1 (mesh): triangle 2");
  const Piece& t = world.pieces()[21];
  EXPECT_EQ(t.kind, PieceKind::kConvex);
  EXPECT_EQ(t.polytope.numVertices(), 4);  // the inner point is not a hull vertex
  EXPECT_NEAR(t.box.min().z(), 3.0, kSameTol);

  std::vector<Eigen::Vector3d> moved;
  for (const auto& p : tetra) moved.push_back(X * p);
  expectSamePieces(worldFromConvexSets({moved}, "sets").pieces(),
                   {Piece::make(ConvexPolytope::fromPoints(moved), PieceKind::kConvex, "")});
  const RigidBody body = bodyFromConvexSets({tetra, moved}, "r");
  ASSERT_EQ(body.pieces().size(), 2u);
  EXPECT_EQ(body.pieces()[1].origin, "r: piece 1");
  // A flat set is a flat convex piece.
  EXPECT_TRUE(bodyFromConvexSets({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, "flat").pieces()[0].polytope.isFlat());
  EXPECT_EQ(buildWorld({}, "empty").pieces().size(), 0u);
}

TEST(Builders, BadArraysNameTheRow) {
  const Mesh box = boxMesh({0, 0, 0}, {1, 1, 1});
  const auto I = Eigen::Isometry3d::Identity();
  expectSceneError([&] { meshArrayPieces(VertexArray(0, 3), box.triangles, I, {}, "m"); },
                   {"m", "vertex array is empty"});
  expectSceneError([&] { meshArrayPieces(box.vertices, TriangleArray(0, 3), I, {}, "m"); },
                   {"m", "triangle array is empty"});
  Mesh bad = box;
  bad.triangles(5, 2) = 8;
  expectSceneError([&] { meshArrayPieces(bad.vertices, bad.triangles, I, {}, "m"); },
                   {"m: triangle 5, corner 2", "vertex index 8", "[0, 8)"});
  bad = box;
  bad.triangles(0, 0) = -1;
  expectSceneError([&] { bodyFromMesh(bad.vertices, bad.triangles, "arm"); }, {"arm: triangle 0, corner 0", "-1"});
  bad = box;
  bad.vertices(3, 1) = std::numeric_limits<double>::quiet_NaN();
  expectSceneError([&] { worldFromMesh(bad.vertices, bad.triangles, "w"); }, {"w: vertex 3", "y coordinate is NaN"});
  bad = box;
  bad.vertices(7, 2) = -std::numeric_limits<double>::infinity();
  expectSceneError([&] { buildWorld({Shape::mesh(bad.vertices, bad.triangles)}, "w"); },
                   {"w: shape 0 (mesh): vertex 7", "z coordinate is infinite"});
  Eigen::Isometry3d nan_pose = I;
  nan_pose.translation().x() = std::numeric_limits<double>::quiet_NaN();
  expectSceneError([&] { meshArrayPieces(box.vertices, box.triangles, nan_pose, {}, "m"); }, {"m", "pose"});
  // Every triangle degenerate: the loader's own message.
  Mesh flat = box;
  flat.triangles.setZero();
  expectSceneError([&] { meshArrayPieces(flat.vertices, flat.triangles, I, {}, "m"); }, {"m", "degenerate"});

  expectSceneError([&] { buildBody({}, "arm"); }, {"arm", "no shapes"});
  expectSceneError([&] { bodyFromConvexSets({}, "arm"); }, {"arm", "no point sets"});
  expectSceneError([&] { worldFromConvexSets({{}}, "w"); }, {"w: piece 0", "empty"});
  expectSceneError(
      [&] {
        worldFromConvexSets({{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}}, "w");
      },
      {"w: piece 0", "convex hull"});
  expectSceneError(
      [&] {
        worldFromConvexSets({{{0, 0, 0}, {1, 1, std::numeric_limits<double>::quiet_NaN()}}}, "w");
      },
      {"w: piece 0: point 1", "z coordinate is NaN"});
  expectSceneError([&] { buildWorld({Shape::box({1, -1, 1})}, "w"); }, {"w: shape 0 (box)", "sizes"});
  expectSceneError(
      [&] {
        buildWorld({Shape::box({1, 1, 1}), Shape::sphere(0.0)}, "w");
      },
      {"w: shape 1 (sphere)", "radius"});
  LoadOptions zero;
  zero.primitive_tolerance = 0.0;
  expectSceneError([&] { buildWorld({Shape::cylinder(1, 1)}, "w", zero); }, {"w", "tolerance"});
  // SceneError is an InvalidInputError.
  EXPECT_THROW(bodyFromMesh(VertexArray(0, 3), box.triangles, "arm"), InvalidInputError);
}

}  // namespace
}  // namespace mddual::scene
