// loadProblemScene: OMPL.app's robot recentring (z kept in the plane), the
// bounds (volume, or the world's box widened to hold start and goal), poses,
// and errors that name the cfg and the file.
#include <gtest/gtest.h>

#include <cmath>

#include "mddual/scene/problem_config.h"
#include "scene_test_util.h"

namespace mddual::scene {
namespace {

using testing::asciiStl;
using testing::boxTriangles;
using testing::expectSceneError;
using testing::TempDir;

void expectSceneBox(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  EXPECT_LE((box.min() - lo).cwiseAbs().maxCoeff(), 1e-9) << box.min().transpose() << " vs " << lo.transpose();
  EXPECT_LE((box.max() - hi).cwiseAbs().maxCoeff(), 1e-9) << box.max().transpose() << " vs " << hi.transpose();
}

/// Robot: a box mesh [2,4]x[1,3]x[1,2] (mean vertex (3, 2, 1.5)); world: a
/// URDF box 10 x 10 x 1 centred at (0, 0, 0.5).
void writeAssets(const TempDir& dir) {
  dir.write("assets/robot.stl", asciiStl(boxTriangles({2, 1, 1}, {4, 3, 2})));
  dir.write("assets/world.urdf", R"(<robot name="floor"><link name="slab">
    <collision><origin xyz="0 0 0.5"/><geometry><box size="10 10 1"/></geometry></collision>
  </link></robot>)");
  dir.write("assets/arm.urdf", R"(<robot name="arm"><link name="base">
    <collision><origin xyz="0 0 1"/><geometry><box size="1 1 2"/></geometry></collision>
  </link></robot>)");
}

const char* kPlanarProblem = R"([problem]
robot = assets/robot.stl
world = assets/world.urdf
start.x = 0.5
start.y = -1.25
start.theta = 0.5
goal.x = 40
goal.y = 3.5
goal.theta = 0.5
)";

TEST(ProblemScene, PlanarMeshRobotIsRecentredInXYOnly) {
  TempDir dir;
  writeAssets(dir);
  const ProblemConfig c = readProblemConfig(dir.write("planar.cfg", kPlanarProblem));
  const ProblemScene s = loadProblemScene(c);
  EXPECT_EQ(s.space, SpaceKind::kSE2);
  EXPECT_TRUE(s.robot_shift.isApprox(Eigen::Vector3d(3, 2, 0)));
  expectSceneBox(s.robot.box(), {-1, -1, 1}, {1, 1, 2});  // z not shifted (OMPL.app zeroes the centre's z in 2D)
  expectSceneBox(s.world.box(), {-5, -5, 0}, {5, 5, 1});
  // No volume: the world's box widened to hold start and goal; z = [0, 0].
  expectSceneBox(s.bounds, {-5, -5, 0}, {40, 5, 0});
  EXPECT_TRUE(s.start.translation().isApprox(Eigen::Vector3d(0.5, -1.25, 0)));
  EXPECT_TRUE(s.start.linear().isApprox(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix()));
  EXPECT_TRUE(s.goal.translation().isApprox(Eigen::Vector3d(40, 3.5, 0)));
}

TEST(ProblemScene, TranslationOnlyPlanar) {
  TempDir dir;
  writeAssets(dir);
  const ProblemConfig c =
      readProblemConfig(dir.write("t.cfg", std::string(kPlanarProblem) + "translation_only = on\n"));
  const ProblemScene s = loadProblemScene(c);
  EXPECT_EQ(s.space, SpaceKind::kR2);
  EXPECT_TRUE(s.goal.linear().isApprox(s.start.linear()));
  expectSceneBox(s.bounds, {-5, -5, 0}, {40, 5, 0});
}

TEST(ProblemScene, SpatialMeshRobotIsRecentredOnItsMeanVertex) {
  TempDir dir;
  writeAssets(dir);
  const auto cfg = dir.write("spatial.cfg", R"([problem]
robot = assets/robot.stl
world = assets/robot.stl
start.x = 1
start.y = 2
start.z = 3
start.axis.x = 0
start.axis.y = 1
start.axis.z = 0
start.theta = 1.0
goal.x = -1
goal.y = -2
goal.z = 30
goal.axis.x = 0
goal.axis.y = 1
goal.axis.z = 0
goal.theta = 1.0
translation_only = true
)");
  const ProblemScene s = loadProblemScene(readProblemConfig(cfg));
  EXPECT_EQ(s.space, SpaceKind::kR3);
  EXPECT_TRUE(s.robot_shift.isApprox(Eigen::Vector3d(3, 2, 1.5)));
  expectSceneBox(s.robot.box(), {-1, -1, -0.5}, {1, 1, 0.5});
  expectSceneBox(s.world.box(), {2, 1, 1}, {4, 3, 2});  // the world is not shifted
  expectSceneBox(s.bounds, {-1, -2, 1}, {4, 3, 30});
  EXPECT_TRUE(s.start.linear().isApprox(Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitY()).toRotationMatrix()));
}

