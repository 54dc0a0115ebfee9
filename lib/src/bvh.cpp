// Bvh: the volume tests (oriented boxes apart, cast intervals) and the
// traversals (box and oriented box queries, tree against tree, the
// branch-and-bound cast). Construction is in bvh_build.cpp.
#include "mddual/bvh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <tuple>

#include "bvh_internal.h"
#include "constants.h"
#include "mddual/error.h"
#include "mddual/query.h"
#include "pair.h"

namespace mddual {
namespace {

using detail::kInf;
using detail::magnitude;
using detail::nodeScale;
using detail::Posed;
using detail::PosedNodes;
using detail::Scratch;
using detail::ScratchLease;

/// The slack of the volume tests (see bvh.h).
constexpr double kSatSlackRel = kBvhSlackRel;
/// Added to |R_ij| in the separating-axis tests (Gottschalk's epsilon): a
/// cross product of nearly parallel edge directions is not a reliable axis.
constexpr double kParallelEps = 1e-12;
/// A hull's toi is used as a lower bound less this fraction of the pair's
/// length scale (the core's answers are accurate to ~1e-10 of it; pieces'
/// tois computed separately may come out that much below the hull's).
constexpr double kHullBoundSlackRel = 1e-8;

/// Whether spheres (c1, r1) and (c2, r2) are apart by more than `slack`.
bool spheresApart(const Eigen::Vector3d& c1, double r1, const Eigen::Vector3d& c2, double r2, double slack) {
  const double r = r1 + r2 + slack;
  return (c1 - c2).squaredNorm() > r * r;
}

/// Whether sphere (c, r) misses the sphere (c0, r0) swept from c0 along unit u
/// by [0, length] (length may be +infinity) by more than `slack`.
bool sweptSphereApart(const Eigen::Vector3d& c0, double r0, const Eigen::Vector3d& u, double length,
                      const Eigen::Vector3d& c, double r, double slack) {
  const double s = std::clamp((c - c0).dot(u), 0.0, length);
  return spheresApart(c0 + s * u, r0, c, r, slack);
}

/// Whether an oriented box of half extents obb_half is much smaller than an
/// axis-aligned box of half extents aabb_half (less than kObbTightRatio of
/// its volume).
bool obbMuchTighter(const Eigen::Vector3d& obb_half, const Eigen::Vector3d& aabb_half) {
  constexpr double kObbTightRatio = 0.25;
  return obb_half.prod() < kObbTightRatio * aabb_half.prod();
}

/// Which node of a pair to descend: the larger one that has children.
bool descendA(const Bvh::Node& a, const Bvh::Node& b) {
  if (b.isLeaf()) return true;
  if (a.isLeaf()) return false;
  return a.radius >= b.radius;
}

/// Separating-axis data of two boxes: b's axes and centre offset in a's frame.
struct SatFrame {
  Eigen::Matrix3d R, absR;
  Eigen::Vector3d t;
  double slack;
  // Inlined into each test (three of them): outlined, it cost twistycool's
  // state checks about 10% more instructions (callgrind;
  // docs/results/tuning.md).
  [[gnu::always_inline]] inline SatFrame(const Obb& a, const Obb& b, double slack_) : slack(slack_) {
    R = a.axes_F.transpose() * b.axes_F;
    absR = R.cwiseAbs().array() + kParallelEps;
    t = a.axes_F.transpose() * (b.centre_F - a.centre_F);
  }
};

double satSlack(const Obb& a, const Obb& b) {
  return kSatSlackRel * (magnitude(a.centre_F, a.half) + magnitude(b.centre_F, b.half));
}

}  // namespace

// ---- Obb ---------------------------------------------------------------------------

Obb Obb::transformed(const Eigen::Isometry3d& X_GF, double margin) const {
  Obb out;
  out.centre_F = X_GF * centre_F;
  out.axes_F = X_GF.linear() * axes_F;
  out.half = half.array() + margin;
  return out;
}

std::array<Eigen::Vector3d, 8> Obb::corners() const {
  std::array<Eigen::Vector3d, 8> out;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d s((c & 1) ? 1.0 : -1.0, (c & 2) ? 1.0 : -1.0, (c & 4) ? 1.0 : -1.0);
    out[static_cast<std::size_t>(c)] = centre_F + axes_F * s.cwiseProduct(half);
  }
  return out;
}

