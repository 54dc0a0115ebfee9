// The paper's benchmark polytopes: vertex counts and size (docs/algorithms.md section 5).
#include <gtest/gtest.h>

#include "mddual/error.h"
#include "mddual/generators.h"
#include "mddual/polytope.h"

namespace mddual {
namespace {

TEST(Generators, PaperPolytopesHaveThePapersSizes) {
  const std::vector<std::pair<const char*, int>> expected{{"P1", 20},  {"P2", 50},  {"P3", 200},
                                                          {"P4", 500}, {"P5", 100}, {"P6", 200}};
  for (const auto& [name, vertices] : expected) {
    SCOPED_TRACE(name);
    const ConvexPolytope p = ConvexPolytope::fromPoints(generators::paperPolytope(name));
    EXPECT_EQ(p.numVertices(), vertices);
    for (const Eigen::Vector3d& v : p.vertices()) EXPECT_LE(v.norm(), 5.0 + 1e-12);
  }
  EXPECT_THROW(generators::paperPolytope("P7"), InvalidInputError);
}

TEST(Generators, SeededRandomnessIsRepeatable) {
  generators::Rng a(42);
  generators::Rng b(42);
  EXPECT_EQ(generators::roundedCubeRandom(10, a), generators::roundedCubeRandom(10, b));
  const Eigen::Matrix3d R = generators::randomRotation(a);
  EXPECT_TRUE((R.transpose() * R).isIdentity(1e-12));
  EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
}

}  // namespace
}  // namespace mddual
