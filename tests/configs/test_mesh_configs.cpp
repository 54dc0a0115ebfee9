// The mesh configs of scripts/make_configs.py (OMPL.app's sizes and shapes,
// our own geometry): each loads through the project's loaders (OBJ, STL and
// COLLADA), its robot and world are single-component, closed, non-convex
// triangle meshes of the stated sizes, its start and goal are collision-free,
// and the witness path written beside it is collision-free when checked densely
// (so the problem is solvable). Collisions are checked piece by piece with the
// core's intersect(), not with the checkers under test.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <numeric>

#include "mddual/constants.h"
#include "mddual/query.h"
#include "mddual/scene/loaders.h"
#include "mddual/scene/problem_config.h"
#include "witness_path.h"

namespace mddual::scene {
namespace {

namespace fs = std::filesystem;

const fs::path kConfigs = MDDUAL_CONFIGS_DIR;

/// Largest displacement of any robot point between two consecutive states of
/// the dense witness check (m): a fifth of the thinnest wall or robot part of
/// these configs (0.125 m partitions), so that no obstacle is stepped over.
constexpr double kWitnessStep = 0.025;
/// Largest distance (m) from the origin of a robot's mesh file, where the
/// generator put the mean of its vertices, to the mean vertex the loader
/// computes from assimp's vertex set (measured: at most 0.052 m, the couch).
constexpr double kShiftLimit = 0.1;
/// Start and goal of the cfg equal the witness path's ends to this (m, rad):
/// both are written from the same numbers with 6 decimals.
constexpr double kPoseMatch = 1e-5;

struct MeshConfig {
  std::string name;
  SpaceKind space;
  std::array<int, 2> robot_triangles;  ///< allowed range, inclusive
  std::array<int, 2> world_triangles;
  Eigen::AlignedBox3d world_box;  ///< the world's bounding box as designed (m)
  PoseSpec blocked;               ///< a pose of the robot that overlaps the world
};

std::ostream& operator<<(std::ostream& out, const MeshConfig& c) {
  return out << c.name;
}

Eigen::AlignedBox3d box(double x0, double y0, double z0, double x1, double y1, double z1) {
  return Eigen::AlignedBox3d(Eigen::Vector3d(x0, y0, z0), Eigen::Vector3d(x1, y1, z1));
}

PoseSpec at(double x, double y, double z, const Eigen::Vector3d& axis = Eigen::Vector3d::UnitZ(), double theta = 0) {
  return PoseSpec{Eigen::Vector3d(x, y, z), axis, theta};
}

const std::vector<MeshConfig>& meshConfigs() {
  const double kHalfTurn = 0.5 * kPi;
  static const std::vector<MeshConfig> configs = {
      // Blocked: across the cup's wall; turned across the slot; across a
      // partition; across the hall's wall; across the maze's outer wall.
      {"bugtrap", SpaceKind::kSE3, {200, 300}, {4500, 5500}, box(-5, -5, 0, 5, 5, 8), at(4.75, 0, 4)},
      {"twistycool",
       SpaceKind::kSE3,
       {50, 70},
       {170, 230},
       box(-0.125, -7, -7, 0.125, 7, 7),
       at(0, 0, 0, Eigen::Vector3d::UnitX(), kHalfTurn)},
      {"cubicles_mesh",
       SpaceKind::kSE3,
       {30, 50},
       {500, 700},
       box(-0.25, -0.25, -0.25, 16.25, 12.25, 3.25),
       at(4, 2, 1)},
      {"apartment",
       SpaceKind::kSE3,
       {2700, 3300},
       {36000, 44000},
       box(-0.25, -0.25, -0.25, 14.25, 10.25, 2.875),
       at(7, 4.06, 0.5)},
      {"maze_planar",
       SpaceKind::kSE2,
       {50, 80},
       {1800, 2200},
       box(-0.125, -0.125, -0.5, 20.125, 20.125, 0.5),
       at(1, 0, 0)},
  };
  return configs;
}

/// True when the robot at X_WR touches or overlaps a world piece.
bool collides(const ProblemScene& s, const Eigen::Isometry3d& X_WR) {
  std::vector<int> candidates;
  s.world.candidates(transformedBox(s.robot.box(), X_WR), &candidates);
  if (candidates.empty()) return false;
  for (const Piece& r : s.robot.pieces()) {
    candidates.clear();
    s.world.candidates(transformedBox(r.box, X_WR), &candidates);
    for (int w : candidates) {
      const IntersectInput in{&s.world.pieces()[w].polytope, Eigen::Isometry3d::Identity(), &r.polytope, X_WR};
      if (intersect(in).intersecting) return true;
    }
  }
  return false;
}

/// What the triangle pieces of a loaded mesh form: their count, the number of
/// edges not shared by exactly two triangles, the connected components
/// (triangles joined across shared edges), and whether some triangle has
/// vertices strictly on both sides of its plane (then the mesh is not convex).
struct Topology {
  int triangles = 0;
  int open_or_branching_edges = 0;
  int components = 0;
  bool has_reflex_triangle = false;
};

Topology topology(const std::vector<Piece>& pieces) {
  std::map<std::array<double, 3>, int> ids;
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> tris;
  for (const Piece& p : pieces) {
    EXPECT_EQ(p.kind, PieceKind::kTriangle) << p.origin;
    EXPECT_EQ(p.polytope.numVertices(), 3) << p.origin;
    if (p.polytope.numVertices() != 3) continue;
    std::array<int, 3> t{};
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d& v = p.polytope.vertex(c);
      const auto [it, inserted] = ids.emplace(std::array<double, 3>{v.x(), v.y(), v.z()}, static_cast<int>(ids.size()));
      if (inserted) points.push_back(v);
      t[static_cast<std::size_t>(c)] = it->second;
    }
    tris.push_back(t);
  }
  Topology out;
  out.triangles = static_cast<int>(tris.size());
  std::map<std::pair<int, int>, std::vector<int>> edges;
  for (int t = 0; t < out.triangles; ++t) {
    for (int c = 0; c < 3; ++c) {
      const int a = tris[static_cast<std::size_t>(t)][static_cast<std::size_t>(c)];
      const int b = tris[static_cast<std::size_t>(t)][static_cast<std::size_t>((c + 1) % 3)];
      edges[{std::min(a, b), std::max(a, b)}].push_back(t);
    }
  }
  std::vector<int> parent(static_cast<std::size_t>(out.triangles));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&parent](int i) {
    while (parent[static_cast<std::size_t>(i)] != i) i = parent[static_cast<std::size_t>(i)];
    return i;
  };
  for (const auto& [edge, owners] : edges) {
    if (owners.size() != 2) ++out.open_or_branching_edges;
    for (std::size_t k = 1; k < owners.size(); ++k) parent[static_cast<std::size_t>(root(owners[k]))] = root(owners[0]);
  }
  for (int t = 0; t < out.triangles; ++t) out.components += root(t) == t ? 1 : 0;