TEST(ProblemScene, UrdfRobotAndVolume) {
  TempDir dir;
  writeAssets(dir);
  const auto cfg = dir.write("urdf.cfg", R"([problem]
robot = assets/arm.urdf
world = assets/world.urdf
start.x = 0
start.y = 0
start.theta = 0
goal.x = 1
goal.y = 1
goal.theta = 0
volume.min.x = -20
volume.min.y = -10
volume.max.x = 20
volume.max.y = 10
)");
  const ProblemScene s = loadProblemScene(readProblemConfig(cfg));
  EXPECT_TRUE(s.robot_shift.isZero());
  expectSceneBox(s.robot.box(), {-0.5, -0.5, 0}, {0.5, 0.5, 2});
  expectSceneBox(s.bounds, {-20, -10, 0}, {20, 10, 0});
  EXPECT_EQ(s.robot.name(), "arm");
}

// The loaders' warnings reach the scene, from a mesh robot and from a mesh
// inside a URDF world, each naming its file (and the URDF element).
TEST(ProblemScene, LoadWarningsAreCollected) {
  TempDir dir;
  // Two boxes side by side (not convex) plus a triangle with a repeated corner.
  std::vector<Eigen::Vector3d> tri = boxTriangles({0, 0, 0}, {1, 1, 1});
  for (const auto& p : boxTriangles({2, 0, 0}, {3, 1, 1})) tri.push_back(p);
  tri.insert(tri.end(), {{0, 0, 0}, {0, 0, 0}, {1, 1, 1}});
  dir.write("assets/two.stl", asciiStl(tri));
  dir.write("assets/world.urdf", R"(<robot name="w"><link name="l">
    <collision><geometry><mesh filename="two.stl"/></geometry></collision></link></robot>)");
  const auto cfg = dir.write("warn.cfg", R"([problem]
robot = assets/two.stl
world = assets/world.urdf
start.x = 10
start.y = 0
start.theta = 0
goal.x = 20
goal.y = 0
goal.theta = 0
)");
  const ProblemScene s = loadProblemScene(readProblemConfig(cfg));
  // Per mesh: it is closed (two closed boxes) and loaded as triangles, so
  // hollow; and a triangle is skipped.
  ASSERT_EQ(s.warnings.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    if (i >= 2) {
      EXPECT_EQ(s.warnings[i].rfind("world.urdf: link 'l', collision 0: ", 0), 0u) << s.warnings[i];
    }
    const char* expected = i % 2 == 0 ? "two.stl: closed mesh of 25 triangles loaded as a hollow triangle soup"
                                      : "two.stl: skipped 1 of 25 triangles";
    EXPECT_NE(s.warnings[i].find(expected), std::string::npos) << s.warnings[i];
  }
  EXPECT_EQ(s.robot.pieces().size(), 24u);
  EXPECT_EQ(s.world.pieces().size(), 24u);
  // The counts behind the summary: one mesh each, a closed triangle soup.
  for (const MeshCounts& m : {s.robot_meshes, s.world_meshes}) {
    EXPECT_EQ(m.meshes, 1);
    EXPECT_EQ(m.convex, 0);
    EXPECT_EQ(m.soups, 1);
    EXPECT_EQ(m.closed_soups, 1);
  }
  EXPECT_EQ(sceneSummary(s),
            "robot 'two': 24 pieces (24 triangles), 1 mesh (1 triangle soup, 1 closed: hollow); "
            "world 'w': 24 pieces (24 triangles), 1 mesh (1 triangle soup, 1 closed: hollow)");
}

