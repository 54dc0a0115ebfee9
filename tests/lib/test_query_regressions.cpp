// Queries that exposed bugs, pinned with their full-precision inputs (as the
// oracle printed them). Each runs through the oracle (mdd, toi, intersect
// against the brute force, contact point and normal checked) and asserts the
// status the brute force gives.
#include <gtest/gtest.h>

#include "mddual/error.h"
#include "query_oracle.h"

namespace mddual::testing {
namespace {

struct Pinned {
  const char* bug;
  std::vector<Eigen::Vector3d> a;
  std::vector<Eigen::Vector3d> b;
  Eigen::Vector3d direction;
  ContactStatus expected;
};

void check(const Pinned& p) {
  SCOPED_TRACE(p.bug);
  const ConvexPolytope a = ConvexPolytope::fromPoints(p.a);
  const ConvexPolytope b = ConvexPolytope::fromPoints(p.b);
  QueryOracle oracle;
  Tally tally;
  EXPECT_EQ(oracle.check(a, Eigen::Isometry3d::Identity(), b, Eigen::Isometry3d::Identity(), {p.direction}, &tally), 0);
  EXPECT_EQ(
      mdd(DirectionalInput{&a, Eigen::Isometry3d::Identity(), &b, Eigen::Isometry3d::Identity(), p.direction}).status,
      p.expected);
}

TEST(QueryRegressions, GrazingLineIsTouchingNotPenetrating) {
  // Planar (grazing) intervals were classified like interior ones.
  check({"lattice box face to face, direction in the contact plane",
         {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}, {1, 0, 2}, {0, 0, 2}, {1, 1, 2}, {0, 1, 2}},
         {{1, 0, -1}, {1, 2, -1}, {3, 0, -1}, {1, 0, 1}},
         {0, 0, 1},
         ContactStatus::kTouching});
  check({"rotated boxes touching, direction in the contact plane",
         {{-0.71044905929684565, 0.23560862873497546, 3.1128364409666403},
          {-2.2619460706919492, -1.7309764174411213, 1.4619578022446329},
          {1.1351502755424008, -2.9840997267596547, -0.23787112621958206},
          {2.6866472869375047, -1.0175146805835578, 1.4130075125024253},
          {2.2619460706919492, 1.7309764174411213, -1.4619578022446329},
          {-1.1351502755424008, 2.9840997267596547, 0.23787112621958206},
          {0.71044905929684565, -0.23560862873497546, -3.1128364409666403},
          {-2.6866472869375047, 1.0175146805835578, -1.4130075125024253}},
         {{-1.3223277671892064, 4.6564679737580494, 5.6904529947523557},
          {-3.3909904490493443, 2.0343545788565875, 3.4892814764563456},
          {-0.84316818937358162, 1.0945120968676876, 2.2144097801081846},
          {1.2254944924865563, 3.7166254917691504, 4.4155812984041942},
          {1.0131438843637786, 5.0908710407814901, 2.9780986410306651},
          {-1.5346783753119841, 6.0307135227703892, 4.2529703373788266},
          {-1.0555187974963594, 2.4687576458800273, 0.77692712273465547},
          {-3.6033410571721221, 3.4086001278689269, 2.0517988190828165}},
         {0.21235060812277762, -1.3742455490123395, 1.4374826573735291},
         ContactStatus::kTouching});
}

TEST(QueryRegressions, PortalMustCrossTheRayAheadOfTheInteriorPoint) {
  // The centre phase's portal straddled the line behind v0: a line missing M
  // was reported as separated.
  check({"two triangles, line misses M",
         {{2.5403361411287371, 0.17326863666065101, -0.73812824510822339},
          {1.374823391405938, 1.4286775778086622, -0.0020609532731457048},
          {2.7673126416654306, 0.050920372596892138, -0.59557918753564776}},
         {{-1.3362985634600157, -0.68033696657554155, -0.038049457361285448},
          {-0.14564343100798161, -1.3674080932016208, -0.59915198209713949},
          {-0.94473450131443826, 0.076137837005725004, 1.1626176292325217}},
         {-0.97941397427162291, -0.072735789409828278, 0.1883023418345981},
         ContactStatus::kNoContact});
}

TEST(QueryRegressions, SupportOnTheRayWithinRoundOff) {
  // The first support lay on the ray up to round-off (side 2.2e-16, not 0):
  // the portal discovery looped without converging.
  check({"lattice boxes, direction (-2,-1,2)",
         {{0, 0, 0}, {0, 3, 0}, {3, 3, 0}, {3, 0, 0}, {3, 0, 3}, {0, 0, 3}, {3, 3, 3}, {0, 3, 3}},
         {{1, 0, 1}, {1, 2, 1}, {3, 2, 1}, {3, 0, 1}, {3, 0, 3}, {1, 0, 3}, {3, 2, 3}, {1, 2, 3}},
         {-2, -1, 2},
         ContactStatus::kPenetrating});
  check({"boxes touching edge to edge, direction (-2,2,2)",
         {{-1.5, -1.5, -1.5},
          {-1.5, 1.5, -1.5},
          {1.5, 1.5, -1.5},
          {1.5, -1.5, -1.5},
          {1.5, -1.5, 1.5},
          {-1.5, -1.5, 1.5},
          {1.5, 1.5, 1.5},
          {-1.5, 1.5, 1.5}},
         {{-4.5, 1.5, -1},
          {-4.5, 4.5, -1},
          {-1.5, 4.5, -1},
          {-1.5, 1.5, -1},
          {-1.5, 1.5, 1},
          {-4.5, 1.5, 1},
          {-1.5, 4.5, 1},
          {-4.5, 4.5, 1}},
         {-2, 2, 2},
         ContactStatus::kTouching});
}

/// Axis-aligned cube of half side h centred at c.
std::vector<Eigen::Vector3d> cube(const Eigen::Vector3d& c, double h) {
  std::vector<Eigen::Vector3d> out;
  for (int k = 0; k < 8; ++k) out.push_back(c + h * Eigen::Vector3d(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1));
  return out;
}

TEST(QueryRegressions, FarFromTheOrigin) {
  // Issue "Exact everywhere", before the core worked in local frames: two
  // cubes of side 1/16 at 1e7 overlapping by 1/32 were "not intersecting"
  // and "separated"; two cubes of side 1/256 touching face to face at 1e6
  // got mdd 0.0069 (separated). All coordinates are exact doubles.
  const Eigen::Vector3d far7 = Eigen::Vector3d::Constant(1e7);
  check({"cubes of side 1/16 at 1e7 overlapping by 1/32",
         cube(far7, 1.0 / 32),
         cube(far7 + Eigen::Vector3d(1.0 / 32, 0, 0), 1.0 / 32),
         {1, 0, 0},
         ContactStatus::kPenetrating});
  const Eigen::Vector3d far6 = Eigen::Vector3d::Constant(1e6);
  check({"cubes of side 1/256 touching face to face at 1e6",
         cube(far6, 1.0 / 512),
         cube(far6 + Eigen::Vector3d(1.0 / 256, 0, 0), 1.0 / 512),
         {-1, 0.3, 0},
         ContactStatus::kTouching});
  const ConvexPolytope a = ConvexPolytope::fromPoints(cube(far7, 1.0 / 32));
  const ConvexPolytope b = ConvexPolytope::fromPoints(cube(far7 + Eigen::Vector3d(1.0 / 32, 0, 0), 1.0 / 32));
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  const MddResult r = mdd(DirectionalInput{&a, I, &b, I, {1, 0, 0}});
  EXPECT_EQ(r.distance, -1.0 / 32);  // exact: the local frames lose nothing here
  EXPECT_TRUE(intersect(IntersectInput{&a, I, &b, I}).intersecting);
}

TEST(QueryRegressions, ToiRejectsANegativeMaxDistance) {
  // Issue "Exact everywhere": toi() answered "never" for max_distance < 0
  // while the planning layer's directed clearance threw; one rule now.
  const ConvexPolytope a = ConvexPolytope::fromPoints(cube(Eigen::Vector3d::Zero(), 1));
  DirectionalInput in{&a, Eigen::Isometry3d::Identity(), &a, Eigen::Isometry3d::Identity(), {1, 0, 0}};
  in.max_distance = -1.0;
  EXPECT_THROW(toi(in), InvalidInputError);
  in.max_distance = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(toi(in), InvalidInputError);
  in.max_distance = 0.0;
  EXPECT_EQ(toi(in).status, ToiStatus::kInContact);
}

TEST(QueryRegressions, PosesBeyondTheSupportedRangeAreNamed) {
  const ConvexPolytope a = ConvexPolytope::fromPoints(cube(Eigen::Vector3d::Zero(), 1));
  Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
  far.translation() = Eigen::Vector3d(1e60, 0, 0);
  try {
    intersect(IntersectInput{&a, Eigen::Isometry3d::Identity(), &a, far});
    ADD_FAILURE() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("pose X_WB has a translation beyond"), std::string::npos) << e.what();
  }
}

