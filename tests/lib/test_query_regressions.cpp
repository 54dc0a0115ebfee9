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

TEST(QueryRegressions, ContactPointOnBothBodiesForRoundedCoplanarFaces) {
  // A pentagonal prism and its shifted copy, rounded at an offset of ~1.5e5
  // (MDDUAL_SWEEP_SCALE=10 MDDUAL_SWEEP_SEED=7 test_far_from_origin): their
  // pentagons are parallel and planar only to ~2e-12, more than the support
  // tie tolerance (1.4e-12 here). The contact (an FV face: A's pentagon, one
  // vertex of B) took B's tie set as that vertex alone and returned x + b, a
  // point of B that was 0.09 to 0.39 outside A; the distances were right.
  const std::vector<Eigen::Vector3d> a{{-156108.00832163668, 91417.017613074713, 85281.499540166318},
                                       {-156109.12788326506, 91416.66307059578, 85281.552901220726},
                                       {-156109.33546499576, 91417.024150605197, 85279.596749117263},
                                       {-156108.21590336738, 91417.378693084131, 85279.543388062855},
                                       {-156107.98299317443, 91418.173862546828, 85281.710280856438},
                                       {-156109.08690095227, 91418.533921541137, 85281.893886820151},
                                       {-156109.79448194164, 91417.600200765461, 85281.796620856141},
                                       {-156110.00206367235, 91417.961280774878, 85279.840468752678},
                                       {-156108.19057490514, 91418.53494255626, 85279.754128752975},
                                       {-156109.29448268298, 91418.895001550569, 85279.937734716688}};
  const std::vector<Eigen::Vector3d> b{{-156108.92045631251, 91416.42495905103, 85282.388106648606},
                                       {-156109.5870549891, 91417.362089220711, 85282.631826284021},
                                       {-156109.7946367198, 91417.723169230128, 85280.675674180558},
                                       {-156109.12803804321, 91416.786039060447, 85280.431954545144},
                                       {-156108.00847641483, 91417.140581539381, 85280.378593490736},
                                       {-156107.98314795256, 91418.29683101151, 85280.589334180855},
                                       {-156107.77556622186, 91417.935751002078, 85282.545486284318},
                                       {-156107.80089468413, 91416.779501529963, 85282.334745594198},
                                       {-156109.0870557304, 91418.656890005819, 85280.772940144569},
                                       {-156108.8794739997, 91418.295809996387, 85282.729092248017}};
  const std::vector<Eigen::Vector3d> directions{{-0.21072026616374634, -0.33269322727694428, 0.91919104975621446},
                                                {-0.11545440860461005, 0.40762469125275175, -0.90582139001839579},
                                                {-0.27076052802687606, -0.27486302070324009, 0.92257197893307907}};
  // The same points moved to the origin: subtracting this integer vector is
  // exact (Sterbenz), so the faces keep their round-off; it failed there too.
  const Eigen::Vector3d offset(-156109, 91417, 85281);
  for (const bool at_origin : {false, true}) {
    Pinned p{at_origin ? "pentagonal prisms, moved to the origin" : "pentagonal prisms at 1.5e5",
             a,
             b,
             {},
             ContactStatus::kPenetrating};
    if (at_origin) {
      for (Eigen::Vector3d& v : p.a) v -= offset;
      for (Eigen::Vector3d& v : p.b) v -= offset;
    }
    for (const Eigen::Vector3d& s : directions) {
      p.direction = s;
      check(p);
    }
  }
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

}  // namespace
}  // namespace mddual::testing
