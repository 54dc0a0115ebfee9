// Bvh's volume tests (lib/src/bvh.cpp): the boxes' separating-axis tests and
// casts, the inner cast, the swept sphere against a box and the triangle
// against a box, each against the core's intersect or time of impact on the
// same shapes as polytopes, on seeded random boxes. The traversals are in
// test_bvh.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "family_support.h"
#include "mddual/bvh.h"
#include "mddual/generators.h"
#include "mddual/query.h"

namespace mddual {
namespace {

using generators::Rng;
using Points = std::vector<Eigen::Vector3d>;
using testing::uniform;
using testing::uniformVector;

/// A box centred within `spread` of the origin, of random axes (or the given
/// ones) and half extents in [half_lo, half_hi].
Obb randomBox(Rng& rng, double spread, double half_lo, double half_hi, const Eigen::Matrix3d* axes = nullptr) {
  Obb box;
  box.centre_F = uniformVector(rng, -spread, spread);
  box.axes_F = axes ? *axes : generators::randomRotation(rng);
  box.half = uniformVector(rng, half_lo, half_hi);
  return box;
}

TEST(Bvh, ObbTestsAgreeWithTheCoreOnTheBoxesAsPolytopes) {
  Rng rng(8);
  int disjoint = 0, overlapping = 0, faces_only_cut = 0;
  for (int q = 0; q < 2000; ++q) {
    const Obb a = randomBox(rng, 1.0, 0.05, 1.0);
    const Obb b = randomBox(rng, 1.0, 0.05, 1.0, q % 4 == 0 ? &a.axes_F : nullptr);  // parallel edges too
    const auto ca = a.corners(), cb = b.corners();
    const ConvexPolytope pa = ConvexPolytope::fromPoints(Points(ca.begin(), ca.end()));
    const ConvexPolytope pb = ConvexPolytope::fromPoints(Points(cb.begin(), cb.end()));
    IntersectInput in;
    in.a = &pa;
    in.b = &pb;
    const bool core = intersect(in).intersecting;
    EXPECT_EQ(obbsDisjoint(a, b), !core) << "query " << q;
    ++(core ? overlapping : disjoint);
    // The cast interval: sampled translations agree with the static test.
    const Eigen::Vector3d u = generators::randomUnitVector(rng);
    double lo = 0, hi = 0;
    const bool meets = obbCastInterval(a, b, u, 3.0, &lo, &hi);
    // The face axes alone: a superset of the 15 axes' interval (same slack).
    double all_lo = 0, all_hi = 0, face_lo = 0, face_hi = 0;
    const bool all_meet = obbCastInterval(a, b, u, 3.0, 0.0, &all_lo, &all_hi);
    const bool faces_meet = obbCastIntervalFaces(a, b, u, 3.0, 0.0, &face_lo, &face_hi);
    if (all_meet) {
      EXPECT_TRUE(faces_meet) << "query " << q;
      EXPECT_LE(face_lo, all_lo) << "query " << q;
      EXPECT_GE(face_hi, all_hi) << "query " << q;
    }
    faces_only_cut += faces_meet && (!all_meet || face_lo < all_lo - 1e-9 || face_hi > all_hi + 1e-9);
    for (int k = 0; k <= 60; ++k) {
      const double s = 3.0 * k / 60.0;
      Obb moved = b;
      moved.centre_F += s * u;
      const bool apart = obbsDisjoint(a, moved);
      if (meets && s > lo + 1e-9 && s < hi - 1e-9) {
        EXPECT_FALSE(apart) << "s " << s;
      }
      if (!meets || s < lo - 1e-9 || s > hi + 1e-9) {
        EXPECT_TRUE(apart) << "s " << s;
      }
    }
  }
  EXPECT_GT(disjoint, 200);
  EXPECT_GT(overlapping, 200);
  EXPECT_GT(faces_only_cut, 50);  // the edge axes do cut some intervals: the comparison is not vacuous
}

TEST(Bvh, InnerCastAnswersAsTwoSeparateCasts) {
  // obbCastIntervalInner: the grown box's interval as obbCastInterval gives
  // it, and the inner box's face-axes verdict as obbCastIntervalFaces with no
  // slack gives it (true when the grown box is cleared).
  Rng rng(21);
  int grown_meets = 0, inner_apart_while_grown_meets = 0, inner_meets = 0;
  for (int q = 0; q < 4000; ++q) {
    // One case in seven moves along the first axis of boxes aligned with the
    // frame: speeds of zero along the other axes (the q == 0 cut).
    const bool aligned = q % 7 == 0;
    const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
    const Obb fixed = randomBox(rng, 1.0, 0.05, 1.0, aligned ? &identity : nullptr);
    Obb grown = randomBox(rng, 2.0, 0.02, 0.5, aligned || q % 5 == 0 ? &fixed.axes_F : nullptr);
    const Eigen::Vector3d inner_half = grown.half;
    grown.half += Eigen::Vector3d::Constant(uniform(rng, 0.0, 0.6));
    const Eigen::Vector3d u = aligned ? Eigen::Vector3d::UnitX() : generators::randomUnitVector(rng);
    const double max_s = q % 3 == 0 ? 0.5 : 3.0;
    const double slack = q % 2 == 0 ? 0.0 : 1e-9;
    double lo = -1, hi = -1, want_lo = -1, want_hi = -1;
    bool inner_apart = false;
    const bool meets = obbCastIntervalInner(fixed, grown, inner_half, u, max_s, slack, &lo, &hi, &inner_apart);
    const bool want = obbCastInterval(fixed, grown, u, max_s, slack, &want_lo, &want_hi);
    Obb inner = grown;
    inner.half = inner_half;
    double face_lo = 0, face_hi = 0;
    const bool want_inner_apart = !obbCastIntervalFaces(fixed, inner, u, max_s, 0.0, &face_lo, &face_hi);
    std::ostringstream repro;
    repro << std::setprecision(17) << "query " << q << ": fixed " << fixed.centre_F.transpose() << " / "
          << fixed.half.transpose() << ", moving " << grown.centre_F.transpose() << " / " << grown.half.transpose()
          << ", inner half " << inner_half.transpose() << ", u " << u.transpose() << ", max_s " << max_s;
    ASSERT_EQ(meets, want) << repro.str();
    if (meets) {
      // The same arithmetic; a tolerance for compilers that contract it
      // differently in the two instantiations.
      EXPECT_NEAR(lo, want_lo, 1e-12 * (1.0 + max_s)) << repro.str();
      EXPECT_NEAR(hi, want_hi, 1e-12 * (1.0 + max_s)) << repro.str();
      EXPECT_EQ(inner_apart, want_inner_apart) << repro.str();
      ++grown_meets;
      inner_apart_while_grown_meets += inner_apart;
      inner_meets += !inner_apart;
    } else {
      EXPECT_TRUE(inner_apart) << repro.str();
    }
  }
  // Both answers of the inner test occur while the grown boxes meet.
  EXPECT_GT(grown_meets, 1000);
  EXPECT_GT(inner_apart_while_grown_meets, 200);
  EXPECT_GT(inner_meets, 200);
}

/// Distance from p_F to the box (0 inside).
double distanceToBox(const Obb& box, const Eigen::Vector3d& p_F) {
  return ((box.axes_F.transpose() * (p_F - box.centre_F)).cwiseAbs() - box.half).cwiseMax(0.0).norm();
}

TEST(Bvh, SweptSphereAgainstABoxIsSoundAndSeparatesOnEveryFaceAxis) {
  // Closed form: the unit box at the origin.
  Obb unit;
  unit.half = Eigen::Vector3d::Ones();
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  EXPECT_TRUE(sweptSphereObbApart(unit, {2.5, 0, 0}, 1.0, zero, 0.0));   // a gap of 0.5 along x
  EXPECT_FALSE(sweptSphereObbApart(unit, {2.5, 0, 0}, 1.5, zero, 0.0));  // touching
  EXPECT_TRUE(sweptSphereObbApart(unit, {2.5, 0, 0}, 1.4, zero, 0.05));
  EXPECT_FALSE(sweptSphereObbApart(unit, {2.5, 0, 0}, 1.4, zero, 0.2));       // the slack closes the gap
  EXPECT_FALSE(sweptSphereObbApart(unit, {3, 0, 0}, 0.5, {-6, 0, 0}, 0.0));   // through the box
  EXPECT_TRUE(sweptSphereObbApart(unit, {3, 0, 0}, 0.5, {0, 5, 0}, 0.0));     // beside it
  EXPECT_FALSE(sweptSphereObbApart(unit, {3, -4, 0}, 0.5, {-4, 8, 0}, 0.0));  // across its middle
  // Off a corner, 0.85 away: apart, but on no face axis, so not reported.
  EXPECT_FALSE(sweptSphereObbApart(unit, {1.6, 1.6, 0}, 0.7, zero, 0.0));
  EXPECT_GT(distanceToBox(unit, {1.6, 1.6, 0}), 0.7);

  // Random boxes and swept spheres against two oracles: the distance from
  // the segment to the box (convex along it: a ternary search), which a
  // sphere reported apart must exceed (soundness), and the face axes' own
  // rule computed on the segment's ends one axis at a time (each separating
  // face axis must be found).
  Rng rng(31);
  int apart_count = 0, meets_count = 0;
  for (int q = 0; q < 3000; ++q) {
    const Obb box = randomBox(rng, 1.0, 0.02, 1.0);
    const Eigen::Vector3d c = uniformVector(rng, -1.5, 1.5);
    const double r = uniform(rng, 0.01, 0.8);
    const Eigen::Vector3d v = q % 4 == 0 ? Eigen::Vector3d::Zero() : uniformVector(rng, -2.0, 2.0);
    const bool apart = sweptSphereObbApart(box, c, r, v, 0.0);
    std::ostringstream repro;
    repro << std::setprecision(17) << "query " << q << ": box centre " << box.centre_F.transpose() << ", half "
          << box.half.transpose() << ", axes " << box.axes_F.reshaped().transpose() << "; c " << c.transpose() << ", r "
          << r << ", v " << v.transpose();
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 200; ++it) {
      const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
      if (distanceToBox(box, c + m1 * v) < distanceToBox(box, c + m2 * v)) {
        hi = m2;
      } else {
        lo = m1;
      }
    }
    const double gap = distanceToBox(box, c + 0.5 * (lo + hi) * v) - r;
    if (apart) {
      EXPECT_GT(gap, -1e-12) << repro.str();
    }
    bool face_separates = false;
    for (int k = 0; k < 3; ++k) {
      const double y0 = box.axes_F.col(k).dot(c - box.centre_F), y1 = box.axes_F.col(k).dot(c + v - box.centre_F);
      const double reach = box.half[k] + r;
      face_separates |= std::min(y0, y1) > reach + 1e-12 || std::max(y0, y1) < -reach - 1e-12;
    }
    if (face_separates) {
      EXPECT_TRUE(apart) << repro.str();
    }
    ++(apart ? apart_count : meets_count);
  }
  // Both answers are common: neither oracle comparison is vacuous.
  EXPECT_GT(apart_count, 600);
  EXPECT_GT(meets_count, 600);
}

/// The box of the world axes about the triangle's centroid that holds it
/// (what the traversals tested a triangle leaf by before the triangle tests).
Obb boxAround(const std::array<Eigen::Vector3d, 3>& tri) {
  Obb box;
  box.centre_F = (tri[0] + tri[1] + tri[2]) / 3.0;
  box.half = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : tri) box.half = box.half.cwiseMax((v - box.centre_F).cwiseAbs());
  return box;
}