bool Obb::contains(const Eigen::Vector3d& p_F, double tol) const {
  const Eigen::Vector3d y = axes_F.transpose() * (p_F - centre_F);
  return (y.cwiseAbs() - half).maxCoeff() <= tol;
}

bool obbsDisjoint(const Obb& a, const Obb& b, double slack) {
  const SatFrame f(a, b, slack);
  const Eigen::Vector3d& ha = a.half;
  const Eigen::Vector3d& hb = b.half;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(f.t[i]) > ha[i] + hb.dot(f.absR.row(i)) + f.slack) return true;
  }
  for (int j = 0; j < 3; ++j) {
    if (std::abs(f.t.dot(f.R.col(j))) > ha.dot(f.absR.col(j)) + hb[j] + f.slack) return true;
  }
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double ra = ha[i1] * f.absR(i2, j) + ha[i2] * f.absR(i1, j);
      const double rb = hb[j1] * f.absR(i, j2) + hb[j2] * f.absR(i, j1);
      if (std::abs(f.t[i2] * f.R(i1, j) - f.t[i1] * f.R(i2, j)) > ra + rb + f.slack) return true;
    }
  }
  return false;
}

namespace {

/// obbCastIntervalInner's second question: the moving box's half extents
/// replaced by *half (no slack), and where its answer goes.
struct InnerCast {
  const Eigen::Vector3d* half = nullptr;
  bool* apart = nullptr;
};

/// Along an axis: |p + s q| <= r cuts [*lo, *hi]; false once it is empty.
/// One reciprocal instead of two divisions (the hot spot of the rotating and
/// translating traversals; the product's round-off, 1e-16 relative, is far
/// below the slack).
bool cutInterval(double p, double q, double r, double* lo, double* hi) {
  if (q == 0.0) return !(std::abs(p) > r) && *lo <= *hi;  // NaN: not apart
  const double inv = 1.0 / q;
  double s0 = (-r - p) * inv, s1 = (r - p) * inv;
  if (s0 > s1) std::swap(s0, s1);
  *lo = std::max(*lo, s0);
  *hi = std::min(*hi, s1);
  return *lo <= *hi;
}

/// obbCastInterval; without the 9 edge-direction axes when edge_axes is
/// false (a superset of the overlap interval: its entry is still a lower
/// bound of the true one, for less work). With kInner, the face axes also
/// cut the inner box's interval (obbCastIntervalInner), which needs no more
/// than its own radii: the frame, offsets and speeds along the axes are the
/// moving box's.
template <bool kInner>
bool castInterval(const Obb& fixed, const Obb& moving, const Eigen::Vector3d& u, double max_s, double slack,
                  bool edge_axes, double* s_lo, double* s_hi, InnerCast inner = {}) {
  const SatFrame f(fixed, moving, slack);
  const Eigen::Vector3d w = fixed.axes_F.transpose() * u;
  double lo = 0.0, hi = max_s;
  double inner_lo = 0.0, inner_hi = max_s;
  bool inner_meets = true;
  // A face axis: the moving box's cut (radius r), then the inner box's
  // (radius r_inner) while it still meets.
  const auto cutFace = [&](double p, double q, double r, double r_inner) {
    if (!cutInterval(p, q, r, &lo, &hi)) return false;
    if (kInner && inner_meets) inner_meets = cutInterval(p, q, r_inner, &inner_lo, &inner_hi);
    return true;
  };
  const auto innerApart = [&](bool apart) {
    if constexpr (kInner) *inner.apart = apart;
  };
  const Eigen::Vector3d& ha = fixed.half;
  const Eigen::Vector3d& hb = moving.half;
  for (int i = 0; i < 3; ++i) {
    const double r_inner = kInner ? ha[i] + inner.half->dot(f.absR.row(i)) : 0.0;
    if (!cutFace(f.t[i], w[i], ha[i] + hb.dot(f.absR.row(i)) + f.slack, r_inner)) {
      innerApart(true);
      return false;
    }
  }
  for (int j = 0; j < 3; ++j) {
    const double r_fixed = ha.dot(f.absR.col(j));
    const double r_inner = kInner ? r_fixed + (*inner.half)[j] : 0.0;
    if (!cutFace(f.t.dot(f.R.col(j)), w.dot(f.R.col(j)), r_fixed + hb[j] + f.slack, r_inner)) {
      innerApart(true);
      return false;
    }
  }
  innerApart(!inner_meets);
  if (edge_axes) {
    for (int i = 0; i < 3; ++i) {
      const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
      for (int j = 0; j < 3; ++j) {
        const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
        const double ra = ha[i1] * f.absR(i2, j) + ha[i2] * f.absR(i1, j);
        const double rb = hb[j1] * f.absR(i, j2) + hb[j2] * f.absR(i, j1);
        const double p = f.t[i2] * f.R(i1, j) - f.t[i1] * f.R(i2, j);
        const double q = w[i2] * f.R(i1, j) - w[i1] * f.R(i2, j);
        if (!cutInterval(p, q, ra + rb + f.slack, &lo, &hi)) {
          innerApart(true);  // separated here: so is the inner box, which lies inside `moving`
          return false;
        }
      }
    }
  }
  *s_lo = lo;
  *s_hi = hi;
  return true;
}

}  // namespace