  Eigen::AlignedBox3d bounds;
  bounds.setEmpty();
  for (const Eigen::Vector3d& p : points) bounds.extend(p);
  const double tol = 1e-6 * bounds.diagonal().norm();
  for (const auto& t : tris) {
    const Eigen::Vector3d& a = points[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d n =
        (points[static_cast<std::size_t>(t[1])] - a).cross(points[static_cast<std::size_t>(t[2])] - a).normalized();
    bool above = false;
    bool below = false;
    for (const Eigen::Vector3d& p : points) {
      const double d = n.dot(p - a);
      above = above || d > tol;
      below = below || d < -tol;
      if (above && below) break;
    }
    if (above && below) {
      out.has_reflex_triangle = true;
      break;
    }
  }
  return out;
}

bool samePose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm() <= kPoseMatch &&
         Eigen::Quaterniond(a.linear()).angularDistance(Eigen::Quaterniond(b.linear())) <= kPoseMatch;
}

/// The cfg's problem: space, planners, limits, start and goal free, the
/// files read unchanged.
void checkProblem(const MeshConfig& c, const ProblemScene& s) {
  const ProblemConfig config = readProblemConfig(kConfigs / c.name / (c.name + ".cfg"));
  EXPECT_EQ(config.name, c.name);
  EXPECT_EQ(config.space, c.space);
  std::vector<std::string> planners;
  for (const PlannerSpec& p : config.planners) planners.push_back(p.name);
  EXPECT_EQ(planners, (std::vector<std::string>{"rrtconnect", "rrt", "kpiece"}));
  EXPECT_GE(config.time_limit, 10.0);
  EXPECT_GE(config.run_count, 5);
  EXPECT_TRUE(s.bounds.contains(s.start.translation()));
  EXPECT_TRUE(s.bounds.contains(s.goal.translation()));
  EXPECT_FALSE(collides(s, s.start)) << "start collides";
  EXPECT_FALSE(collides(s, s.goal)) << "goal collides";
  EXPECT_TRUE(collides(s, toIsometry(c.blocked, c.space))) << "the check misses an overlap";
  // The files are read unchanged (no axis conversion, no scaling).
  EXPECT_TRUE(s.world.box().isApprox(c.world_box, 1e-6))
      << s.world.box().min().transpose() << " / " << s.world.box().max().transpose();
  // The robot's frame is its mean vertex, which the generator put at the
  // origin of the file: the loader's shift is within centimetres of it
  // (assimp keeps a vertex once per face normal around it, so its mean
  // weighs the vertices differently).
  EXPECT_LT(s.robot_shift.norm(), kShiftLimit) << s.robot_shift.transpose();
}

