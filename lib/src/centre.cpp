// The centre of duality (paper IV-A), found without building M.
//
// The paper projects A and B along u onto a plane, builds both silhouettes and
// their 2D Minkowski difference M' (O(n)), and locates the origin in M'. We
// locate the origin in M' = projection of M with a 2D portal refinement
// (Minkowski portal refinement in the plane) driven by support queries on A
// and B, which touches O(log n) vertices per support with the hierarchy or a
// warm start instead of all of them:
//
//   1. v0 = projection of g (centroid(A) - centroid(B), interior to M).
//   2. Discovery: v1 = support of M' toward the origin, v2 = support normal
//      to v0-v1 on the origin's side, repeated until v1 and v2 lie on either
//      side of the ray from v0 through the origin; the portal v1-v2 then
//      crosses that ray ahead of v0.
//   3. Refinement: replace the portal end on the same side as the new support
//      point in the portal's outward normal, until the origin is inside the
//      triangle (v0, v1, v2) with a weight >= kCentreMinWeight on v0, or the
//      portal reaches the boundary of M'.
//   4. Result: barycentric weights (w0, w1, w2) of the origin give
//      c = w0 g + w1 m1 + w2 m2 on the line; w0 > 0 and g interior put c in
//      the interior of M (a convex combination with positive weight on an
//      interior point).
//
// Every support value h_M(w) seen on the way is a certificate: h < -tol means
// the line misses M (no contact), |h| <= tol that the line lies in a
// supporting plane (grazing; answered by the planar path).
#include "centre.h"

#include <cmath>

#include "mddual/defaults.h"
#include "mddual/error.h"

namespace mddual::detail {
namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Support of M' = projection of M in a 2D direction, with the 3D point.
struct PlanarSupport {
  MPoint m;
  Eigen::Vector2d v;
  double h = 0.0;  // support value along the unit 2D direction
  Eigen::Vector3d w_A;
};

}  // namespace

