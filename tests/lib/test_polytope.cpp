// ConvexPolytope construction: topology, merged faces, flat polygons, the
// Gaussian-arc wedges, and the documented errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "mddual/constants.h"
#include "mddual/error.h"
#include "mddual/generators.h"
#include "mddual/polytope.h"
#include "qhull_wrapper.h"
#include "test_shapes.h"

namespace mddual {
namespace {

using generators::Points;

/// Checks invariants every polytope must satisfy.
void expectWellFormed(const ConvexPolytope& p) {
  const double tol = 1e-9 * (1.0 + p.radius());
  if (!p.isFlat()) {
    EXPECT_EQ(p.numVertices() - p.numEdges() + p.numFaces(), 2);
  }
  for (int f = 0; f < p.numFaces(); ++f) {
    EXPECT_NEAR(p.faceNormal(f).norm(), 1.0, 1e-12);
    for (int v = 0; v < p.numVertices(); ++v) {
      EXPECT_LE(p.faceNormal(f).dot(p.vertex(v)), p.faceOffset(f) + tol) << "vertex " << v << " outside face " << f;
    }
    for (int v : p.faceVertices(f)) EXPECT_NEAR(p.faceNormal(f).dot(p.vertex(v)), p.faceOffset(f), tol);
  }
  for (int e = 0; e < p.numEdges(); ++e) {
    const ConvexPolytope::Edge& edge = p.edge(e);
    // Each face normal lies on the boundary of the edge's wedge, the other
    // face normal inside it; the edge direction matches its endpoints.
    const Eigen::Vector3d nl = p.faceNormal(edge.face_left);
    const Eigen::Vector3d nr = p.faceNormal(edge.face_right);
    EXPECT_NEAR(nl.dot(edge.wedge_left_P), 0.0, 1e-12);
    EXPECT_NEAR(nr.dot(edge.wedge_right_P), 0.0, 1e-12);
    EXPECT_GE(nl.dot(edge.wedge_right_P), -1e-12);
    EXPECT_GE(nr.dot(edge.wedge_left_P), -1e-12);
    EXPECT_NEAR(edge.dir_P.dot((p.vertex(edge.v1) - p.vertex(edge.v0)).normalized()), 1.0, 1e-12);
  }
  for (int v = 0; v < p.numVertices(); ++v) {
    EXPECT_EQ(p.vertexNeighbors(v).size(), p.vertexEdges(v).size());
    EXPECT_GE(p.vertexNeighbors(v).size(), 2);
    EXPECT_GE(p.vertexFaces(v).size(), p.isFlat() ? 2 : 3);
  }
}

TEST(Polytope, UnitCube) {
  const ConvexPolytope cube = ConvexPolytope::fromPoints(generators::box({0.5, 0.5, 0.5}));
  EXPECT_EQ(cube.numVertices(), 8);
  EXPECT_EQ(cube.numEdges(), 12);
  EXPECT_EQ(cube.numFaces(), 6);  // qhull's triangles merged into squares
  EXPECT_FALSE(cube.isFlat());
  EXPECT_NEAR(cube.radius(), std::sqrt(0.75), 1e-15);
  EXPECT_TRUE(cube.centroid().isZero(1e-15));
  for (int f = 0; f < 6; ++f) {
    EXPECT_EQ(cube.faceVertices(f).size(), 4);
    EXPECT_NEAR(cube.faceOffset(f), 0.5, 1e-15);
  }
  expectWellFormed(cube);
}

// Edge::otherFace: across every edge of a face lies a different face that
// also lists the edge, and crossing back returns to the first; on a cube, the
// face across is perpendicular.
TEST(Polytope, OtherFaceCrossesEachEdgeToItsNeighbour) {
  const ConvexPolytope cube = ConvexPolytope::fromPoints(generators::box({0.5, 0.5, 0.5}));
  for (int f = 0; f < cube.numFaces(); ++f) {
    for (const int e : cube.faceEdges(f)) {
      const ConvexPolytope::Edge& edge = cube.edge(e);
      const int g = edge.otherFace(f);
      EXPECT_NE(g, f) << "face " << f << ", edge " << e;
      EXPECT_EQ(edge.otherFace(g), f) << "face " << f << ", edge " << e;
      const IndexRange g_edges = cube.faceEdges(g);
      EXPECT_NE(std::find(g_edges.begin(), g_edges.end(), e), g_edges.end()) << "face " << g << ", edge " << e;
      EXPECT_NEAR(cube.faceNormal(f).dot(cube.faceNormal(g)), 0.0, 1e-15);
    }
  }
}

TEST(Polytope, LatticeKeepsOnlyCornersAndMergesCoplanarFacets) {
  // 4 x 4 x 4 lattice points: 56 boundary points, but a cube.
  const ConvexPolytope p = ConvexPolytope::fromPoints(testing::lattice(3, 3, 3, 1.0));
  EXPECT_EQ(p.numVertices(), 8);
  EXPECT_EQ(p.numFaces(), 6);
  expectWellFormed(p);
}

TEST(Polytope, RegularPrismHasMergedCaps) {
  const ConvexPolytope p = ConvexPolytope::fromPoints(generators::prism(7, 1.0, 2.0));
  EXPECT_EQ(p.numVertices(), 14);
  EXPECT_EQ(p.numFaces(), 9);  // two heptagons and seven rectangles
  EXPECT_EQ(p.numEdges(), 21);
  expectWellFormed(p);
}

TEST(Polytope, FlatTriangleHasTwoOppositeFaces) {
  const ConvexPolytope t =
      ConvexPolytope::fromPoints(generators::triangle({0.0, 0.0, 1.0}, {1.0, 0.0, 1.0}, {0.0, 1.0, 1.0}));
  ASSERT_TRUE(t.isFlat());
  EXPECT_EQ(t.numVertices(), 3);
  EXPECT_EQ(t.numEdges(), 3);
  EXPECT_EQ(t.numFaces(), 2);
  EXPECT_NEAR(std::abs(t.faceNormal(0).z()), 1.0, 1e-15);
  EXPECT_NEAR(t.faceNormal(0).dot(t.faceNormal(1)), -1.0, 1e-15);
  EXPECT_NEAR(t.faceOffset(0) + t.faceOffset(1), 0.0, 1e-15);
  // Each edge's wedge is the half-plane of its outward in-plane normal.
  for (int e = 0; e < 3; ++e) {
    const ConvexPolytope::Edge& edge = t.edge(e);
    EXPECT_TRUE(edge.wedge_left_P.isApprox(edge.wedge_right_P, 1e-15));
    const Eigen::Vector3d mid = 0.5 * (t.vertex(edge.v0) + t.vertex(edge.v1));
    EXPECT_GT(edge.wedge_left_P.dot(mid - t.centroid()), 0.0);
  }
  expectWellFormed(t);
}

TEST(Polytope, FlatPolygonFromManyCoplanarPoints) {
  // A planar lattice tilted in space: a flat square with 4 corners.
  Points points = testing::lattice(4, 4, 0, 0.5);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (Eigen::Vector3d& p : points) p = R * p + Eigen::Vector3d(3, -2, 1);
  const ConvexPolytope p = ConvexPolytope::fromPoints(points);
  EXPECT_TRUE(p.isFlat());
  EXPECT_EQ(p.numVertices(), 4);
  expectWellFormed(p);
}

TEST(Polytope, NeedleAndSlabAreSolids) {
  for (const Points& pts : {generators::box({0.01, 0.01, 1.0}), generators::box({1.0, 1.0, 0.01})}) {
    const ConvexPolytope p = ConvexPolytope::fromPoints(pts);
    EXPECT_FALSE(p.isFlat());
    EXPECT_EQ(p.numFaces(), 6);
    expectWellFormed(p);
  }
}

TEST(Polytope, PaperPolytopesAreWellFormed) {
  for (const char* name : {"P1", "P2", "P3", "P4", "P5", "P6"}) {
    SCOPED_TRACE(name);
    const Points pts = generators::paperPolytope(name);
    const ConvexPolytope p = ConvexPolytope::fromPoints(pts);
    EXPECT_EQ(p.numVertices(), static_cast<int>(pts.size()));  // every generated point is a corner
    expectWellFormed(p);
  }
}

TEST(Polytope, ErrorsNameTheProblem) {
  auto message = [](const Points& pts) -> std::string {
    try {
      ConvexPolytope::fromPoints(pts);
    } catch (const DegenerateGeometryError& e) {
      return std::string("degenerate: ") + e.what();
    } catch (const InvalidInputError& e) {
      return std::string("invalid: ") + e.what();
    }
    return "no error";
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(message({}), "invalid: polytope: the point set is empty");
  EXPECT_NE(message({{0, 0, 0}, {1, 0, 0}, {0, nan, 0}}).find("point 2"), std::string::npos);
  EXPECT_NE(message({{0, 0, 0}, {inf, 0, 0}, {0, 1, 0}}).find("non-finite"), std::string::npos);
  EXPECT_NE(message({{0, 0, 0}, {1, 0, 0}}).find("degenerate: polytope: 2 point(s)"), std::string::npos);
  EXPECT_NE(message({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}}).find("collinear"), std::string::npos);
  // A box 1e12 long and 0.8 wide: collinear within the relative tolerance,
  // said with both sizes (a hostile-input hunt read it as a wrong message).
  std::vector<Eigen::Vector3d> needle;
  for (double x : {0.0, 1e12}) {
    for (double y : {0.0, 0.8}) {
      for (double z : {0.0, 0.8}) needle.emplace_back(x, y, z);
    }
  }
  const std::string long_box = message(needle);
  EXPECT_NE(long_box.find("degenerate: polytope: all 8 points are collinear (fewer than three non-collinear "
                          "points): they lie within 0.566 of a line and span about 1e+12, below 1e-10 of their extent"),
            std::string::npos)
      << long_box;
  EXPECT_NE(message({{1, 2, 3}, {1, 2, 3}, {1, 2, 3}}).find("coincide"), std::string::npos);
  // Out of the supported range (defaults::kMaxCoordinate, kMinSize): named,
  // instead of "collinear" or an Euler-formula failure deep in the hull.
  EXPECT_NE(message({{0, 0, 0}, {1e75, 0, 0}, {0, 1, 0}, {0, 0, 1}})
                .find("point 1 [9.9999999999999993e+74, 0, 0] is out of the supported range"),
            std::string::npos);
  EXPECT_NE(
      message({{0, 0, 0}, {1e-80, 0, 0}, {0, 1e-80, 0}, {0, 0, 1e-80}}).find("below the smallest supported body size"),
      std::string::npos);
  // The base class catches them all.
  EXPECT_THROW(ConvexPolytope::fromPoints({}), Error);
}

TEST(Polytope, FarFromTheOriginKeepsItsShape) {
  // Issue "Exact everywhere": an octahedron of radius 1e-5 at (1000, 1000,
  // 1000) failed with "hull edge 5->3 appears twice", a triangle of size 5e-3
  // at 2.5e4 with qhull's "not enough points to construct initial simplex".
  // In the local frame (the points' box centre) both are well conditioned.
  const double r = 1e-5;
  const Eigen::Vector3d c(1000, 1000, 1000);
  const Points octahedron = {c + Eigen::Vector3d(r, 0, 0), c - Eigen::Vector3d(r, 0, 0), c + Eigen::Vector3d(0, r, 0),
                             c - Eigen::Vector3d(0, r, 0), c + Eigen::Vector3d(0, 0, r), c - Eigen::Vector3d(0, 0, r)};
  const ConvexPolytope o = ConvexPolytope::fromPoints(octahedron);
  EXPECT_EQ(o.numVertices(), 6);
  EXPECT_EQ(o.numFaces(), 8);
  expectWellFormed(o);
  EXPECT_EQ(o.p_PL(), c);
  for (int v = 0; v < o.numVertices(); ++v) {
    EXPECT_EQ(o.vertex(v), o.localVertex(v) + o.p_PL());  // exact: the input point
    EXPECT_LE(o.localVertex(v).norm(), r * (1 + 1e-9));
  }
  for (int f = 0; f < o.numFaces(); ++f) {
    EXPECT_NEAR(o.localFaceOffset(f), r / std::sqrt(3.0), 4e-13);  // the input points carry ulp(1000) = 1.1e-13
    EXPECT_NEAR(o.faceOffset(f), o.localFaceOffset(f) + o.faceNormal(f).dot(c), 1e-12);
  }
  const double o2 = 2.5e4;
  const double t = 5e-3;
  const ConvexPolytope tri = ConvexPolytope::fromPoints({{o2, o2, o2}, {o2 + t, o2, o2}, {o2, o2 + t, o2 + t / 3}});
  EXPECT_TRUE(tri.isFlat());
  EXPECT_EQ(tri.numVertices(), 3);
  expectWellFormed(tri);
}

TEST(Polytope, AStraightCornerOfNearlyCoplanarFacetsStaysInEveryLoop) {
  // MDDUAL_SWEEP_SCALE=10 MDDUAL_SWEEP_SEED=7 test_far_from_origin: the
  // brute force's M = A - A of a hexagonal prism rounded at ~1.6e6 threw
  // "hull edge 9-12 borders only one face". A vertex of three or more hull
  // facets where one facet's loop goes straight on was dropped from that
  // loop only, leaving the edges beside it with one face each.
  const Points a = {{336696.19525450299, -805975.94897517166, 1340546.9251244387},
                    {336692.10467527987, -805962.07719614508, 1340553.7691662458},
                    {336685.89795355493, -805961.43726316828, 1340548.7624616197},
                    {336689.98853277805, -805975.30904219486, 1340541.9184198126},
                    {336703.29486947093, -805972.86116499, 1340544.9099580466},
                    {336686.79084679793, -805957.7095200097, 1340541.740590601},
                    {336690.88142602105, -805971.58129903639, 1340534.8965487941},
                    {336697.98104098899, -805968.49348885461, 1340532.8813824018},
                    {336693.89046176587, -805954.62170982803, 1340539.7254242089},
                    {336700.09718349081, -805955.26164280483, 1340544.7321288351},
                    {336704.18776271393, -805969.13342183142, 1340537.8880870279},
                    {336699.20429024781, -805958.9893859633, 1340551.7539998535}};
  Points differences;
  for (const Eigen::Vector3d& p : a)
    for (const Eigen::Vector3d& q : a) differences.push_back(p - q);
  const ConvexPolytope m = ConvexPolytope::fromPoints(differences);
  expectWellFormed(m);
  // M = A - A is symmetric and holds every difference.
  for (const Eigen::Vector3d& d : differences) {
    for (int f = 0; f < m.numFaces(); ++f) EXPECT_LE(m.faceNormal(f).dot(d), m.faceOffset(f) + 1e-9);
  }
}

/// The support value of the polytope in direction d, and that of its
/// corners by brute force.
double support(const ConvexPolytope& p, const Eigen::Vector3d& d) {
  return d.dot(p.vertex(p.supportVertex(d)));
}
double supportBrute(const ConvexPolytope& p, const Eigen::Vector3d& d) {
  double best = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& v : p.vertices()) best = std::max(best, d.dot(v));
  return best;
}

// Vertex indices from the caller are checked, not read out of range (a hint
// of 8 on a cube read past the vertex array; hostile-input hunt).
TEST(Polytope, SupportQueriesRefuseVertexIndicesOutOfRange) {
  const ConvexPolytope cube = ConvexPolytope::fromPoints(generators::box({1, 1, 1}));
  const Eigen::Vector3d d(1, 2, 3);
  EXPECT_THROW(cube.supportVertex(d, 8), InvalidInputError);
  EXPECT_THROW(cube.supportVertexHillClimb(d, -1), InvalidInputError);
  std::vector<int> ties;
  EXPECT_THROW(cube.supportTies(d, -1, 0.0, &ties), InvalidInputError);
  EXPECT_THROW(cube.supportTies(d, 8, 0.0, &ties), InvalidInputError);
  EXPECT_EQ(cube.supportVertex(d, -1), cube.supportVertex(d, 7));  // -1: no hint
}

TEST(Polytope, PrismEqualsTheHullOfItsCornersForACoplanarBase) {
  // A heptagon in the plane normal to a tilted axis, away from the origin:
  // prism() must give the polytope fromPoints gives for the same corners.
  generators::Rng rng(31);
  const Eigen::Vector3d axis = generators::randomUnitVector(rng);
  const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis);
  const Eigen::Vector3d centre(3.0, -2.0, 7.5);
  Points base;
  for (int i = 0; i < 7; ++i) {
    const double a = 2.0 * kPi * i / 7.0 + 0.3;
    base.push_back(centre + q * Eigen::Vector3d(0.8 * std::cos(a), 0.5 * std::sin(a), 0.0));
  }
  const double h = 0.25;
  const ConvexPolytope p = ConvexPolytope::prism(base, 2.0 * axis, h);  // the axis need not be unit
  Points corners;
  for (const Eigen::Vector3d& b : base) {
    corners.push_back(b + h * axis);
    corners.push_back(b - h * axis);
  }
  const ConvexPolytope ref = ConvexPolytope::fromPoints(corners);
  EXPECT_EQ(p.numVertices(), 14);
  EXPECT_EQ(p.numFaces(), ref.numFaces());
  EXPECT_EQ(p.numEdges(), ref.numEdges());
  EXPECT_FALSE(p.isFlat());
  expectWellFormed(p);
  for (int k = 0; k < 300; ++k) {
    const Eigen::Vector3d d = generators::randomUnitVector(rng);
    EXPECT_NEAR(support(p, d), support(ref, d), 1e-12) << "direction " << d.transpose();
  }
}

