// Mesh loading through assimp: convex meshes become one piece, others their
// triangles (or their hull on request), COLLADA's up axis, recentring on the
// mean vertex, and the documented errors.
#include <gtest/gtest.h>

#include <array>
#include <sstream>

#include "mddual/scene/loaders.h"
#include "scene_test_util.h"

namespace mddual::scene {
namespace {

using testing::asciiStl;
using testing::boxTriangles;
using testing::expectSceneError;
using testing::TempDir;

const Eigen::Isometry3d kIdentity = Eigen::Isometry3d::Identity();
const Eigen::Vector3d kOnes = Eigen::Vector3d::Ones();

/// OBJ text of vertices and triangles (1-based in the file).
std::string obj(const std::vector<Eigen::Vector3d>& v, const std::vector<std::array<int, 3>>& f) {
  std::ostringstream s;
  for (const auto& p : v) s << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (const auto& t : f) s << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
  return s.str();
}

/// An L-shaped prism (non-convex): the L (0,0) (2,0) (2,1) (1,1) (1,2) (0,2)
/// extruded over z in [0, 1]; 20 triangles.
std::string lShapeObj() {
  const double L[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  std::vector<Eigen::Vector3d> v;
  for (int z = 0; z < 2; ++z) {
    for (const auto& p : L) v.emplace_back(p[0], p[1], z);
  }
  std::vector<std::array<int, 3>> f;
  for (int i = 1; i < 5; ++i) {
    f.push_back({0, i + 1, i});          // bottom, fan from (0,0)
    f.push_back({6, 6 + i, 6 + i + 1});  // top
  }
  for (int i = 0; i < 6; ++i) {
    const int j = (i + 1) % 6;
    f.push_back({i, j, 6 + j});
    f.push_back({i, 6 + j, 6 + i});
  }
  return obj(v, f);
}

/// A COLLADA file of the box [lo, hi] with the given up axis.
std::string colladaBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const std::string& up) {
  std::ostringstream pos;
  for (int i = 0; i < 8; ++i) {
    pos << ((i & 1) ? hi.x() : lo.x()) << " " << ((i & 2) ? hi.y() : lo.y()) << " " << ((i & 4) ? hi.z() : lo.z())
        << " ";
  }
  const char* tris = "0 2 3 0 3 1 4 5 7 4 7 6 0 1 5 0 5 4 2 6 7 2 7 3 0 4 6 0 6 2 1 3 7 1 7 5";
  return std::string(R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>)") +
         up + R"(</up_axis></asset>
  <library_geometries><geometry id="box" name="box"><mesh>
    <source id="box-pos"><float_array id="box-pos-array" count="24">)" +
         pos.str() + R"(</float_array>
      <technique_common><accessor source="#box-pos-array" count="8" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <vertices id="box-vtx"><input semantic="POSITION" source="#box-pos"/></vertices>
    <triangles count="12"><input semantic="VERTEX" source="#box-vtx" offset="0"/><p>)" +
         tris + R"(</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="Scene" name="Scene">
    <node id="n" name="n"><instance_geometry url="#box"/></node>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#Scene"/></scene>
</COLLADA>
)";
}

void expectBox(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  EXPECT_LE((box.min() - lo).cwiseAbs().maxCoeff(), 1e-6) << box.min().transpose() << " vs " << lo.transpose();
  EXPECT_LE((box.max() - hi).cwiseAbs().maxCoeff(), 1e-6) << box.max().transpose() << " vs " << hi.transpose();
}

TEST(Meshes, ConvexCubeInEachFormatIsOnePiece) {
  TempDir dir;
  std::vector<Eigen::Vector3d> corners;
  for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  const std::vector<std::array<int, 3>> faces = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                                                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  std::ostringstream ply;
  ply << "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
      << "element face 6\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& c : corners) ply << c.x() << " " << c.y() << " " << c.z() << "\n";
  ply << "4 0 2 3 1\n4 4 5 7 6\n4 0 1 5 4\n4 2 6 7 3\n4 0 4 6 2\n4 1 3 7 5\n";  // quads
  const std::vector<std::filesystem::path> files = {
      dir.write("cube.stl", asciiStl(boxTriangles({0, 0, 0}, {1, 1, 1}))), dir.write("cube.obj", obj(corners, faces)),
      dir.write("cube.ply", ply.str()), dir.write("cube.dae", colladaBox({0, 0, 0}, {1, 1, 1}, "Y_UP"))};
  for (const auto& file : files) {
    MeshInfo info;
    const std::vector<Piece> pieces = meshPieces(file, kOnes, kIdentity, {}, &info);
    ASSERT_EQ(pieces.size(), 1u) << file;
    EXPECT_TRUE(info.convex) << file;
    EXPECT_EQ(info.triangles, 12) << file;
    EXPECT_EQ(info.degenerate_triangles, 0) << file;
    EXPECT_EQ(pieces[0].kind, PieceKind::kConvex);
    EXPECT_EQ(pieces[0].polytope.numVertices(), 8) << file;
    EXPECT_EQ(pieces[0].origin, file.filename().string() + ": convex");
    expectBox(pieces[0].box, {0, 0, 0}, {1, 1, 1});
  }
}