bool obbCastInterval(const Obb& fixed, const Obb& moving, const Eigen::Vector3d& u, double max_s, double slack,
                     double* s_lo, double* s_hi) {
  return castInterval<false>(fixed, moving, u, max_s, slack, true, s_lo, s_hi);
}

bool obbCastIntervalFaces(const Obb& fixed, const Obb& moving, const Eigen::Vector3d& u, double max_s, double slack,
                          double* s_lo, double* s_hi) {
  return castInterval<false>(fixed, moving, u, max_s, slack, false, s_lo, s_hi);
}

bool obbCastIntervalInner(const Obb& fixed, const Obb& moving, const Eigen::Vector3d& inner_half,
                          const Eigen::Vector3d& u, double max_s, double slack, double* s_lo, double* s_hi,
                          bool* inner_apart) {
  return castInterval<true>(fixed, moving, u, max_s, slack, true, s_lo, s_hi, InnerCast{&inner_half, inner_apart});
}

bool sweptAabbApart(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& c, const Eigen::Vector3d& h,
                    const Eigen::Vector3d& u, double max_s, double slack) {
  double lo = 0.0, hi = max_s;
  for (int k = 0; k < 3; ++k) {
    // c_k + s u_k must lie in [a, b] for the boxes to overlap along axis k.
    const double a = box.min()[k] - h[k] - slack, b = box.max()[k] + h[k] + slack;
    if (u[k] == 0.0) {
      if (c[k] < a || c[k] > b) return true;
      continue;
    }
    const double inv = 1.0 / u[k];
    double s0 = (a - c[k]) * inv, s1 = (b - c[k]) * inv;
    if (s0 > s1) std::swap(s0, s1);
    lo = std::max(lo, s0);
    hi = std::min(hi, s1);
    if (lo > hi) return true;
  }
  return false;
}

