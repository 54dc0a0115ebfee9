// Queries that exposed bugs, pinned with their full-precision inputs (as the
// oracle printed them). Each runs through the oracle (mdd, toi, intersect
// against the brute force, contact point and normal checked) and asserts the
// status the brute force gives.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include "mddual/error.h"
#include "mddual/generators.h"
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

TEST(QueryRegressions, ContactPointOnBothBodiesForBoxesTouchingAlongAnEdge) {
  // QueryFamilies.ExactlyTouchingPlacements at MDDUAL_SWEEP_SCALE=5
  // MDDUAL_SWEEP_SEED=6: boxes of half extents (1, 1, 2) and (2, 2, 1), B at
  // (3, 3, 0.5) in A's frame, both turned by R: they touch along a vertical
  // edge (x and y exactly touching), so the origin lies on the boundary of
  // M's face. mdd was 0 (touching), the normal valid, but the contact point
  // was a corner of A 0.5 outside B.
  Eigen::Matrix3d R;
  R << -0.0052340499641851945, 0.99993691029558196, -0.0099388203272739728,  //
      0.99997589243118146, 0.0051883867196734768, -0.0046146722212574275,    //
      -0.0045628146395557505, -0.0099627341514533542, -0.99993996052302725;
  const ConvexPolytope a = ConvexPolytope::fromPoints(generators::box({1, 1, 2}));
  const ConvexPolytope b = ConvexPolytope::fromPoints(generators::box({2, 2, 1}));
  Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity();
  X_WA.linear() = R;
  Eigen::Isometry3d X_WB = X_WA;
  X_WB.translation() = R * Eigen::Vector3d(3, 3, 0.5);
  const std::vector<Eigen::Vector3d> directions{{-1.0145805009859448, -1.0143936235933699, -1.9853543722550453},
                                                {-1.0046416806586707, -1.0097789513721125, -0.98541441173201816},
                                                {-1.9847009502997048, -1.005737993649271, 1.0244282434654897}};
  QueryOracle oracle;
  Tally tally;
  EXPECT_EQ(oracle.check(a, X_WA, b, X_WB, directions, &tally), 0);
  for (const Eigen::Vector3d& s : directions) {
    EXPECT_EQ(mdd(DirectionalInput{&a, X_WA, &b, X_WB, s}).status, ContactStatus::kTouching);
  }
}