TEST(Meshes, ScaleAndPoseApply) {
  TempDir dir;
  const auto file = dir.write("cube.stl", asciiStl(boxTriangles({0, 0, 0}, {1, 1, 1})));
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(5, 6, 7);
  const auto pieces = meshPieces(file, Eigen::Vector3d(2, 3, 4), X, {});
  ASSERT_EQ(pieces.size(), 1u);
  expectBox(pieces[0].box, {5, 6, 7}, {7, 9, 11});
}

TEST(Meshes, NonConvexMeshBecomesTrianglesOrItsHull) {
  TempDir dir;
  const auto file = dir.write("l.obj", lShapeObj());
  MeshInfo info;
  const std::vector<Piece> pieces = meshPieces(file, kOnes, kIdentity, {}, &info);
  EXPECT_FALSE(info.convex);
  EXPECT_EQ(info.triangles, 20);
  ASSERT_EQ(pieces.size(), 20u);
  double area = 0.0;
  for (const Piece& p : pieces) {
    EXPECT_EQ(p.kind, PieceKind::kTriangle);
    EXPECT_TRUE(p.polytope.isFlat());
    EXPECT_EQ(p.polytope.numVertices(), 3);
    const auto& v = p.polytope.vertices();
    area += 0.5 * (v[1] - v[0]).cross(v[2] - v[0]).norm();
  }
  EXPECT_NEAR(area, 2 * 3.0 + 8.0, 1e-9);  // two L caps of area 3, sides of perimeter 8 and height 1
  EXPECT_EQ(pieces[7].origin, "l.obj: triangle 7");

  LoadOptions hull;
  hull.mesh_convex_hull = true;
  const std::vector<Piece> one = meshPieces(file, kOnes, kIdentity, hull, &info);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].kind, PieceKind::kConvex);
  EXPECT_EQ(one[0].polytope.numVertices(), 10);  // the L's reflex corner (1,1) is not on the hull
  expectBox(one[0].box, {0, 0, 0}, {2, 2, 1});
}

TEST(Meshes, OpenBoxIsNotConvex) {
  TempDir dir;
  std::vector<Eigen::Vector3d> tri = boxTriangles({0, 0, 0}, {1, 1, 1});
  tri.resize(tri.size() - 6);  // drop one face: every triangle is on the hull, the area is not
  const auto file = dir.write("open.stl", asciiStl(tri));
  MeshInfo info;
  const auto pieces = meshPieces(file, kOnes, kIdentity, {}, &info);
  EXPECT_FALSE(info.convex);
  EXPECT_EQ(pieces.size(), 10u);
}

TEST(Meshes, DegenerateTrianglesAreSkippedAndCounted) {
  TempDir dir;
  std::vector<Eigen::Vector3d> tri = boxTriangles({0, 0, 0}, {1, 1, 1});
  tri.insert(tri.end(), {{0, 0, 0}, {0.5, 0.5, 0.5}, {1, 1, 1}});  // collinear
  const auto file = dir.write("cube_plus.stl", asciiStl(tri));
  MeshInfo info;
  const auto pieces = meshPieces(file, kOnes, kIdentity, {}, &info);
  EXPECT_EQ(info.triangles, 13);
  EXPECT_EQ(info.degenerate_triangles, 1);
  EXPECT_TRUE(info.convex);
  EXPECT_EQ(pieces.size(), 1u);
}

TEST(Meshes, ColladaZUpIsConvertedToYUpAsAssimpDoes) {
  TempDir dir;
  // Z_UP: a point (x, y, z) of the file is read as (x, z, -y).
  const auto z_up = dir.write("box_z.dae", colladaBox({0, 0, 0}, {1, 2, 3}, "Z_UP"));
  const auto pieces = meshPieces(z_up, kOnes, kIdentity, {});
  ASSERT_EQ(pieces.size(), 1u);
  expectBox(pieces[0].box, {0, 0, -2}, {1, 3, 0});
  const auto y_up = dir.write("box_y.dae", colladaBox({0, 0, 0}, {1, 2, 3}, "Y_UP"));
  expectBox(meshPieces(y_up, kOnes, kIdentity, {})[0].box, {0, 0, 0}, {1, 2, 3});
}