bool triangleObbApart(const std::array<Eigen::Vector3d, 3>& tri, const Obb& box, double slack) {
  // 1. The triangle in the box's frame, where the box is [-half, half].
  const Eigen::Matrix3d& U = box.axes_F;
  const Eigen::Vector3d p0 = U.transpose() * (tri[0] - box.centre_F);
  const Eigen::Vector3d p1 = U.transpose() * (tri[1] - box.centre_F);
  const Eigen::Vector3d p2 = U.transpose() * (tri[2] - box.centre_F);
  const Eigen::Vector3d& h = box.half;
  // 2. The box's face normals: the triangle's extent against the box's.
  const Eigen::Array3d lo = p0.cwiseMin(p1).cwiseMin(p2).array(), hi = p0.cwiseMax(p1).cwiseMax(p2).array();
  if ((lo - h.array() > slack).any() || (hi + h.array() < -slack).any()) return true;
  // 3. An axis a of any length: the box projects to [-r, r], r = half .
  //    |a|; the slack is scaled by |a|_1 >= |a| (no square root, and never
  //    less than the slack along the unit axis). The 9 axes e_k x f are
  //    perpendicular to an edge f of the triangle (their components are f's
  //    own, no round-off), whose two ends project to one point: the
  //    triangle's interval is spanned by one end, q, and the third vertex, w
  //    (Akenine-Moller's triangle-box test). The ends differ by the
  //    round-off of the dot products, about 1e-16 of |a| |p|, far below the
  //    slack (kBvhSlackRel of the scale). Callgrind, the state checks of the
  //    five mesh configs: 3% to 8% fewer instructions than projecting all
  //    three (docs/results/planning-speed.md, "A world triangle against the robot node's box").
  const auto apart = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& q, const Eigen::Vector3d& w) {
    const double r = h.dot(a.cwiseAbs()) + slack * a.cwiseAbs().sum();
    const double dq = a.dot(q), dw = a.dot(w);
    return std::min(dq, dw) > r || std::max(dq, dw) < -r;
  };
  const Eigen::Vector3d f0 = p1 - p0, f1 = p2 - p1, f2 = p0 - p2;
  // The triangle's normal, from all three corners (zero for a segment, never
  // apart): for a sliver its computed direction is off the plane by up to
  // 1e-16 of the edges over the height, and any axis is sound when the
  // triangle's span along it is measured, not assumed.
  const Eigen::Vector3d n = f0.cross(f1);
  const double r_n = h.dot(n.cwiseAbs()) + slack * n.cwiseAbs().sum();
  const double d0 = n.dot(p0), d1 = n.dot(p1), d2 = n.dot(p2);
  if (std::min({d0, d1, d2}) > r_n || std::max({d0, d1, d2}) < -r_n) return true;
  // 4. Box axis e_k x edge f: e_x x f = (0, -f_z, f_y), e_y x f = (f_z, 0,
  //    -f_x), e_z x f = (-f_y, f_x, 0); f0 joins p0 and p1, f1 p1 and p2, f2
  //    p2 and p0.
  const auto apartAlong = [&](const Eigen::Vector3d& f, const Eigen::Vector3d& q, const Eigen::Vector3d& w) {
    return apart(Eigen::Vector3d(0.0, -f.z(), f.y()), q, w) || apart(Eigen::Vector3d(f.z(), 0.0, -f.x()), q, w) ||
           apart(Eigen::Vector3d(-f.y(), f.x(), 0.0), q, w);
  };
  return apartAlong(f0, p0, p2) || apartAlong(f1, p1, p0) || apartAlong(f2, p2, p1);
}