TEST(QueryRegressions, SearchOnFacesPlanarOnlyToRoundOff) {
  // QueryFamilies.ParallelFacesPlanarOnlyToRoundOff at MDDUAL_SWEEP_SCALE=10:
  // a prism and its shifted copy, rotated in their points and jittered by
  // ~1e-11 of their size. (1) Seed 6: an EE face of two nearly parallel edges
  // (sine ~1e-11) got a normal 3e-5 off and a plane through the edges that
  // cut into M: mdd 3.6e-6 too short. (2) Seed 7: the exit search stopped at
  // a thin EE face of the caps (arcs crossing ~1e-11 from their ends) whose
  // edge neighbours all looked worse: t_hi 0.105 too far.
  check({"pentagonal prism copies, nearly parallel edges",
         {{-0.43837195979790622, 0.92771336679280769, -0.018596954231987938},
          {-0.30033850669144813, -0.12240113246530127, 0.97364400934621131},
          {0.54529918293746327, -0.11727404481536823, 0.86143108387876577},
          {0.4072657298301261, 0.93284045444276864, -0.13080987970196484},
          {-0.63553981790260716, -0.68398528825851701, 0.42593565016349633},
          {0.002932068331766291, -1.0259362964342915, -0.02477965720704739},
          {0.73273070609277302, -0.67568948617352198, 0.24437132277657922},
          {-0.77357327100744677, 0.36612921100240942, -0.5663053134214151},
          {-0.13510138477142689, 0.024178202831292371, -1.0170206207890244},
          {0.5946972529825022, 0.37442501308251214, -0.74786964080588247}},
         {{-0.70993027286470367, 1.0731538175515416, 0.17310371604297889},
          {-0.57189681975824558, 0.023039318293432726, 1.1653446796211782},
          {0.27374086987066582, 0.028166405943365766, 1.0531317541537326},
          {0.13570741676332865, 1.0782809052015025, 0.060890790573001979},
          {-0.90709813096940461, -0.53854483749978299, 0.61763632043846317},
          {-0.26862624473503116, -0.8804958456755575, 0.16692101306791943},
          {0.46117239302597557, -0.53024903541478796, 0.43607199305154604},
          {-1.0451315840742441, 0.51156966176114338, -0.37460464314644826},
          {-0.40665969783822431, 0.16961865359002637, -0.8253199505140576},
          {0.32313893991570475, 0.5198654638412461, -0.55616897053091563}},
         {-0.028315754585719406, 0.00068300318574001902, 0.99959879529183582},
         ContactStatus::kPenetrating});
  check({"heptagonal prism copies, exit search through thin cap faces",
         {{0.22562962717918814, 1.092457370016545, 0.29628093938104727},
          {-0.31301460287822896, 1.0988386565057344, -0.16349218437606353},
          {-0.97282057945409373, -0.18909161998037324, 0.59162378962648265},
          {-0.43417634939701838, -0.1954729064669635, 1.0513969133757064},
          {-0.36752877365485948, 0.76269090601962519, -0.78446122365078741},
          {-1.0273347502303261, -0.52523937046984104, -0.029345249656378736},
          {-0.55666857924943292, -0.95079004565527792, -0.34390785241570915},
          {0.10313739732687002, 0.33714023082626843, -1.0990238264151984},
          {0.41393478505620068, -0.96228872659280829, 0.48457468918490121},
          {0.1829878483594127, -0.53957799106013549, 1.0037555817610255},
          {0.08475670690050581, -1.1452953074782901, -0.11519196287914041},
          {1.0737407616355559, 0.32564154989644056, -0.27054128481233158},
          {0.84279382493920463, 0.74835228542526799, 0.24863960776135791},
          {0.74456268347349486, 0.14263496901015285, -0.87030793687913288}},
         {{0.060678133035019483, 0.77047480089512166, 0.48505993288109184},
          {-0.47796609702239762, 0.77685608738431111, 0.025286809123981041},
          {-1.1377720735982624, -0.51107418910179658, 0.78040278312652722},
          {-0.59912784354118709, -0.51745547558838689, 1.240175906875751},
          {-0.53248026779902813, 0.44070833689820182, -0.59568223015074284},
          {-1.1922862443744946, -0.84722193959126435, 0.15943374384366582},
          {-0.72162007339360157, -1.2727726147767013, -0.15512885891566458},
          {-0.06181409681729863, 0.01515766170484506, -0.91024483291515379},
          {0.24898329091203203, -1.2842712957142317, 0.67335368268494578},
          {0.018036354215244049, -0.8615605601815588, 1.1925345752610701},
          {-0.080194787243662843, -1.4672778765997134, 0.073587030620904159},
          {0.90878926749138722, 0.0036589807750171954, -0.081762291312287017},
          {0.67784233079503597, 0.42636971630384463, 0.43741860126140247},
          {0.5796111893293262, -0.17934760011127052, -0.68152894337908831}},
         {-0.20714472718934346, 0.94221493503617926, -0.26329086234129184},
         ContactStatus::kPenetrating});
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
// test_mesh_soundness.cpp, maze_planar, MDDUAL_PLANNING_SCALE=50). Two
// vertical triangles (world: x = 11.875; robot: a triangle of the maze robot
// in its body frame, two vertices one above the other), queried along two
// translation edges of the planner with one WarmStart, as MddScene does per
// pair and thread: after the first query, the second toi() was 0.0339 early
// (0.68872 instead of 0.72262, which the cold query gives and an FCL
// bisection of the edge confirms). A warm start may only change the speed.
// Cause: the warm search started at an FV face (a facet of A, a vertex of B)
// whose better neighbour lies across an edge of A parallel to an edge of B
// (both triangles have a vertical edge): no EE face there, the neighbour is
// a VF face, and the climb over edge neighbours did not name it (the cold
// search met it in SEARCH-VF). Fixed in search.cpp (parallelEdgeNeighbours).
/// Whether a separating axis proves two triangles (world points) disjoint:
/// their normals and the cross products of their edges (the separating-axis
/// theorem, complete for triangles that are not coplanar). Independent of
/// the library: a bracket for a pinned time of impact.
bool trianglesSeparated(const std::vector<Eigen::Vector3d>& p, const std::vector<Eigen::Vector3d>& q) {
  std::vector<Eigen::Vector3d> axes = {(p[1] - p[0]).cross(p[2] - p[0]), (q[1] - q[0]).cross(q[2] - q[0])};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) axes.push_back((p[(i + 1) % 3] - p[i]).cross(q[(j + 1) % 3] - q[j]));
  }
  for (const Eigen::Vector3d& n : axes) {
    if (n.norm() < 1e-12) continue;  // parallel edges: no axis
    const auto extent = [&n](const std::vector<Eigen::Vector3d>& points) {
      double lo = std::numeric_limits<double>::infinity();
      double hi = -lo;
      for (const Eigen::Vector3d& x : points) {
        lo = std::min(lo, n.dot(x));
        hi = std::max(hi, n.dot(x));
      }
      return std::make_pair(lo, hi);
    };
    const auto [p_lo, p_hi] = extent(p);
    const auto [q_lo, q_hi] = extent(q);
    if (p_hi < q_lo || q_hi < p_lo) return true;
  }
  return false;
}

TEST(QueryRegressions, WarmStartFromAnotherPoseKeepsTheToi) {
  const std::vector<Eigen::Vector3d> a_points = {{11.875, 13.875, 0.5}, {11.875, 14.125, -0.5}, {11.875, 14.125, 0.5}};
  const std::vector<Eigen::Vector3d> b_points = {{0.24859311214337745, -0.2056179940700531, -0.20000000298023224},
                                                 {0.27111210456738871, 0, 0.20000000298023224},
                                                 {0.24859311214337745, -0.2056179940700531, 0.20000000298023224}};
  const ConvexPolytope a = ConvexPolytope::fromPoints(a_points);
  const ConvexPolytope b = ConvexPolytope::fromPoints(b_points);
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
  // 0.7226214933036319: the brute force's value (explicit M), bracketed by
  // the separating-axis test: B 1e-6 short of it is disjoint from A, 1e-6
  // past it is not (no axis separates the two triangles, which are not
  // coplanar).
  EXPECT_NEAR(cold.toi, 0.7226214933036319, 1e-12);
  EXPECT_NEAR(bruteForceToi(second).toi, 0.7226214933036319, 1e-12);
  const auto b_at = [&](double t) {
    std::vector<Eigen::Vector3d> out;
    for (const Eigen::Vector3d& x : b_points) out.push_back(second.X_WB * x + t * second.s_W.normalized());
    return out;
  };
  EXPECT_TRUE(trianglesSeparated(a_points, b_at(0.7226214933036319 - 1e-6)));
  EXPECT_FALSE(trianglesSeparated(a_points, b_at(0.7226214933036319 + 1e-6)));
  WarmStart warm;
  toi(first, &warm);
  const ToiResult hot = toi(second, &warm);
  EXPECT_EQ(hot.status, cold.status);
  EXPECT_NEAR(hot.toi, cold.toi, 1e-9);  // was 0.68872205014173626
}

}  // namespace
}  // namespace mddual::testing
