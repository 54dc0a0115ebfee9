// Pairs that exposed bugs while the penetration-depth module was written,
// pinned with full-precision coordinates (world frame, identity poses, as
// printed by toJsonLine / the oracle's failure messages).
#include <gtest/gtest.h>

#include <vector>

#include "mddual/brute_force.h"
#include "mddual/error.h"
#include "mddual/penetration.h"

namespace mddual {
namespace {

using Points = std::vector<Eigen::Vector3d>;

PenetrationResult pdOf(const Points& a_pts, const Points& b_pts, PenetrationMethod method, double delta = 0.0) {
  const ConvexPolytope a = ConvexPolytope::fromPoints(a_pts);
  const ConvexPolytope b = ConvexPolytope::fromPoints(b_pts);
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  return penetrationDepth(PenetrationInput{&a, I, &b, I, method, delta});
}

// Core bug found here (brute force, not this module), fixed by b1bf5b1 ("Hull:
// merge coplanar facets inside qhull"): two unit cubes in the same random
// orientation at an offset of ~2000, B shifted by (0.7, 0.2, 0) in the cubes'
// frame. MinkowskiDifference::build hulls the 64 vertex differences, many of
// them coplanar, and ConvexPolytope::fromPoints rejected qhull's answer with
// "polytope: hull edge 1->2 appears twice" (NumericalError). The fast methods
// answered 0.3 (to 5e-14) all along.
TEST(PenetrationRegressions, BruteForceOnRotatedCubesFarFromTheOrigin) {
  const Points a = {{1000, -2000, 500},
                    {999.102931576218, -1999.7307660462648, 500.35040165697308},
                    {998.97730339610393, -1999.1259136564652, 499.56403587254778},
                    {999.87437181988594, -1999.3951476102002, 499.21363421557476},
                    {1000.2980294687187, -1998.6457033729753, 499.72240482388042},
                    {1000.4236576488329, -1999.2505557627751, 500.50877060830572},
                    {999.40096104493671, -1998.37646941924, 500.0728064808535},
                    {999.52658922505088, -1998.9813218090399, 500.85917226527874}};
  const Points b = {{999.73264658916378, -1999.5227565363932, 499.51962428229695},
                    {998.83557816538178, -1999.253522582658, 499.87002593927002},
                    {998.70994998526771, -1998.6486701928584, 499.08366015484472},
                    {999.60701840904972, -1998.9179041465934, 498.7332584978717},
                    {1000.0306760578825, -1998.1684599093685, 499.24202910617737},
                    {1000.1563042379967, -1998.7733122991683, 500.02839489060267},
                    {999.13360763410049, -1997.8992259556333, 499.59243076315045},
                    {999.25923581421466, -1998.5040783454331, 500.37879654757569}};
  EXPECT_NEAR(pdOf(a, b, PenetrationMethod::kExact).depth, 0.3, 1e-9);
  EXPECT_NEAR(pdOf(a, b, PenetrationMethod::kBruteForce).depth, 0.3, 1e-9);
}

}  // namespace
}  // namespace mddual