bool triangleObbCastInterval(const std::array<Eigen::Vector3d, 3>& tri, const Obb& moving, const Eigen::Vector3d& u,
                             double max_s, double slack, double* s_lo, double* s_hi, const Eigen::Vector3d* inner_half,
                             bool* inner_apart) {
  // 1. The triangle in the moving box's frame at s = 0, where the box is
  //    [-h, h] and moves by s w.
  const Eigen::Matrix3d& U = moving.axes_F;
  const Eigen::Vector3d p0 = U.transpose() * (tri[0] - moving.centre_F);
  const Eigen::Vector3d p1 = U.transpose() * (tri[1] - moving.centre_F);
  const Eigen::Vector3d p2 = U.transpose() * (tri[2] - moving.centre_F);
  const Eigen::Vector3d w = U.transpose() * u;
  const Eigen::Vector3d& h = moving.half;
  const Eigen::Vector3d g = inner_half ? *inner_half : h;
  double lo = 0.0, hi = max_s, in_lo = 0.0, in_hi = max_s;
  bool inner_meets = inner_half != nullptr;
  // 2. On an axis a of any length along which the triangle spans [m - t, m
  //    + t] and the box [-r, r] + s (a . w), r = h . |a|: they meet while
  //    |m - s (a . w)| <= r + t. The box's cut, r with the slack (scaled by
  //    |a|_1 >= |a|, as in triangleObbApart), then the inner box's (radius
  //    g . |a|, no slack). Each axis's dot products are written out: six of
  //    the nine e_k x f have a zero component.
  const auto cut = [&](double m, double t, double aw, double ah, double a1, double ag) {
    if (!cutInterval(m, -aw, ah + t + slack * a1, &lo, &hi)) return false;
    if (inner_meets) inner_meets = cutInterval(m, -aw, ag + t, &in_lo, &in_hi);
    return true;
  };
  const auto finish = [&](bool meets) {
    if (inner_apart) *inner_apart = !meets || (inner_half != nullptr && !inner_meets);
    if (meets) {
      *s_lo = lo;
      *s_hi = hi;
    }
    return meets;
  };
  // 3. The box's face normals e_k: the triangle's extent along each.
  for (int k = 0; k < 3; ++k) {
    const double t_lo = std::min({p0[k], p1[k], p2[k]}), t_hi = std::max({p0[k], p1[k], p2[k]});
    if (!cut(0.5 * (t_lo + t_hi), 0.5 * (t_hi - t_lo), w[k], h[k], 1.0, g[k])) return finish(false);
  }
  // 4. The normal, from all three corners: for a sliver its computed
  //    direction is off the plane by up to 1e-16 of the edges over the
  //    height (1e-9 at the loaders' sliver limit, mesh_loader.cpp), and any
  //    axis is sound when the triangle's span along it is measured, not
  //    assumed.
  const Eigen::Vector3d f0 = p1 - p0, f1 = p2 - p1, f2 = p0 - p2;
  const Eigen::Vector3d n = f0.cross(f1), abs_n = n.cwiseAbs();
  const double d0 = n.dot(p0), d1 = n.dot(p1), d2 = n.dot(p2);
  const double n_lo = std::min({d0, d1, d2}), n_hi = std::max({d0, d1, d2});
  if (!cut(0.5 * (n_lo + n_hi), 0.5 * (n_hi - n_lo), n.dot(w), h.dot(abs_n), abs_n.sum(), g.dot(abs_n))) {
    return finish(false);
  }
  // 5. e_k x f for each edge f: e_x x f = (0, -f_z, f_y), e_y x f = (f_z,
  //    0, -f_x), e_z x f = (-f_y, f_x, 0), whose components are f's own (no
  //    round-off in the axis) and perpendicular to f: the triangle spans one
  //    end q of f and the third vertex v.
  const auto cutAlong = [&](const Eigen::Vector3d& f, const Eigen::Vector3d& q, const Eigen::Vector3d& v) {
    const double ax = std::abs(f.x()), ay = std::abs(f.y()), az = std::abs(f.z());
    // The axis whose nonzero components are c_i and c_j (abs_i = |c_i|).
    const auto across = [&](int i, int j, double ci, double cj, double abs_i, double abs_j) {
      const double dq = ci * q[i] + cj * q[j], dv = ci * v[i] + cj * v[j];
      return cut(0.5 * (dq + dv), 0.5 * std::abs(dq - dv), ci * w[i] + cj * w[j], h[i] * abs_i + h[j] * abs_j,
                 abs_i + abs_j, g[i] * abs_i + g[j] * abs_j);
    };
    return across(1, 2, -f.z(), f.y(), az, ay) && across(0, 2, f.z(), -f.x(), az, ax) &&
           across(0, 1, -f.y(), f.x(), ay, ax);
  };
  return finish(cutAlong(f0, p0, p2) && cutAlong(f1, p1, p0) && cutAlong(f2, p2, p1));
}

bool sweptSphereObbApart(const Obb& box, const Eigen::Vector3d& c, double r, const Eigen::Vector3d& v, double slack) {
  // The segment's ends in the box's frame (y = axes^T (x - centre)): the
  // sphere misses the box when, on one axis, both ends lie beyond the box's
  // half extent grown by r + slack, on the same side.
  const Eigen::Vector3d p0 = box.axes_F.transpose() * (c - box.centre_F);
  const Eigen::Vector3d p1 = p0 + box.axes_F.transpose() * v;
  const Eigen::Array3d reach = box.half.array() + (r + slack);
  return (p0.cwiseMin(p1).array() > reach).any() || (p0.cwiseMax(p1).array() < -reach).any();
}

bool obbsDisjoint(const Obb& a, const Obb& b) {
  return obbsDisjoint(a, b, satSlack(a, b));
}

