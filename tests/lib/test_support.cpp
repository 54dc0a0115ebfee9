// Support-vertex queries: hill climbing and the Dobkin-Kirkpatrick hierarchy
// against an exhaustive scan, and tie sets.
#include <gtest/gtest.h>

#include <algorithm>

#include "mddual/generators.h"
#include "mddual/polytope.h"

namespace mddual {
namespace {

double bestValue(const ConvexPolytope& p, const Eigen::Vector3d& d) {
  double best = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& v : p.vertices()) best = std::max(best, d.dot(v));
  return best;
}

void expectExactSupports(const ConvexPolytope& p, std::uint64_t seed, int directions) {
  generators::Rng rng(seed);
  for (int i = 0; i < directions; ++i) {
    const Eigen::Vector3d d = generators::randomUnitVector(rng);
    const double best = bestValue(p, d);
    const int hint = std::uniform_int_distribution<int>(0, p.numVertices() - 1)(rng);
    EXPECT_EQ(d.dot(p.vertex(p.supportVertexHillClimb(d, hint))), best);
    EXPECT_EQ(d.dot(p.vertex(p.supportVertexHierarchy(d))), best);
    EXPECT_EQ(d.dot(p.vertex(p.supportVertex(d))), best);
  }
}

TEST(Support, ExactOnPaperPolytopes) {
  for (const char* name : {"P1", "P2", "P3", "P4", "P5", "P6"}) {
    SCOPED_TRACE(name);
    expectExactSupports(ConvexPolytope::fromPoints(generators::paperPolytope(name)), 11, 2000);
  }
}

TEST(Support, HierarchyOnLargeHullsBeatsClimbing) {
  generators::Rng rng(12);
  for (int n : {1000, 5000}) {
    SCOPED_TRACE(n);
    const ConvexPolytope p = ConvexPolytope::fromPoints(generators::blob(n, {1.0, 2.0, 3.0}, rng));
    ASSERT_GT(p.hierarchyDepth(), 0);
    expectExactSupports(p, 13, 500);
    // A cold hierarchical query evaluates fewer vertices than a climb from a
    // fixed start, and a small fraction of them (about 65 of 1000 and 83 of
    // 5000 on these hulls).
    SupportStats hierarchy;
    SupportStats climb;
    for (int i = 0; i < 200; ++i) {
      const Eigen::Vector3d d = generators::randomUnitVector(rng);
      p.supportVertexHierarchy(d, &hierarchy);
      p.supportVertexHillClimb(d, 0, &climb);
    }
    EXPECT_LT(hierarchy.vertices_visited, climb.vertices_visited);
    EXPECT_LT(hierarchy.vertices_visited / 200, p.numVertices() / 10);
  }
}

TEST(Support, DirectionTableStartsNextToTheAnswer) {
  // Cold queries start from the direction table's vertex: on the paper's
  // 500-vertex ellipsoid they evaluate a couple of neighbourhoods, not a
  // path across the polytope (measured: about 14 vertices per query).
  const ConvexPolytope p = ConvexPolytope::fromPoints(generators::paperPolytope("P4"));
  generators::Rng rng(16);
  SupportStats table;
  SupportStats climb;
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d d = generators::randomUnitVector(rng);
    p.supportVertex(d, -1, &table);
    p.supportVertexHillClimb(d, 0, &climb);
  }
  EXPECT_LT(table.vertices_visited / 1000, 25);
  EXPECT_LT(table.vertices_visited * 3, climb.vertices_visited);
}

TEST(Support, SmallPolytopesHaveNoHierarchy) {
  const ConvexPolytope cube = ConvexPolytope::fromPoints(generators::box({1, 1, 1}));
  EXPECT_EQ(cube.hierarchyDepth(), 0);
  expectExactSupports(cube, 14, 200);
}

TEST(Support, FlatPolygonWithManyVertices) {
  generators::Points ring;
  for (int i = 0; i < 400; ++i) {
    const double t = 2.0 * 3.14159265358979 * i / 400;
    ring.emplace_back(std::cos(t), 2.0 * std::sin(t), 0.5);
  }
  const ConvexPolytope p = ConvexPolytope::fromPoints(ring);
  ASSERT_TRUE(p.isFlat());
  EXPECT_GT(p.hierarchyDepth(), 0);
  expectExactSupports(p, 15, 1000);
}

TEST(Support, TiesSpanTheSupportingFeature) {
  const ConvexPolytope cube = ConvexPolytope::fromPoints(generators::box({1, 1, 1}));
  std::vector<int> ties;
  cube.supportTies(Eigen::Vector3d::UnitZ(), cube.supportVertex(Eigen::Vector3d::UnitZ()), 1e-12, &ties);
  EXPECT_EQ(ties.size(), 4u);  // the top face
  ties.clear();
  const Eigen::Vector3d d(1, 1, 0);
  cube.supportTies(d, cube.supportVertex(d), 1e-12, &ties);
  EXPECT_EQ(ties.size(), 2u);  // an edge
  ties.clear();
  const Eigen::Vector3d c(1, 2, 3);
  cube.supportTies(c, cube.supportVertex(c), 1e-12, &ties);
  EXPECT_EQ(ties.size(), 1u);  // a vertex
}

}  // namespace
}  // namespace mddual
