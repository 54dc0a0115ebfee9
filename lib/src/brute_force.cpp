// Brute force: M = hull{a_i - b_j} built explicitly, then the line clipped
// with every face plane (docs/algorithms.md section 1, "Ground truth").
//
// A flat M (parallel flat A and B) has only the two faces +-N; its polygon's
// edges are added as side planes (the edge's outward in-plane normal), so the
// clipping is right there too. A face plane parallel to the line (|n.u| at
// most kParallelSin) does not bound t: the line is outside (h < -tol: no
// contact), inside, or lying in the plane (|h| <= tol: grazing, which rules
// out penetration).
#include "mddual/brute_force.h"

#include <array>
#include <cmath>
#include <map>

#include "constants.h"
#include "mddual/defaults.h"
#include "mddual/error.h"
#include "pair.h"

namespace mddual {
// The two types BruteForce::Line (a class with linkage) holds are in a named
// namespace; the functions stay file-local.
namespace brute_force_detail {

/// A half-space n . x <= h bounding M, with the vertices of M on its boundary.
struct Constraint {
  Eigen::Vector3d n;
  double h = 0.0;
  std::vector<int> vertices;  // a face loop, or an edge's two ends (flat M)
};

struct ClippedLine {
  bool hit = false;
  bool grazing = false;  // the line lies in a supporting plane of M
  double t_lo = -detail::kInf;
  double t_hi = detail::kInf;
  const Constraint* lo = nullptr;
  const Constraint* hi = nullptr;
};

}  // namespace brute_force_detail

namespace {

using brute_force_detail::ClippedLine;
using brute_force_detail::Constraint;
using detail::kInf;
using detail::kNaN;

std::vector<Constraint> constraintsOf(const ConvexPolytope& m) {
  std::vector<Constraint> out;
  for (int f = 0; f < m.numFaces(); ++f) {
    const IndexRange loop = m.faceVertices(f);
    out.push_back({m.faceNormal(f), m.faceOffset(f), std::vector<int>(loop.begin(), loop.end())});
  }
  if (m.isFlat()) {
    for (int e = 0; e < m.numEdges(); ++e) {
      const ConvexPolytope::Edge& edge = m.edge(e);
      const Eigen::Vector3d n = edge.wedge_left_P.normalized();  // outward in-plane normal
      out.push_back({n, std::max(n.dot(m.vertex(edge.v0)), n.dot(m.vertex(edge.v1))), {edge.v0, edge.v1}});
    }
  }
  return out;
}

ClippedLine clip(const std::vector<Constraint>& constraints, const Eigen::Vector3d& u, double tol) {
  ClippedLine out;
  for (const Constraint& c : constraints) {
    const double a = c.n.dot(u);
    if (std::abs(a) <= defaults::kParallelSin) {
      if (c.h < -tol) return out;
      if (c.h <= tol) out.grazing = true;
      continue;
    }
    const double t = c.h / a;
    if (a > 0.0 && t < out.t_hi) {
      out.t_hi = t;
      out.hi = &c;
    } else if (a < 0.0 && t > out.t_lo) {
      out.t_lo = t;
      out.lo = &c;
    }
  }
  if (out.lo == nullptr || out.hi == nullptr || out.t_lo > out.t_hi + tol) return out;
  if (out.t_lo > out.t_hi) out.t_lo = out.t_hi = 0.5 * (out.t_lo + out.t_hi);
  out.hit = true;
  return out;
}

/// A point a of A with x = a - b, b in B, x on constraint c of M: x is
/// written in the vertices of M on c (fan triangles of a face, or a segment),
/// and a is the same combination of the A vertices behind them.
Eigen::Vector3d decompose(const MinkowskiDifference& md, const std::vector<Eigen::Vector3d>& a_W, const Constraint& c,
                          const Eigen::Vector3d& x) {
  const ConvexPolytope& m = md.polytope;
  auto a_of = [&](int k) { return a_W[md.source[k].first]; };
  const std::vector<int>& vs = c.vertices;
  if (vs.size() == 2) {
    const Eigen::Vector3d d = m.vertex(vs[1]) - m.vertex(vs[0]);
    const double lambda = std::clamp((x - m.vertex(vs[0])).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (1.0 - lambda) * a_of(vs[0]) + lambda * a_of(vs[1]);
  }
  double best_score = -kInf;
  Eigen::Vector3d best = a_of(vs[0]);
  const Eigen::Vector3d& p0 = m.vertex(vs[0]);
  for (size_t k = 1; k + 1 < vs.size(); ++k) {
    const Eigen::Vector3d e1 = m.vertex(vs[k]) - p0;
    const Eigen::Vector3d e2 = m.vertex(vs[k + 1]) - p0;
    const Eigen::Vector3d r = x - p0;
    const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
    const double denom = d11 * d22 - d12 * d12;
    if (!(denom > 0.0)) continue;
    const double l1 = (d22 * r.dot(e1) - d12 * r.dot(e2)) / denom;
    const double l2 = (d11 * r.dot(e2) - d12 * r.dot(e1)) / denom;
    const double score = std::min({1.0 - l1 - l2, l1, l2});
    if (score > best_score) {
      best_score = score;
      const double c1 = std::clamp(l1, 0.0, 1.0);
      const double c2 = std::clamp(l2, 0.0, 1.0 - c1);
      best = (1.0 - c1 - c2) * a_of(vs[0]) + c1 * a_of(vs[k]) + c2 * a_of(vs[k + 1]);
    }
  }
  return best;
}

}  // namespace

MinkowskiDifference MinkowskiDifference::build(const ConvexPolytope& a, const Eigen::Isometry3d& X_WA,
                                               const ConvexPolytope& b, const Eigen::Isometry3d& X_WB) {
  // d_W = a_W - b_W for every pair of vertices, formed from the local frames
  // (polytope.h) so that bodies far from the origin keep their precision:
  //   d_W = R_WA a_L - R_WB b_L + (p_WLa - p_WLb),
  // the last term (two nearly equal large vectors) in long double.
  using Vec3L = Eigen::Matrix<long double, 3, 1>;
  const Vec3L p_WLa =
      X_WA.translation().cast<long double>() + X_WA.linear().cast<long double>() * a.p_PL().cast<long double>();
  const Vec3L p_WLb =
      X_WB.translation().cast<long double>() + X_WB.linear().cast<long double>() * b.p_PL().cast<long double>();
  const Eigen::Vector3d p_LbLa_W = (p_WLa - p_WLb).cast<double>();
  std::vector<Eigen::Vector3d> points;
  std::map<std::array<double, 3>, std::pair<int, int>> source_of;
  for (int i = 0; i < a.numVertices(); ++i) {
    const Eigen::Vector3d p = X_WA.linear() * a.localVertex(i) + p_LbLa_W;
    for (int j = 0; j < b.numVertices(); ++j) {
      const Eigen::Vector3d d = p - X_WB.linear() * b.localVertex(j);
      points.push_back(d);
      source_of.emplace(std::array<double, 3>{d.x(), d.y(), d.z()}, std::make_pair(i, j));
    }
  }
  MinkowskiDifference md;
  md.polytope = ConvexPolytope::fromPoints(points);
  for (const Eigen::Vector3d& v : md.polytope.vertices()) {
    md.source.push_back(source_of.at({v.x(), v.y(), v.z()}));
  }
  return md;
}

struct BruteForce::Line {
  ClippedLine line;
  bool penetrable = false;  // M has an interior the line can cross
  Contact lo;
  Contact hi;
};

BruteForce::BruteForce(const ConvexPolytope* a, const Eigen::Isometry3d& X_WA, const ConvexPolytope* b,
                       const Eigen::Isometry3d& X_WB) {
  const detail::PairGeometry pair(a, X_WA, b, X_WB, "brute force");
  tol_ = pair.touchTolerance();
  md_ = MinkowskiDifference::build(*a, X_WA, *b, X_WB);
  for (const Eigen::Vector3d& v : a->vertices()) a_W_.push_back(X_WA * v);
}

BruteForce::Line BruteForce::solve(const Eigen::Vector3d& s_W, const char* query) const {
  const Eigen::Vector3d u_W = detail::unitDirection(s_W, query);
  const std::vector<Constraint> constraints = constraintsOf(md_.polytope);
  Line out;
  out.line = clip(constraints, u_W, tol_);
  out.penetrable = !md_.polytope.isFlat() && !out.line.grazing;
  if (!out.line.hit) return out;
  auto contact = [&](double t, const Constraint& c) {
    Contact k;
    k.t = t;
    k.normal_W = c.n;
    k.point_W = decompose(md_, a_W_, c, t * u_W);
    return k;
  };
  out.lo = contact(out.line.t_lo, *out.line.lo);
  out.hi = contact(out.line.t_hi, *out.line.hi);
  return out;
}

MddResult BruteForce::mdd(const Eigen::Vector3d& s_W) const {
  const Line ans = solve(s_W, "mdd (brute force)");
  MddResult r;
  if (!ans.line.hit) return r;
  r.t_lo = ans.line.t_lo;
  r.t_hi = ans.line.t_hi;
  if (r.t_lo > tol_) {
    r.status = ContactStatus::kSeparated;
    r.distance = r.t_lo;
    r.contact = ans.lo;
  } else if (r.t_hi < -tol_) {
    r.status = ContactStatus::kSeparated;
    r.distance = -r.t_hi;
    r.contact = ans.hi;
  } else if (!ans.penetrable || r.t_lo >= -tol_ || r.t_hi <= tol_) {
    r.status = ContactStatus::kTouching;
    r.distance = 0.0;
    r.contact = std::abs(r.t_lo) <= std::abs(r.t_hi) ? ans.lo : ans.hi;
  } else {
    r.status = ContactStatus::kPenetrating;
    const bool backward = -r.t_lo < r.t_hi;
    r.distance = backward ? r.t_lo : -r.t_hi;
    r.contact = backward ? ans.lo : ans.hi;
  }
  return r;
}

ToiResult BruteForce::toi(const Eigen::Vector3d& s_W, double max_distance) const {
  detail::checkMaxDistance(max_distance, "toi (brute force)");
  const Line ans = solve(s_W, "toi (brute force)");
  ToiResult r;
  if (!ans.line.hit || ans.line.t_hi < -tol_) return r;
  if (ans.line.t_lo <= tol_) {
    r.status = ToiStatus::kInContact;
    r.toi = 0.0;
  } else if (ans.line.t_lo <= max_distance) {
    r.status = ToiStatus::kHit;
    r.toi = ans.line.t_lo;
    r.contact = ans.lo;
  }
  return r;
}

IntersectResult BruteForce::intersect() const {
  // Signed distance of the origin to M's boundary planes: max over planes of -h.
  double outside = -kInf;
  Eigen::Vector3d normal = Eigen::Vector3d::Constant(kNaN);
  for (const Constraint& c : constraintsOf(md_.polytope)) {
    if (-c.h > outside) {
      outside = -c.h;
      normal = c.n;
    }
  }
  IntersectResult r;
  if (outside > tol_) {
    r.status = IntersectStatus::kSeparated;
    r.separating_normal_W = normal;
  } else {
    r.intersecting = true;
    r.status = outside >= -tol_ || md_.polytope.isFlat() ? IntersectStatus::kTouching : IntersectStatus::kPenetrating;
  }
  return r;
}

MddResult bruteForceMdd(const DirectionalInput& in) {
  return BruteForce(in.a, in.X_WA, in.b, in.X_WB).mdd(in.s_W);
}

ToiResult bruteForceToi(const DirectionalInput& in) {
  return BruteForce(in.a, in.X_WA, in.b, in.X_WB).toi(in.s_W, in.max_distance);
}

IntersectResult bruteForceIntersect(const IntersectInput& in) {
  return BruteForce(in.a, in.X_WA, in.b, in.X_WB).intersect();
}

}  // namespace mddual