bool obbCastInterval(const Obb& fixed, const Obb& moving, const Eigen::Vector3d& u, double max_s, double* s_lo,
                     double* s_hi) {
  return obbCastInterval(fixed, moving, u, max_s, satSlack(fixed, moving), s_lo, s_hi);
}

bool sweptAabbApart(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& c, const Eigen::Vector3d& h,
                    const Eigen::Vector3d& u, double max_s) {
  const double slack =
      kSatSlackRel * (magnitude(c, h) + box.min().cwiseAbs().maxCoeff() + box.max().cwiseAbs().maxCoeff());
  return sweptAabbApart(box, c, h, u, max_s, slack);
}

// ---- Queries -------------------------------------------------------------------------

bool Bvh::queryBox(const Eigen::AlignedBox3d& box_S, FunctionRef<bool(int)> fn) const {
  if (box_S.min().hasNaN() || box_S.max().hasNaN()) {  // infinite corners: an unbounded query
    throw InvalidInputError("Bvh::queryBox: the box has a NaN corner");
  }
  if (empty()) return true;
  ScratchLease s;
  s->stack.clear();
  s->stack.emplace_back(0, 0);
  while (!s->stack.empty()) {
    const int n = s->stack.back().first;
    s->stack.pop_back();
    const Node& node = nodes_[static_cast<std::size_t>(n)];
    if (!node.box.intersects(box_S)) continue;
    if (node.isLeaf()) {
      if (!fn(leafPiece(n))) return false;
      continue;
    }
    s->stack.emplace_back(node.right, 0);
    s->stack.emplace_back(node.left, 0);
  }
  return true;
}

bool Bvh::queryObb(const Obb& obb_S, FunctionRef<bool(int)> fn) const {
  if (obb_S.centre_F.hasNaN() || obb_S.axes_F.hasNaN() || obb_S.half.hasNaN()) {
    throw InvalidInputError("Bvh::queryObb: the box has a NaN entry");
  }
  if (empty()) return true;
  ScratchLease s;
  s->stack.clear();
  s->stack.emplace_back(0, 0);
  while (!s->stack.empty()) {
    const int n = s->stack.back().first;
    s->stack.pop_back();
    const Node& node = nodes_[static_cast<std::size_t>(n)];
    if (obbsDisjoint(node.obb, obb_S)) continue;
    if (node.isLeaf()) {
      if (!fn(leafPiece(n))) return false;
      continue;
    }
    s->stack.emplace_back(node.right, 0);
    s->stack.emplace_back(node.left, 0);
  }
  return true;
}

bool forEachOverlappingPair(const Bvh& a, const Bvh& b, const Eigen::Isometry3d& X_AB, double margin_b,
                            FunctionRef<bool(int, int)> fn, BvhStats* stats) {
  if (!(margin_b >= 0.0)) throw InvalidInputError("forEachOverlappingPair: margin_b is negative or NaN");
  // A NaN pose fails every overlap test: it would report no pair at all.
  // Finiteness only (see the header): the full pose check was 28% of the
  // thin wall's state-check instructions (callgrind; docs/results/tuning.md),
  // as its poses mostly reach no pair.
  requireFinitePose(X_AB, "pose X_AB", "forEachOverlappingPair");
  if (a.empty() || b.empty()) return true;
  ScratchLease s;
  PosedNodes posed(b, X_AB, margin_b, *s);
  s->stack.clear();
  BvhStats local;
  bool completed = true;
  // The pair visited next: a split pushes its second child pair and visits
  // the first at once (the order of a push of both and a pop); a pair
  // pruned or reported takes the next one from the stack.
  int na = a.root(), nb = b.root();
  const auto next = [&] {
    if (s->stack.empty()) return false;
    std::tie(na, nb) = s->stack.back();
    s->stack.pop_back();
    return true;
  };
  for (;;) {
    const Bvh::Node& A = a.node(na);
    const Bvh::Node& B = b.node(nb);
    ++local.node_pairs;
    // The volume tests, cheapest first, B's box posed only when its sphere
    // meets A's.
    const auto apart = [&] {
      const Posed& pb = posed.sphere(nb);
      const double slack = kSatSlackRel * (A.scale + pb.scale);
      if (spheresApart(A.centre, A.radius, pb.centre, pb.radius, slack)) return true;
      posed.box(nb);
      if (sweptAabbApart(A.box, pb.obb.centre_F, pb.aabb_half, Eigen::Vector3d::Zero(), 0.0, slack)) return true;
      // A triangle leaf of A: the exact triangle-box test in place of its
      // box (which a large triangle fills only half of).
      if (A.triangle >= 0) return triangleObbApart(a.triangle(A.triangle), pb.obb, slack);
      // The 15-axis test where it pays: at a leaf, or where A's box is much
      // larger than its oriented box (a tilted slab of large flat
      // triangles); near the roots of small trees it rarely prunes and cost
      // the small scenes up to half their state-check time.
      const bool obb_pays = A.isLeaf() || B.isLeaf() || obbMuchTighter(A.obb.half, 0.5 * A.box.sizes()) ||
                            obbMuchTighter(pb.obb.half, pb.aabb_half);
      return obb_pays && obbsDisjoint(A.obb, pb.obb, slack);
    };
    if (!apart()) {
      if (!A.isLeaf() || !B.isLeaf()) {
        if (descendA(A, B)) {
          s->stack.emplace_back(A.right, nb);
          na = A.left;
        } else {
          s->stack.emplace_back(na, B.right);
          nb = B.left;
        }
        continue;
      }
      ++local.leaf_pairs;
      if (!fn(a.leafPiece(na), b.leafPiece(nb))) {
        completed = false;
        break;
      }
    }
    if (!next()) break;
  }
  if (stats) {
    stats->node_pairs += local.node_pairs;
    stats->leaf_pairs += local.leaf_pairs;
  }
  return completed;
}