TEST(Polytope, PrismOfALargeBaseIsBuiltWithoutItsHierarchyAndSupportsExactly) {
  // 2,000 base corners (fromPoints on its corners is quadratic in qhull's
  // merging of the caps), a base of uneven heights: the prism spans from the
  // lowest minus h to the highest plus h along the axis.
  generators::Rng rng(32);
  Points base;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * kPi * i / n;
    base.emplace_back(0.3 * std::cos(a), 0.3 * std::sin(a), i == 5 ? 0.01 : (i == 900 ? -0.02 : 0.0));
  }
  const double h = 1e-3;
  const ConvexPolytope p = ConvexPolytope::prism(base, Eigen::Vector3d::UnitZ(), h);
  EXPECT_EQ(p.numVertices(), 2 * n);
  EXPECT_EQ(p.numFaces(), n + 2);
  EXPECT_EQ(p.hierarchyDepth(), 0);
  EXPECT_NEAR(support(p, Eigen::Vector3d::UnitZ()), 0.01 + h, 1e-15);
  EXPECT_NEAR(support(p, -Eigen::Vector3d::UnitZ()), 0.02 + h, 1e-15);
  int cold_mismatch = 0;
  for (int k = 0; k < 2000; ++k) {
    const Eigen::Vector3d d = generators::randomUnitVector(rng);
    const double brute = supportBrute(p, d);
    if (std::abs(support(p, d) - brute) > 1e-13) ++cold_mismatch;
    // Every base point's segment p +- h axis lies inside.
    const Eigen::Vector3d& b = base[static_cast<std::size_t>(k % n)];
    EXPECT_LE(d.dot(b) + h * std::abs(d.z()), brute + 1e-13);
  }
  EXPECT_EQ(cold_mismatch, 0);
}

