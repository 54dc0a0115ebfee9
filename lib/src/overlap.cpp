// Minkowski portal refinement (Snethen, "XenoCollide", Game Programming Gems 7)
// used as a certificate of overlap or separation before an MDD-DUAL search:
//
//   1. v0: an interior point of M; the ray from v0 through the origin.
//   2. Portal discovery: support points v1, v2, v3 of M such that the ray
//      passes through the triangle (v1, v2, v3) (the portal).
//   3. Refinement: if the origin lies on v0's side of the portal it is inside
//      the tetrahedron (v0, v1, v2, v3), hence in M. Otherwise the support
//      along the portal's normal replaces the portal vertex that keeps the ray
//      inside the new portal, and so on.
//
// Every support value is also a separation test: a support point p along a
// unit direction n with n . p < -tol proves the plane n . x = n . p separates
// the origin from M. When neither certificate appears within a few steps the
// caller falls back to the exact search.
#include "overlap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace mddual::detail {
namespace {

/// Refinement steps before giving up: enough for deep overlaps and clear
/// separations; near-contact cases go to the exact search anyway.
constexpr int kMaxPortalSteps = 8;

double triple(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return a.dot(b.cross(c));
}

}  // namespace

double originDepthInTetrahedron(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                                const Eigen::Vector3d& p3) {
  const Eigen::Vector3d* p[4] = {&p0, &p1, &p2, &p3};
  const double volume6 = triple(p1 - p0, p2 - p0, p3 - p0);
  const double size = std::max(
      {(p1 - p0).norm(), (p2 - p0).norm(), (p3 - p0).norm(), (p2 - p1).norm(), (p3 - p1).norm(), (p3 - p2).norm()});
  if (!(std::abs(volume6) > 1e-12 * size * size * size)) return -std::numeric_limits<double>::infinity();
  double depth = std::numeric_limits<double>::infinity();
  for (int l = 0; l < 4; ++l) {  // the face opposite vertex l
    const Eigen::Vector3d& a = *p[(l + 1) % 4];
    const Eigen::Vector3d& b = *p[(l + 2) % 4];
    const Eigen::Vector3d& c = *p[(l + 3) % 4];
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.dot(*p[l] - a) > 0.0) n = -n;              // outward
    depth = std::min(depth, n.normalized().dot(a));  // the origin's distance inside this plane
  }
  return depth;
}

OverlapTest portalOverlapTest(const PairGeometry& pair, const Eigen::Vector3d& v0, double min_depth, WarmStart* warm,
                              SearchStats* stats) {
  OverlapTest out;
  const double tol = pair.touchTolerance();
  // Hints: the first three supports start where they ended in the last
  // query on this pair (warm), later ones from the previous support (close
  // directions).
  int stage = 0;
  int hint_a = -1;
  int hint_b = -1;
  // Support of M along n (any length); false when it proves separation or
  // does not reach past the origin (then no certificate can follow).
  auto support = [&](const Eigen::Vector3d& n, Eigen::Vector3d* v) {
    const Eigen::Vector3d unit = n.normalized();
    const bool warm_stage = warm != nullptr && stage < 3;
    if (warm_stage && warm->overlap_a[stage] >= 0) hint_a = warm->overlap_a[stage];
    if (warm_stage && warm->overlap_b[stage] >= 0) hint_b = warm->overlap_b[stage];
    const MPoint m = pair.supportM(unit, hint_a, hint_b, stats);
    hint_a = m.va;
    hint_b = m.vb;
    if (warm_stage) {
      warm->overlap_a[stage] = m.va;
      warm->overlap_b[stage] = m.vb;
    }
    ++stage;
    *v = m.p_A;
    const double h = unit.dot(m.p_A);
    if (h < -tol) {
      out.kind = OverlapTest::Kind::kSeparated;
      out.n_A = unit;
    }
    return h > tol;
  };
  auto inside = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    if (originDepthInTetrahedron(v0, a, b, c) > min_depth) out.kind = OverlapTest::Kind::kOverlap;
    return out;
  };
  const double scale = pair.scale();
  if (!(v0.norm() > 1e-12 * scale)) return out;  // the origin is v0 itself: depth unknown

  // 2. Portal discovery.
  Eigen::Vector3d v1;
  Eigen::Vector3d v2;
  Eigen::Vector3d v3;
  if (!support(-v0, &v1)) return out;
  Eigen::Vector3d n = v0.cross(v1);                             // normal of the plane (v0, v1, origin)
  if (!(n.norm() > 1e-12 * v0.norm() * v1.norm())) return out;  // origin on the segment v0-v1: depth unknown
  if (!support(n, &v2)) return out;
  n = (v1 - v0).cross(v2 - v0);
  if (n.dot(v0) > 0.0) {  // orient the portal so that n faces the origin
    std::swap(v1, v2);
    n = -n;
  }
  for (int step = 0;; ++step) {
    if (step == kMaxPortalSteps || !support(n, &v3)) return out;
    // The ray must pass inside the planes (v0, v1, v3) and (v0, v3, v2).
    if (triple(v1, v3, v0) < 0.0) {
      v2 = v3;
      n = (v1 - v0).cross(v3 - v0);
    } else if (triple(v3, v2, v0) < 0.0) {
      v1 = v3;
      n = (v3 - v0).cross(v2 - v0);
    } else {
      break;
    }
  }

  // 3. Refinement.
  for (int step = 0; step < kMaxPortalSteps; ++step) {
    n = (v2 - v1).cross(v3 - v1);
    if (n.dot(v1 - v0) < 0.0) n = -n;  // away from v0
    if (n.dot(v1) >= 0.0) return inside(v1, v2, v3);
    Eigen::Vector3d v4;
    if (!support(n, &v4)) return out;
    if (n.normalized().dot(v4 - v1) <= tol) return out;  // the portal is on the boundary, origin beyond it
    // Keep the ray inside the new portal: v4 replaces one of v1, v2, v3.
    const Eigen::Vector3d c = v4.cross(v0);
    if (v1.dot(c) > 0.0) {
      (v2.dot(c) > 0.0 ? v1 : v3) = v4;
    } else {
      (v3.dot(c) > 0.0 ? v2 : v1) = v4;
    }
  }
  return out;
}

