// Pairs that exposed bugs while the penetration-depth module was written,
// pinned with full-precision coordinates (world frame, identity poses, as
// printed by toJsonLine / the oracle's failure messages).
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
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

// Found by the far-from-origin families (not an offset bug: the same at the
// origin): a hexagonal prism against an identical copy. The exact method's
// closest plane was an edge-edge crossing whose normal was off by 6e-6 (its
// depth agreed with the brute force to 3e-12, but the translation left an
// overlap of 3e-7). The final support check now catches it and the explicit
// M answers (stats.brute_fallbacks).
TEST(PenetrationRegressions, IdenticalHexagonalPrisms) {
  const Points a = {{519.69246951265723, 311.90899409413197, -152.51250924184504},
                    {519.66441808280285, 311.90216962377156, -152.50054653364717},
                    {519.64766912012169, 311.96217189848397, -152.50559126143401},
                    {519.67572054997595, 311.96899636884439, -152.5175539696319},
                    {519.65986131100851, 311.90349454451302, -152.46965894850615},
                    {519.64311234832735, 311.96349681922538, -152.47470367629299},
                    {519.69921520803598, 311.97714575994621, -152.49862909268876},
                    {519.71596417071714, 311.91714348523385, -152.49358436490192},
                    {519.7114073989228, 311.91846840597526, -152.4626967797609},
                    {519.68335596906854, 311.91164393561485, -152.45073407156301},
                    {519.69465843624164, 311.97847068068768, -152.46774150754774},
                    {519.66660700638727, 311.97164621032726, -152.45577879934987}};
  const PenetrationResult exact = pdOf(a, a, PenetrationMethod::kExact);
  const PenetrationResult brute = pdOf(a, a, PenetrationMethod::kBruteForce);
  ASSERT_EQ(exact.status, PenetrationStatus::kPenetrating);
  EXPECT_NEAR(exact.depth, brute.depth, 1e-12);
  // A reference independent of both (the exact method answers this pair
  // from the explicit M, as the brute force does): the depth of a body
  // against its own copy is its minimum width, which for a right prism is
  // attained along a face normal (every edge-edge normal of A - A is one:
  // lateral edges are parallel, base edges lie in the bases).
  const ConvexPolytope prism = ConvexPolytope::fromPoints(a);
  double min_width = std::numeric_limits<double>::infinity();
  for (int f = 0; f < prism.numFaces(); ++f) {
    double f_lo = std::numeric_limits<double>::infinity();
    double f_hi = -f_lo;
    for (const Eigen::Vector3d& p : a) {
      f_lo = std::min(f_lo, prism.faceNormal(f).dot(p));
      f_hi = std::max(f_hi, prism.faceNormal(f).dot(p));
    }
    min_width = std::min(min_width, f_hi - f_lo);
  }
  EXPECT_NEAR(exact.depth, min_width, 1e-9);
  // The translation separates: A's extent along the normal is the depth.
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const Eigen::Vector3d& p : a) {
    lo = std::min(lo, exact.normal_W.dot(p));
    hi = std::max(hi, exact.normal_W.dot(p));
  }
  EXPECT_NEAR(hi - lo, exact.depth, 1e-12);
}

// Found by test_far_from_origin (IdenticalAndShiftedCopies, MDDUAL_SWEEP_SEED=1):
// a pentagonal prism of size ~128 about 1.2e6 from the origin against an
// identical copy. The depth and normal were right (the brute force's to all
// digits), but the exact method's Gaussian-map walk lost its region on one arc
// and redid it by testing every edge of B (stats.walk_fallbacks = 1), which
// never happens in exact arithmetic: a lateral edge of B within 1e-12 of
// parallel to the arc's edge of A gave a crossing "behind" the walk's point,
// and the walk stepped back to it, tens of degrees along the arc.
TEST(PenetrationRegressions, IdenticalPentagonalPrismsFarFromTheOrigin) {
  const Points a = {{445853.89464830677, 432701.69839414355, 1119027.382596642},
                    {445917.81859785813, 432682.6299329961, 1119136.626005886},
                    {445930.2282769856, 432756.62027509446, 1119142.2794935},
                    {445866.3043274342, 432775.6887362419, 1119033.0360842561},
                    {446022.49440946395, 432707.6716408849, 1119079.745828771},
                    {445958.5704599126, 432726.7401020323, 1118970.5024195272},
                    {445930.99753680656, 432791.1653628535, 1118997.8822015133},
                    {445994.921486358, 432772.09690170607, 1119107.125610757},
                    {445974.84220374026, 432652.3780133517, 1119097.9780756421},
                    {445910.91825418884, 432671.4464744991, 1118988.7346663985}};
  const PenetrationResult exact = pdOf(a, a, PenetrationMethod::kExact);
  const PenetrationResult brute = pdOf(a, a, PenetrationMethod::kBruteForce);
  ASSERT_EQ(exact.status, PenetrationStatus::kPenetrating);
  EXPECT_NEAR(exact.depth, brute.depth, 1e-9);
  EXPECT_GT(exact.stats.ee_facets, 0);  // the walk ran (pruning did not skip every arc)
  EXPECT_EQ(exact.stats.walk_fallbacks, 0);
  EXPECT_EQ(exact.stats.brute_fallbacks, 0);
}

}  // namespace
}  // namespace mddual