TEST(Meshes, RecentringMovesTheMeanVertexToTheOrigin) {
  TempDir dir;
  // A tetrahedron as STL: each corner is in three faces with different
  // normals, so assimp keeps 12 vertices, three per corner: the mean vertex is
  // the corners' mean (1, 1, 1).
  const Eigen::Vector3d a(0, 0, 0), b(4, 0, 0), c(0, 4, 0), d(0, 0, 4);
  const auto file = dir.write("tet.stl", asciiStl({a, c, b, a, b, d, a, d, c, b, c, d}));
  MeshInfo info;
  LoadOptions recentre;
  recentre.recentre_mesh = true;
  const auto pieces = meshPieces(file, kOnes, kIdentity, recentre, &info);
  EXPECT_EQ(info.vertices, 12);
  EXPECT_TRUE(info.mean_vertex.isApprox(Eigen::Vector3d(1, 1, 1), 1e-12));
  EXPECT_TRUE(info.shift.isApprox(Eigen::Vector3d(1, 1, 1), 1e-12));
  EXPECT_TRUE(meshMeanVertex(file).isApprox(Eigen::Vector3d(1, 1, 1), 1e-12));
  ASSERT_EQ(pieces.size(), 1u);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& v : pieces[0].polytope.vertices()) mean += v;
  EXPECT_LE((mean / 4.0).norm(), 1e-12);

  const RigidBody body = loadBody(file, recentre);
  expectBox(body.box(), {-1, -1, -1}, {3, 3, 3});
  EXPECT_EQ(body.name(), "tet");
  const RigidBody unshifted = loadBody(file);
  expectBox(unshifted.box(), {0, 0, 0}, {4, 4, 4});
  // Worlds are never recentred.
  expectBox(loadWorld(file, recentre).box(), {0, 0, 0}, {4, 4, 4});
}

TEST(MeshErrors, MissingFile) {
  TempDir dir;
  expectSceneError([&] { meshPieces(dir.path() / "none.stl", kOnes, kIdentity, {}); }, {"none.stl", "file not found"});
}

TEST(MeshErrors, Folder) {
  TempDir dir;
  std::filesystem::create_directories(dir.path() / "sub.stl");
  expectSceneError([&] { loadWorld(dir.path() / "sub.stl"); }, {"sub.stl", "not a regular file"});
}

TEST(MeshErrors, EmptyFile) {
  TempDir dir;
  const auto file = dir.write("empty.stl", "");
  expectSceneError([&] { loadWorld(file); }, {"empty.stl", "cannot read the mesh (assimp: "});
}

TEST(MeshErrors, UnsupportedFormat) {
  TempDir dir;
  const auto file = dir.write("notes.txt", "this is not a mesh\n");
  expectSceneError([&] { loadBody(file); }, {"notes.txt", "cannot read the mesh (assimp: "});
}

TEST(MeshErrors, GarbageInAMeshExtension) {
  TempDir dir;
  const auto file = dir.write("junk.ply", "ply\nformat nonsense\n");
  expectSceneError([&] { loadBody(file); }, {"junk.ply", "assimp"});
}

TEST(MeshErrors, NoTriangles) {
  TempDir dir;
  const auto file = dir.write("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n");
  expectSceneError([&] { loadBody(file); }, {"lines.obj", "the mesh has no triangles"});
}

TEST(MeshErrors, AllTrianglesDegenerate) {
  TempDir dir;
  const auto file = dir.write("flat.stl", asciiStl({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {0, 0, 0}, {0, 0, 1}, {0, 0, 3}}));
  expectSceneError([&] { loadWorld(file); }, {"flat.stl", "all 2 triangles are degenerate"});
}

TEST(MeshErrors, NonFiniteScale) {
  TempDir dir;
  const auto file = dir.write("cube.stl", asciiStl(boxTriangles({0, 0, 0}, {1, 1, 1})));
  expectSceneError([&] { meshPieces(file, Eigen::Vector3d(1, std::nan(""), 1), kIdentity, {}); },
                   {"cube.stl", "scale"});
}

}  // namespace
}  // namespace mddual::scene