TEST(Polytope, PrismErrorsNameTheProblem) {
  auto message = [](const Points& base, const Eigen::Vector3d& axis, double h) -> std::string {
    try {
      ConvexPolytope::prism(base, axis, h);
    } catch (const DegenerateGeometryError& e) {
      return std::string("degenerate: ") + e.what();
    } catch (const InvalidInputError& e) {
      return std::string("invalid: ") + e.what();
    }
    return "no error";
  };
  const Points square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message(square, z, 0.5), "no error");
  EXPECT_NE(message({{0, 0, 0}, {1, 0, 0}}, z, 0.5).find("degenerate: polytope prism: 2 base point(s)"),
            std::string::npos);
  EXPECT_NE(message({{0, 0, 0}, {1, 0, 0}, {0, nan, 0}}, z, 0.5).find("invalid: polytope: point 2"), std::string::npos);
  EXPECT_NE(message(square, Eigen::Vector3d::Zero(), 0.5).find("invalid: polytope prism: the axis"), std::string::npos);
  EXPECT_NE(message(square, Eigen::Vector3d(nan, 0, 1), 0.5).find("not a finite nonzero vector"), std::string::npos);
  EXPECT_NE(message(square, z, 0.0).find("half height"), std::string::npos);
  EXPECT_NE(message(square, z, nan).find("half height"), std::string::npos);
  EXPECT_NE(message(square, z, 1e300).find("invalid: polytope prism: the half height 1e+300 takes its corners"),
            std::string::npos);
  // Seen along x, the square in the plane z = 0 is a segment.
  EXPECT_NE(message(square, Eigen::Vector3d::UnitX(), 0.5)
                .find("degenerate: polytope prism: the 4 base points are collinear"),
            std::string::npos);
}

}  // namespace
}  // namespace mddual

namespace mddual {
namespace {

TEST(QhullWrapper, FailureIsReportedBrieflyAndFreesQhull) {
  // Found by fuzz_polytope: qhull's buffers leaked on every failed hull (the
  // wrapper threw from its constructor, so its destructor never ran); the
  // leak check of the sanitizer build fails this test if that comes back.
  const std::vector<Eigen::Vector3d> coplanar = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  try {
    detail::hull3d(coplanar, "test");
    ADD_FAILURE() << "qhull built a 3D hull of coplanar points";
  } catch (const HullError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("test: the convex hull failed (qhull exit code"), std::string::npos) << what;
    EXPECT_NE(what.find("QH6"), std::string::npos) << what;  // qhull's code and first sentence ...
    EXPECT_LT(what.size(), 400u) << what;                    // ... not its kilobytes of diagnostics
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace mddual