/// Robot and world: single, closed, non-convex components of the stated sizes.
void checkMeshes(const MeshConfig& c, const ProblemScene& s) {
  for (const bool robot : {true, false}) {
    SCOPED_TRACE(robot ? "robot" : "world");
    const Topology t = topology(robot ? s.robot.pieces() : s.world.pieces());
    const std::array<int, 2>& range = robot ? c.robot_triangles : c.world_triangles;
    EXPECT_GE(t.triangles, range[0]);
    EXPECT_LE(t.triangles, range[1]);
    EXPECT_EQ(t.open_or_branching_edges, 0);
    EXPECT_EQ(t.components, 1);
    EXPECT_TRUE(t.has_reflex_triangle);
  }
  // The loader kept every triangle (none degenerate) and found the meshes
  // non-convex (one kTriangle piece per triangle, checked above).
  const ProblemConfig config = readProblemConfig(kConfigs / c.name / (c.name + ".cfg"));
  MeshInfo info;
  meshPieces(resolvePath(config, config.robot), Eigen::Vector3d::Ones(), Eigen::Isometry3d::Identity(), LoadOptions{},
             &info);
  EXPECT_FALSE(info.convex);
  EXPECT_EQ(info.degenerate_triangles, 0);
  EXPECT_EQ(static_cast<std::size_t>(info.triangles), s.robot.pieces().size());
}

/// witness_path.txt goes from start to goal without a collision.
void checkWitnessPath(const MeshConfig& c, const ProblemScene& s) {
  const std::vector<Eigen::Isometry3d> path = testing::witnessPath(kConfigs / c.name / "witness_path.txt", c.space);
  ASSERT_GE(path.size(), 2u);
  EXPECT_TRUE(samePose(path.front(), s.start));
  EXPECT_TRUE(samePose(path.back(), s.goal));
  int checked = 0;
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    const Eigen::Quaterniond q0(path[k].linear());
    const Eigen::Quaterniond q1(path[k + 1].linear());
    const Eigen::Vector3d p0 = path[k].translation();
    const Eigen::Vector3d p1 = path[k + 1].translation();
    const double travel = (p1 - p0).norm() + s.robot.radius() * q0.angularDistance(q1);
    const int steps = std::max(1, static_cast<int>(std::ceil(travel / kWitnessStep)));
    for (int i = 0; i <= steps; ++i) {
      const double t = static_cast<double>(i) / steps;
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
      X.linear() = q0.slerp(t, q1).toRotationMatrix();
      X.translation() = p0 + t * (p1 - p0);
      EXPECT_TRUE(s.bounds.contains(X.translation())) << "segment " << k << ", t = " << t;
      ASSERT_FALSE(collides(s, X)) << "segment " << k << ", t = " << t;
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
}

class MeshConfigs : public ::testing::TestWithParam<MeshConfig> {};

// One test per config, so that each (large) scene is loaded once per process.
TEST_P(MeshConfigs, LoadsWithValidMeshesStartGoalAndWitnessPath) {
  const MeshConfig& c = GetParam();
  const ProblemScene s = loadProblemScene(readProblemConfig(kConfigs / c.name / (c.name + ".cfg")));
  {
    SCOPED_TRACE("problem");
    checkProblem(c, s);
  }
  {
    SCOPED_TRACE("meshes");
    checkMeshes(c, s);
  }
  {
    SCOPED_TRACE("witness path");
    checkWitnessPath(c, s);
  }
}

// twistycool's slot (1.5 x 0.8125 m) must make the bar screw: unturned, the
// bar's section in the wall turns with its twist (pi/4 per metre along it),
// and with an end in the wall (position +-0.875 m: sections turned by 0.59
// to 0.79 rad) it is 0.76 to 0.88 m tall, more than the slot; turned by the
// screw angle (pi/4 * position) its sections in the wall are within 0.1 rad
// of flat (at most 0.35 m tall). Near the middle (position 0.5 m,
// at most 0.69 m tall) the slot lets it through unturned, which the old
// 0.6875 m slot did not (scripts/make_configs.py, twistycool()).
TEST(TwistycoolSlot, TheBarMustScrewThroughAndTheSlotAllowsIt) {
  const ProblemScene s = loadProblemScene(readProblemConfig(kConfigs / "twistycool" / "twistycool.cfg"));
  const double screw = kPi / 4;  // rad per metre of the bar's position (twist / length)
  const auto pose = [](double x, double beta) {
    return toIsometry(PoseSpec{Eigen::Vector3d(x, 0, 0), Eigen::Vector3d::UnitX(), beta}, SpaceKind::kSE3);
  };
  for (const double x : {-0.875, 0.875}) {
    SCOPED_TRACE("position " + std::to_string(x));
    EXPECT_TRUE(collides(s, pose(x, 0.0))) << "unturned, the bar's end fits the slot: the twist is not needed";
    EXPECT_FALSE(collides(s, pose(x, screw * x))) << "screwed, the bar does not pass";
  }
  EXPECT_FALSE(collides(s, pose(0.5, 0.0))) << "the slot is narrower than designed (0.8125 m)";
  // The height itself: unturned at 0.7 m the bar is 0.798 m tall in the wall
  // (fits), at 0.75 m 0.823 m (does not): the slot is between the two.
  EXPECT_FALSE(collides(s, pose(0.7, 0.0))) << "the slot is lower than 0.798 m";
  EXPECT_TRUE(collides(s, pose(0.75, 0.0))) << "the slot is higher than 0.823 m";
}

INSTANTIATE_TEST_SUITE_P(Configs, MeshConfigs, ::testing::ValuesIn(meshConfigs()),
                         [](const ::testing::TestParamInfo<MeshConfig>& p) { return p.param.name; });

}  // namespace
}  // namespace mddual::scene