Centre findCentre(const PairGeometry& pair, const Eigen::Vector3d& u_A, WarmStart* warm, SearchStats* stats) {
  const Eigen::Vector3d t = std::abs(u_A.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = u_A.cross(t).normalized();
  const Eigen::Vector3d e2 = u_A.cross(e1);
  auto project = [&](const Eigen::Vector3d& x) { return Eigen::Vector2d(x.dot(e1), x.dot(e2)); };
  const double tol = pair.touchTolerance();
  // Warm hints per stage: consecutive queries on a pair search in similar
  // directions at the same stage (0: toward the origin, 1: across the ray),
  // so those start where they ended last time; refinement steps start from
  // the previous support of this query, whose direction is close.
  int stage = 0;
  int hint_a = -1;
  int hint_b = -1;

  Centre out;
  auto support = [&](const Eigen::Vector2d& dir) {
    PlanarSupport s;
    const Eigen::Vector2d n = dir.normalized();
    s.w_A = n.x() * e1 + n.y() * e2;
    const bool warm_stage = warm != nullptr && stage < 2;
    if (warm_stage && warm->centre_a[stage] >= 0) hint_a = warm->centre_a[stage];
    if (warm_stage && warm->centre_b[stage] >= 0) hint_b = warm->centre_b[stage];
    s.m = pair.supportM(s.w_A, hint_a, hint_b, stats);
    hint_a = s.m.va;
    hint_b = s.m.vb;
    if (warm_stage) {
      warm->centre_a[stage] = hint_a;
      warm->centre_b[stage] = hint_b;
    }
    ++stage;
    s.v = project(s.m.p_A);
    s.h = n.dot(s.v);
    return s;
  };
  // A support value proves "no contact" (h < -tol) or "grazing" (|h| <= tol).
  auto certificate = [&](const PlanarSupport& s) {
    if (s.h > tol) return false;
    out.kind = s.h < -tol ? Centre::Kind::kNoContact : Centre::Kind::kGrazing;
    out.w_A = s.w_A;
    out.va = s.m.va;
    out.vb = s.m.vb;
    return true;
  };
  auto finish = [&](const Eigen::Vector3d& c0, const Eigen::Vector3d& m1, const Eigen::Vector3d& m2) {
    out.kind = Centre::Kind::kInterior;
    out.m1_A = m1;
    out.m2_A = m2;
    out.tau = c0.dot(u_A);
    out.c_A = out.tau * u_A;  // exactly on the line
    return out;
  };

  // 1. The interior point g, projected.
  const Eigen::Vector3d& g = pair.interiorPoint();
  const Eigen::Vector2d v0 = project(g);
  if (v0.isZero(0.0)) return finish(g, g, g);

  // 2. Discovery.
  const Eigen::Vector2d r = -v0.normalized();
  PlanarSupport s1 = support(r);
  if (certificate(s1)) return out;
  // Side of the ray a point is on: +1, -1, or 0 when on it (sine of the
  // angle at v0 within kParallelSin).
  auto side = [&](const Eigen::Vector2d& v) {
    const double c = cross2(r, v - v0);
    return std::abs(c) <= defaults::kParallelSin * (v - v0).norm() ? 0 : (c > 0.0 ? 1 : -1);
  };
  const int side1 = side(s1.v);
  if (side1 == 0) {
    // v1 lies on the ray beyond the origin: the origin is on segment v0-v1.
    const double lambda = v0.norm() / r.dot(s1.v - v0);
    return finish((1.0 - lambda) * g + lambda * s1.m.p_A, s1.m.p_A, s1.m.p_A);
  }
  // v2: support perpendicular to v0-v1 on the origin's side. Everything on
  // that side of the line v0-v1 meets the ray ahead of v0, so once v1 and v2
  // lie on opposite sides of the ray the portal v1-v2 crosses it ahead of v0.
  // While v2 lands on v1's side it becomes the new v1 (closer to the ray).
  PlanarSupport s2;
  for (int it = 0;; ++it) {
    if (it == defaults::kMaxCentreIterations) {
      throw NumericalError("centre of duality: portal discovery did not converge in " +
                           std::to_string(defaults::kMaxCentreIterations) + " steps");
    }
    const Eigen::Vector2d edge = s1.v - v0;
    Eigen::Vector2d normal(-edge.y(), edge.x());
    if (normal.dot(-v0) < 0.0) normal = -normal;
    s2 = support(normal);
    if (certificate(s2)) return out;
    const int side2 = side(s2.v);
    if (side2 != side1) break;
    s1 = s2;
  }

  // 3. Refinement.
  for (int it = 0; it < defaults::kMaxCentreIterations; ++it) {
    if (stats != nullptr) ++stats->centre_iterations;
    const Eigen::Vector2d edge = s2.v - s1.v;
    Eigen::Vector2d normal = Eigen::Vector2d(edge.y(), -edge.x()).normalized();
    if (normal.dot(s1.v - v0) < 0.0) normal = -normal;
    const double origin_beyond = -normal.dot(s1.v);  // > 0: origin outside the portal
    const double v0_depth = normal.dot(s1.v - v0);   // > 0
    const bool inside = origin_beyond <= 0.0;
    if (inside && -origin_beyond >= defaults::kCentreMinWeight * v0_depth) break;
    PlanarSupport s3 = support(normal);
    if (certificate(s3)) return out;
    if (normal.dot(s3.v - s1.v) <= tol) {
      // The portal is on the boundary of M'.
      if (inside) break;
      out.kind = Centre::Kind::kGrazing;  // origin within round-off of the portal
      out.w_A = s3.w_A;
      out.va = s3.m.va;
      out.vb = s3.m.vb;
      return out;
    }
    if (side(s3.v) == side1) {
      s1 = s3;
    } else {
      s2 = s3;
    }
    if (it + 1 == defaults::kMaxCentreIterations) {
      throw NumericalError("centre of duality: portal refinement did not converge in " +
                           std::to_string(defaults::kMaxCentreIterations) + " steps");
    }
  }

  // 4. Barycentric weights of the origin in (v0, v1, v2).
  const double area = cross2(s1.v - v0, s2.v - v0);
  const double w1 = std::max(0.0, cross2(-v0, s2.v - v0) / area);
  const double w2 = std::max(0.0, cross2(s1.v - v0, -v0) / area);
  const double w0 = std::max(0.0, 1.0 - w1 - w2);
  return finish(w0 * g + w1 * s1.m.p_A + w2 * s2.m.p_A, s1.m.p_A, s2.m.p_A);
}

}  // namespace mddual::detail