TEST(Bvh, TriangleAgainstABoxAgreesWithTheCore) {
  // triangleObbApart (no slack) against the core's intersect on the
  // triangle and the box's corners as polytopes; triangles of every shape
  // (large and thin ones, some segments), boxes flat and thick.
  Rng rng(41);
  int apart_count = 0, meets_count = 0, box_test_misses = 0;
  for (int q = 0; q < 3000; ++q) {
    const Obb box = randomBox(rng, 1.0, q % 5 == 0 ? 0.001 : 0.05, 1.0);
    std::array<Eigen::Vector3d, 3> tri;
    const double size = q % 3 == 0 ? 3.0 : 1.0;
    for (Eigen::Vector3d& v : tri) v = uniformVector(rng, -size, size);
    const bool segment = q % 50 == 0;
    if (segment) tri[2] = 0.5 * (tri[0] + tri[1]);
    const bool apart = triangleObbApart(tri, box, 0.0);
    if (segment) {
      // No polytope for three collinear points: a sound answer is enough
      // (every point of a segment called apart lies outside the box).
      for (int k = 0; k <= 200 && apart; ++k) {
        EXPECT_GT(distanceToBox(box, tri[0] + (k / 200.0) * (tri[1] - tri[0])), 0.0) << "query " << q;
      }
      continue;
    }
    const auto corners = box.corners();
    const ConvexPolytope pb = ConvexPolytope::fromPoints(Points(corners.begin(), corners.end()));
    const ConvexPolytope pt = ConvexPolytope::fromPoints(Points(tri.begin(), tri.end()));
    IntersectInput in;
    in.a = &pb;
    in.b = &pt;
    std::ostringstream repro;
    repro << std::setprecision(17) << "query " << q << ": box centre " << box.centre_F.transpose() << ", half "
          << box.half.transpose() << ", axes " << box.axes_F.reshaped().transpose() << "; triangle "
          << tri[0].transpose() << " / " << tri[1].transpose() << " / " << tri[2].transpose();
    EXPECT_EQ(apart, !intersect(in).intersecting) << repro.str();
    ++(apart ? apart_count : meets_count);
    // The triangle's own box (what the traversal tested before): apart less often.
    const Obb tri_box = boxAround(tri);
    if (apart && !obbsDisjoint(tri_box, box, 0.0)) ++box_test_misses;
    if (!apart) {
      EXPECT_FALSE(obbsDisjoint(tri_box, box, 0.0)) << repro.str();
    }
  }
  EXPECT_GT(apart_count, 600);
  EXPECT_GT(meets_count, 600);
  EXPECT_GT(box_test_misses, 100);  // the triangle test prunes pairs its box does not
  // A slack closes a gap smaller than itself.
  Obb unit;
  unit.half = Eigen::Vector3d::Ones();
  const std::array<Eigen::Vector3d, 3> above{Eigen::Vector3d(0, 0, 1.5), Eigen::Vector3d(1, 0, 1.5),
                                             Eigen::Vector3d(0, 1, 1.5)};
  EXPECT_TRUE(triangleObbApart(above, unit, 0.4));
  EXPECT_FALSE(triangleObbApart(above, unit, 0.6));
  // Off the box's edge, apart only along an edge axis: the triangle x + y =
  // 2.2 (a gap of 0.2 / sqrt(2) from the edge x = y = 1).
  const std::array<Eigen::Vector3d, 3> diagonal{Eigen::Vector3d(2.2, 0, -3), Eigen::Vector3d(0, 2.2, -3),
                                                Eigen::Vector3d(1.1, 1.1, 3)};
  EXPECT_TRUE(triangleObbApart(diagonal, unit, 0.1));
  EXPECT_FALSE(triangleObbApart(diagonal, unit, 0.2));
}

