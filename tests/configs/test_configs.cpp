// Every committed benchmark config parses, loads (robot, world, bounds), and
// poses its robot collision-free at start and goal, checked piece by piece
// with the core's intersect() (not with the checkers under test). The thin-wall
// config's walls are thinner than OMPL's default motion-check resolution.
#include <gtest/gtest.h>

#include <filesystem>

#include "mddual/query.h"
#include "mddual/scene/loaders.h"
#include "mddual/scene/problem_config.h"

namespace mddual::scene {
namespace {

namespace fs = std::filesystem;

const fs::path kConfigs = MDDUAL_CONFIGS_DIR;

/// True when the robot at X_WR touches or overlaps a world piece.
bool collides(const ProblemScene& s, const Eigen::Isometry3d& X_WR) {
  for (const Piece& r : s.robot.pieces()) {
    std::vector<int> candidates;
    s.world.candidates(transformedBox(r.box, X_WR), &candidates);
    for (int w : candidates) {
      const IntersectInput in{&s.world.pieces()[w].polytope, Eigen::Isometry3d::Identity(), &r.polytope, X_WR};
      if (intersect(in).intersecting) return true;
    }
  }
  return false;
}

TEST(Configs, EveryConfigLoadsWithValidStartAndGoal) {
  const std::map<std::string, SpaceKind> expected{{"thin_walls", SpaceKind::kR3},
                                                  {"convex_field", SpaceKind::kR3},
                                                  {"narrow_passage", SpaceKind::kSE3},
                                                  {"maze_se2", SpaceKind::kSE2},
                                                  {"cubicles", SpaceKind::kSE3}};
  int seen = 0;
  for (const auto& [name, space] : expected) {
    SCOPED_TRACE(name);
    const fs::path cfg = kConfigs / name / (name + ".cfg");
    const ProblemConfig config = readProblemConfig(cfg, {"mdd_rrtconnect"});
    EXPECT_EQ(config.name, name);
    EXPECT_EQ(config.space, space);
    EXPECT_FALSE(config.planners.empty());
    const ProblemScene scene = loadProblemScene(config);
    EXPECT_FALSE(scene.world.pieces().empty());
    EXPECT_TRUE(scene.bounds.contains(scene.start.translation()));
    EXPECT_TRUE(scene.bounds.contains(scene.goal.translation()));
    EXPECT_FALSE(collides(scene, scene.start)) << "start collides";
    EXPECT_FALSE(collides(scene, scene.goal)) << "goal collides";
    ++seen;
  }
  EXPECT_EQ(seen, 5);
}

TEST(Configs, ThinWallsAreThinnerThanOmplsDefaultResolution) {
  const ProblemScene scene =
      loadProblemScene(readProblemConfig(kConfigs / "thin_walls/thin_walls.cfg", {"mdd_rrtconnect"}));
  // OMPL's default: longest_valid_segment_fraction 0.01 of the space's
  // maximum extent (the diagonal of the position bounds for R^3).
  const double resolution = 0.01 * scene.bounds.diagonal().norm();
  double thinnest = std::numeric_limits<double>::infinity();
  for (const Piece& p : scene.world.pieces()) thinnest = std::min(thinnest, p.box.sizes().minCoeff());
  EXPECT_LT(thinnest * 10.0, resolution);  // 1 cm against 24.5 cm
}

// Each rock of convex_field is one convex piece, as the configs' README says:
// its OBJ mesh is the triangulated hull of its vertices, so the loader keeps it
// as one solid kConvex piece, not as a hollow soup of triangles (19 rocks with slightly non-planar side faces loaded as
// soups). The README says more: every face is planar as loaded. So each rock is convex with the round-off allowance
// alone (mesh_convex_tolerance = 0), not only within the default tolerance, and is closed.
TEST(Configs, ConvexFieldRocksLoadAsOneConvexPieceEach) {
  constexpr int kRocks = 60;
  LoadOptions exact;
  exact.mesh_convex_tolerance = 0.0;
  for (int i = 0; i < kRocks; ++i) {
    const std::string name = std::string("rock_") + (i < 10 ? "0" : "") + std::to_string(i) + ".obj";
    SCOPED_TRACE(name);
    for (const LoadOptions& options : {LoadOptions{}, exact}) {
      MeshInfo info;
      const std::vector<Piece> pieces = meshPieces(kConfigs / "convex_field/meshes" / name, Eigen::Vector3d::Ones(),
                                                   Eigen::Isometry3d::Identity(), options, &info);
      EXPECT_TRUE(info.convex);
      EXPECT_TRUE(info.closed);
      EXPECT_EQ(info.degenerate_triangles, 0);
      ASSERT_EQ(pieces.size(), 1u);
      EXPECT_EQ(pieces[0].kind, PieceKind::kConvex);
    }
  }
  const ProblemScene scene =
      loadProblemScene(readProblemConfig(kConfigs / "convex_field/convex_field.cfg", {"mdd_rrtconnect"}));
  EXPECT_EQ(scene.world.pieces().size(), static_cast<std::size_t>(kRocks));
  for (const Piece& p : scene.world.pieces()) EXPECT_EQ(p.kind, PieceKind::kConvex) << p.origin;
  EXPECT_TRUE(scene.warnings.empty());
  EXPECT_EQ(scene.world_meshes.meshes, kRocks);
  EXPECT_EQ(scene.world_meshes.convex, kRocks);
  EXPECT_EQ(scene.world_meshes.closed_soups, 0);
}

}  // namespace
}  // namespace mddual::scene