CastHit castFirst(const Bvh& a, const Bvh& b, const Eigen::Isometry3d& X_AB, const Eigen::Vector3d& u_A,
                  double max_distance, CastLeafFn leaf, const CastOptions& options, BvhStats* stats) {
  const Eigen::Vector3d u = detail::unitDirection(u_A, "castFirst");
  if (!(max_distance >= 0.0)) throw InvalidInputError("castFirst: max_distance is negative or NaN");
  // A NaN pose fails every overlap test: the cast would report no contact.
  // Finiteness only, as in forEachOverlappingPair (bvh.h).
  requireFinitePose(X_AB, "pose X_AB", "castFirst");
  if (!(options.margin_b >= 0.0)) throw InvalidInputError("castFirst: margin_b is negative or NaN");
  if (!(options.stop_within >= 0.0)) throw InvalidInputError("castFirst: stop_within is negative or NaN");
  CastHit hit;
  if (a.empty() || b.empty()) return hit;
  const bool hulls = options.use_hulls && options.margin_b == 0.0 && a.numHulls() > 0 && b.numHulls() > 0;
  ScratchLease s;
  PosedNodes posed(b, X_AB, options.margin_b, *s);
  BvhStats local;
  double best = kInf;  // best contact so far (a pair's distance <= the limit)
  const auto limit = [&] { return std::min(best, max_distance); };
  // Lower bound of the pair's contact distance, or +inf when it is pruned.
  const auto bound = [&](int na, int nb) {
    ++local.node_pairs;
    const Bvh::Node& A = a.node(na);
    const Posed& pb = posed.sphere(nb);
    const double lim = limit();
    const double slack = kSatSlackRel * (A.scale + pb.scale + (std::isfinite(lim) ? lim : 0.0));
    if (sweptSphereApart(pb.centre, pb.radius, u, lim, A.centre, A.radius, slack)) return kInf;
    posed.box(nb);
    if (sweptAabbApart(A.box, pb.obb.centre_F, pb.aabb_half, u, lim, slack)) return kInf;
    double lo = 0.0, hi = 0.0;
    // A yes/no cast (depth first): a triangle leaf of A larger than B's node
    // is tested itself on its 13 axes (its box may be twice its area, a
    // large triangle's much more). On the mesh configs' translating
    // checkMotion (mddual_bench_planning --mdd-only, callgrind) that takes
    // 3.5% to 7.4% fewer instructions (docs/results/tuning.md). Not for the
    // first contact (lastValid): there it keeps the heap smaller but costs
    // more than it saves on bugtrap and the maze.
    if (A.triangle >= 0 && !options.first_contact && A.radius > pb.radius) {
      return triangleObbCastInterval(a.triangle(A.triangle), pb.obb, u, lim, slack, &lo, &hi) ? lo : kInf;
    }
    // The face axes only: on the scenes of the planning benchmark the edge
    // axes cost more than the node pairs they prune.
    if (!castInterval<false>(A.obb, pb.obb, u, lim, slack, false, &lo, &hi)) return kInf;
    return lo;
  };
  // Nearest first (a heap on the bounds) for the first contact. Without
  // first_contact any contact ends the search and a free sweep visits every
  // pair whose volumes meet in any order, so the pairs go on a stack (depth
  // first): no heap work, and a leaf is reached after a few steps. On the
  // mesh configs' translating checkMotion (mddual_bench_planning --mdd-only
  // --cpu) the stack takes up to 28% less time than the heap
  // (docs/results/tuning.md).
  const bool depth_first = !options.first_contact;
  using Entry = Scratch::Entry;
  const auto later = [](const Entry& x, const Entry& y) { return x.bound > y.bound; };
  std::vector<Entry>& heap = s->heap;  // a stack when depth_first
  heap.clear();
  const auto enqueue = [&](const Entry& e) {
    heap.push_back(e);
    if (!depth_first) std::push_heap(heap.begin(), heap.end(), later);
  };
  const auto push = [&](int na, int nb) {
    const double lb = bound(na, nb);
    if (lb < best && lb <= max_distance) enqueue(Entry{lb, na, nb, false});
  };
  push(a.root(), b.root());
  while (!heap.empty()) {
    if (!depth_first) std::pop_heap(heap.begin(), heap.end(), later);
    Entry e = heap.back();
    heap.pop_back();
    // Nearest first, every remaining pair is bounded below by e.bound: none
    // comes before the best contact (or, with a tolerance, before it less
    // stop_within). Depth first, best is +infinity until the contact that
    // ends the search, so this never fires.
    if (e.bound >= best - options.stop_within) {
      hit.lower_bound = std::min(best, e.bound);
      break;
    }
    const Bvh::Node& A = a.node(e.a);
    const Bvh::Node& B = b.node(e.b);
    if (A.isLeaf() && B.isLeaf()) {
      ++local.leaf_pairs;
      const double lim = limit();
      const double d = leaf(a.leafPiece(e.a), b.leafPiece(e.b), lim);
      if (d <= lim && d < best) {
        best = d;
        hit.distance = d;
        hit.piece_a = a.leafPiece(e.a);
        hit.piece_b = b.leafPiece(e.b);
        if (!options.first_contact) break;
      }
      continue;
    }
    if (hulls && !e.hull_done && A.hull >= 0 && B.hull >= 0) {
      // Raise the bound to the hulls' toi (computed only for pairs that reach
      // the top of the heap), then put the pair back.
      e.hull_done = true;
      ++local.hull_queries;
      DirectionalInput in;
      in.a = a.hull(e.a);
      in.b = b.hull(e.b);
      in.X_WB = X_AB;
      in.s_W = u;
      in.max_distance = limit();
      try {
        const ToiResult r = toi(in);
        if (r.status == ToiStatus::kNever) continue;
        if (r.status == ToiStatus::kHit) {
          const double scale =
              std::max({in.a->radius(), in.b->radius(), (X_AB * in.b->centroid() - in.a->centroid()).norm()});
          e.bound = std::max(e.bound, r.toi - kHullBoundSlackRel * scale);
        }
      } catch (const Error&) {
        // Keep the boxes' bound.
      }
      if (e.bound < best) enqueue(e);
      continue;
    }
    if (descendA(A, B)) {
      push(A.left, e.b);
      push(A.right, e.b);
    } else {
      push(e.a, B.left);
      push(e.a, B.right);
    }
  }
  hit.lower_bound = std::min(hit.lower_bound, hit.distance);  // the distance itself unless stopped early
  if (stats) {
    stats->node_pairs += local.node_pairs;
    stats->leaf_pairs += local.leaf_pairs;
    stats->hull_queries += local.hull_queries;
  }
  return hit;
}

}  // namespace mddual