// The cfg's mesh_convex_tolerance reaches the loader: a world box whose
// corner (1, 0, 1) is raised by 1.7e-3 (10 times the default tolerance of
// its size) is a closed, hollow soup by default and one convex piece with a
// tolerance of 1e-2; the summary counts it either way.
TEST(ProblemScene, MeshConvexToleranceFromTheCfg) {
  TempDir dir;
  writeAssets(dir);
  std::vector<Eigen::Vector3d> tri = boxTriangles({0, 0, 0}, {1, 1, 1});
  for (Eigen::Vector3d& p : tri) {
    if (p == Eigen::Vector3d(1, 0, 1)) p.z() += 10.0 * kDefaultMeshConvexTolerance * std::sqrt(3.0);
  }
  dir.write("assets/rock.stl", asciiStl(tri));
  std::string text = kPlanarProblem;
  text.replace(text.find("assets/world.urdf"), 17, "assets/rock.stl");
  const ProblemScene soup = loadProblemScene(readProblemConfig(dir.write("soup.cfg", text)));
  EXPECT_EQ(soup.world.pieces().size(), 12u);
  EXPECT_EQ(soup.world_meshes.closed_soups, 1);
  EXPECT_EQ(soup.robot_meshes.convex, 1);
  ASSERT_EQ(soup.warnings.size(), 1u);
  EXPECT_NE(soup.warnings[0].find("rock.stl: closed mesh of 12 triangles loaded as a hollow triangle soup"),
            std::string::npos)
      << soup.warnings[0];
  EXPECT_EQ(sceneSummary(soup),
            "robot 'robot': 1 piece (1 convex), 1 mesh (1 convex); "
            "world 'rock': 12 pieces (12 triangles), 1 mesh (1 triangle soup, 1 closed: hollow)");

  const ProblemScene convex =
      loadProblemScene(readProblemConfig(dir.write("convex.cfg", text + "mesh_convex_tolerance = 1e-2\n")));
  EXPECT_EQ(convex.world.pieces().size(), 1u);
  EXPECT_EQ(convex.world_meshes.convex, 1);
  EXPECT_EQ(convex.world_meshes.closed_soups, 0);
  EXPECT_TRUE(convex.warnings.empty());
  EXPECT_EQ(
      sceneSummary(convex),
      "robot 'robot': 1 piece (1 convex), 1 mesh (1 convex); world 'rock': 1 piece (1 convex), 1 mesh (1 convex)");
  // The cfg's value overrides the caller's options; without it, they apply.
  LoadOptions strict;
  strict.mesh_convex_tolerance = 0.0;
  EXPECT_EQ(loadProblemScene(readProblemConfig(dir.path() / "convex.cfg"), strict).world.pieces().size(), 1u);
  LoadOptions loose;
  loose.mesh_convex_tolerance = 1e-2;
  EXPECT_EQ(loadProblemScene(readProblemConfig(dir.path() / "soup.cfg"), loose).world.pieces().size(), 1u);
  // A URDF world counts its primitives as pieces, not meshes.
  const ProblemScene plain = loadProblemScene(readProblemConfig(dir.write("plain.cfg", kPlanarProblem)));
  EXPECT_EQ(sceneSummary(plain),
            "robot 'robot': 1 piece (1 convex), 1 mesh (1 convex); world 'floor': 1 piece (1 convex)");
}

TEST(ProblemSceneErrors, TranslationOnlyConfigBuiltInCodeWithARotatedGoal) {
  TempDir dir;
  writeAssets(dir);
  ProblemConfig c = readProblemConfig(dir.write("t.cfg", std::string(kPlanarProblem) + "translation_only = true\n"));
  c.goal.theta = 1.0;
  expectSceneError([&] { loadProblemScene(c); }, {"t.cfg: translation_only", "rotation differs"});
}

TEST(ProblemSceneErrors, MissingRobotNamesTheCfgAndTheFile) {
  TempDir dir;
  writeAssets(dir);
  std::string text = kPlanarProblem;
  text.replace(text.find("assets/robot.stl"), 16, "assets/car.stl");
  const ProblemConfig c = readProblemConfig(dir.write("scene.cfg", text));
  expectSceneError([&] { loadProblemScene(c); }, {"scene.cfg: ", "car.stl", "file not found"});
}

TEST(ProblemSceneErrors, MalformedWorldNamesTheCfgAndTheFile) {
  TempDir dir;
  writeAssets(dir);
  dir.write("assets/world.urdf", "<robot name='w'>");
  const ProblemConfig c = readProblemConfig(dir.write("scene.cfg", kPlanarProblem));
  expectSceneError([&] { loadProblemScene(c); }, {"scene.cfg: ", "world.urdf", "not a valid URDF"});
}

}  // namespace
}  // namespace mddual::scene