// Found by the mesh configs' soundness sweep (tests/configs/
// test_mesh_soundness.cpp, maze_planar, MDDUAL_PLANNING_SCALE=50; not yet
// fixed, hence DISABLED_: run with --gtest_also_run_disabled_tests). Two
// vertical triangles (world: x = 11.875; robot: a triangle of the maze robot
// in its body frame, two vertices one above the other), queried along two
// translation edges of the planner with one WarmStart, as MddScene does per
// pair and thread: after the first query, the second toi() is 0.0339 early
// (0.68872 instead of 0.72262, which the cold query gives and an FCL
// bisection of the edge confirms). A warm start may only change the speed.
TEST(QueryRegressions, DISABLED_WarmStartFromAnotherPoseKeepsTheToi) {
  const ConvexPolytope a =
      ConvexPolytope::fromPoints({{11.875, 13.875, 0.5}, {11.875, 14.125, -0.5}, {11.875, 14.125, 0.5}});
  const ConvexPolytope b =
      ConvexPolytope::fromPoints({{0.24859311214337745, -0.2056179940700531, -0.20000000298023224},
                                  {0.27111210456738871, 0, 0.20000000298023224},
                                  {0.24859311214337745, -0.2056179940700531, 0.20000000298023224}});
  const auto pose = [](double x, double y, double qw, double qz) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = Eigen::Vector3d(x, y, 0);
    X.linear() = Eigen::Quaterniond(qw, 0, 0, qz).normalized().toRotationMatrix();
    return X;
  };
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  DirectionalInput first{&a,
                         I,
                         &b,
                         pose(10.919814241864696, 13.767155869968731, 0.98980246348703427, 0.14244677348047707),
                         {0.84212834365750067, 0.53927715769228923, 0}};
  first.max_distance = 1.6955338918155691;
  DirectionalInput second{&a,
                          I,
                          &b,
                          pose(10.926912118014048, 14.390465041027468, 0.99583697635839641, -0.091152161342266808),
                          {0.98948620059553971, -0.14462731011466418, 0}};
  second.max_distance = 1.3728998237483596;
  const ToiResult cold = toi(second);
  ASSERT_EQ(cold.status, ToiStatus::kHit);
  EXPECT_NEAR(cold.toi, 0.7226214933036319, 1e-12);
  WarmStart warm;
  toi(first, &warm);
  const ToiResult hot = toi(second, &warm);
  EXPECT_EQ(hot.status, cold.status);
  EXPECT_NEAR(hot.toi, cold.toi, 1e-9);  // measured: 0.68872205014173626
}

}  // namespace
}  // namespace mddual::testing