TEST(Bvh, TriangleCastIsTheStaticTriangleTestAtEveryTime) {
  // triangleObbCastInterval against triangleObbApart at sampled s: inside
  // the interval the moved box meets the triangle, outside it (and on a false
  // answer, everywhere) it does not; the inner box's verdict holds at every
  // sampled s. Triangles of every shape (large, thin, slivers, segments), boxes
  // flat and thick, motions along and across the triangle.
  Rng rng(43);
  int meets_count = 0, cleared_count = 0, inner_apart_while_meeting = 0, inner_meets = 0, box_cast_misses = 0;
  for (int q = 0; q < 3000; ++q) {
    Obb moving = randomBox(rng, 2.0, q % 5 == 0 ? 0.001 : 0.05, 0.6);
    const Eigen::Vector3d inner_half = moving.half;
    moving.half += Eigen::Vector3d::Constant(uniform(rng, 0.0, 0.3));
    std::array<Eigen::Vector3d, 3> tri;
    const double size = q % 3 == 0 ? 3.0 : 1.0;
    for (Eigen::Vector3d& v : tri) v = uniformVector(rng, -size, size);
    const bool segment = q % 50 == 0;
    if (segment) tri[2] = 0.5 * (tri[0] + tri[1]);
    if (q % 50 == 25) {
      // A sliver at the loaders' limit (height 1e-7 of the longest edge):
      // the normal's computed direction is off its plane by about 1e-9.
      const Eigen::Vector3d f = tri[1] - tri[0];
      tri[2] = 0.5 * (tri[0] + tri[1]) + 1e-7 * f.norm() * f.unitOrthogonal();
    }
    // Toward the triangle (most casts meet it) or any way, one in eleven
    // along a box axis (zero speed along the other two: the q == 0 cut); u of
    // any length.
    Eigen::Vector3d u =
        q % 2 == 0 ? Eigen::Vector3d(tri[0] - moving.centre_F).normalized() : generators::randomUnitVector(rng);
    if (q % 11 == 0) u = moving.axes_F.col(q % 3);
    u *= q % 7 == 0 ? 0.3 : 1.0;
    const double max_s = q % 4 == 0 ? 1.0 : 5.0;
    const double slack = q % 3 == 0 ? 1e-9 : 0.0;
    double lo = -1, hi = -1;
    bool inner_apart = false;
    const bool meets = triangleObbCastInterval(tri, moving, u, max_s, slack, &lo, &hi, &inner_half, &inner_apart);
    std::ostringstream repro;
    repro << std::setprecision(17) << "query " << q << ": moving centre " << moving.centre_F.transpose() << ", half "
          << moving.half.transpose() << ", axes " << moving.axes_F.reshaped().transpose() << ", inner half "
          << inner_half.transpose() << "; triangle " << tri[0].transpose() << " / " << tri[1].transpose() << " / "
          << tri[2].transpose() << "; u " << u.transpose() << ", max_s " << max_s << ", slack " << slack;
    // Without the inner box: the same interval.
    double plain_lo = -1, plain_hi = -1;
    ASSERT_EQ(triangleObbCastInterval(tri, moving, u, max_s, slack, &plain_lo, &plain_hi), meets) << repro.str();
    if (meets) {
      EXPECT_EQ(plain_lo, lo) << repro.str();
      EXPECT_EQ(plain_hi, hi) << repro.str();
      EXPECT_LE(0.0, lo) << repro.str();
      EXPECT_LE(lo, hi) << repro.str();
      EXPECT_LE(hi, max_s) << repro.str();
    } else {
      EXPECT_TRUE(inner_apart) << repro.str();
    }
    const double tol = 1e-9 * max_s;
    bool inner_met_somewhere = false;
    for (int k = 0; k <= 100; ++k) {
      const double s = max_s * k / 100.0;
      Obb moved = moving;
      moved.centre_F += s * u;
      if (segment) {
        // triangleObbApart's normal axis is round-off for a segment: the
        // cast is only asked to be sound (a point of the segment in the
        // moved box lies in the interval).
        const bool outside = !meets || s < lo - tol || s > hi + tol;
        for (int j = 0; j <= 50 && outside; ++j) {
          EXPECT_GT(distanceToBox(moved, tri[0] + (j / 50.0) * (tri[1] - tri[0])), 0.0) << repro.str() << " at s " << s;
        }
        continue;
      }
      const bool apart = triangleObbApart(tri, moved, slack);
      if (meets && s > lo + tol && s < hi - tol) {
        EXPECT_FALSE(apart) << repro.str() << " at s " << s;
      }
      if (!meets || s < lo - tol || s > hi + tol) {
        EXPECT_TRUE(apart) << repro.str() << " at s " << s;
      }
      Obb inner = moved;
      inner.half = inner_half;
      inner_met_somewhere |= !triangleObbApart(tri, inner, 0.0);
    }
    if (inner_apart) {
      EXPECT_FALSE(inner_met_somewhere) << repro.str();
    }
    // The triangle's own box cast (what the traversals tested before): it
    // never clears a cast the triangle meets, and meets some it clears.
    const Obb tri_box = boxAround(tri);
    double box_lo = 0, box_hi = 0;
    const bool box_meets = obbCastInterval(tri_box, moving, u, max_s, slack, &box_lo, &box_hi);
    if (meets) {
      ++meets_count;
      inner_apart_while_meeting += inner_apart;
      inner_meets += !inner_apart;
      EXPECT_TRUE(box_meets) << repro.str();
    } else {
      ++cleared_count;
      box_cast_misses += box_meets;
    }
  }
  // Not vacuous: both answers, both inner verdicts while meeting, and casts
  // the triangle clears where its box does not.
  EXPECT_GT(meets_count, 900);
  EXPECT_GT(cleared_count, 600);
  EXPECT_GT(inner_apart_while_meeting, 100);
  EXPECT_GT(inner_meets, 300);
  EXPECT_GT(box_cast_misses, 100);
}

}  // namespace
}  // namespace mddual