OverlapTest trianglesSeparated(const PairGeometry& pair, double tol) {
  // In A's frame. For an axis L (any length), A's projection [lo_a, hi_a]
  // and B's [lo_b, hi_b]; the gap along the unit axis is
  // max(lo_b - hi_a, lo_a - hi_b) / |L|. Its round-off (a few 1e-16 of the
  // pair's scale) is far below tol (1e-10 of it): a gap above 2 tol is a
  // separation the exact test also sees.
  const std::array<Eigen::Vector3d, 3> a = {pair.a().localVertex(0), pair.a().localVertex(1), pair.a().localVertex(2)};
  const std::array<Eigen::Vector3d, 3> b = {pair.bVertex(0), pair.bVertex(1), pair.bVertex(2)};
  const std::array<Eigen::Vector3d, 3> ea = {a[1] - a[0], a[2] - a[1], a[0] - a[2]};
  const std::array<Eigen::Vector3d, 3> eb = {b[1] - b[0], b[2] - b[1], b[0] - b[2]};
  const double threshold = 2.0 * tol;
  OverlapTest out;
  const auto separates = [&](const Eigen::Vector3d& L) {
    const double la0 = L.dot(a[0]), la1 = L.dot(a[1]), la2 = L.dot(a[2]);
    const double lb0 = L.dot(b[0]), lb1 = L.dot(b[1]), lb2 = L.dot(b[2]);
    const double hi_a = std::max({la0, la1, la2}), lo_b = std::min({lb0, lb1, lb2});
    const double lo_a = std::min({la0, la1, la2}), hi_b = std::max({lb0, lb1, lb2});
    const double gap = std::max(lo_b - hi_a, lo_a - hi_b);
    if (!(gap > 0.0)) return false;
    const double norm = L.norm();
    if (!(gap > threshold * norm)) return false;  // also false for a zero (degenerate) axis
    out.kind = OverlapTest::Kind::kSeparated;
    out.n_A = (lo_b - hi_a >= lo_a - hi_b ? L : Eigen::Vector3d(-L)) / norm;
    return true;
  };
  if (separates(ea[0].cross(ea[1])) || separates(eb[0].cross(eb[1]))) return out;
  for (const Eigen::Vector3d& e : ea) {
    for (const Eigen::Vector3d& f : eb) {
      if (separates(e.cross(f))) return out;
    }
  }
  return out;
}

}  // namespace mddual::detail
