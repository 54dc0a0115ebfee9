#include "scene.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mddual/brute_force.h"
#include "mddual/constants.h"
#include "mddual/defaults.h"
#include "mddual/generators.h"
#include "mddual/query.h"

namespace mddual::bench {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Scene scale for "relative" errors: every polytope lies within radius 5.
constexpr double kScale = 10.0;
/// Agreement required between two exact answers (relative to kScale).
constexpr double kExactRel = 1e-9;
/// Below this (absolute, = 1e-6 * kScale) a contact at t = 0 is a tolerance call.
constexpr double kAmbiguous = 1e-6 * kScale;

/// A face plane n . x <= h of M0.
struct Plane {
  Eigen::Vector3d n;
  double h = 0.0;
};

std::vector<Plane> planesOf(const ConvexPolytope& m) {
  std::vector<Plane> out;
  for (int f = 0; f < m.numFaces(); ++f) out.push_back({m.faceNormal(f), m.faceOffset(f)});
  return out;
}

/// Exact depth of x inside M0 (negative outside, where it is a lower bound on
/// minus the distance): min over faces of h - n . x. Concave in x.
double depth(const std::vector<Plane>& planes, const Eigen::Vector3d& x) {
  double d = kInf;
  for (const Plane& p : planes) d = std::min(d, p.h - p.n.dot(x));
  return d;
}

/// The library's touch tolerance for a pair of poses (pair.cpp): kTouchRel
/// times max(radius A, radius B, distance between the vertex centroids).
double touchTolerance(const ConvexPolytope& a, const Eigen::Isometry3d& X_WA, const ConvexPolytope& b,
                      const Eigen::Isometry3d& X_WB) {
  const double g = (X_WA * a.centroid() - X_WB * b.centroid()).norm();
  return defaults::kTouchRel * std::max({a.radius(), b.radius(), g});
}

/// Brute-force answer for B translated by v (M = M0 - v), clipping exactly as
/// lib/src/brute_force.cpp does (same tolerances, same tie rules).
Reference clipReference(const std::vector<Plane>& planes, const Eigen::Vector3d& v, const Eigen::Vector3d& u,
                        double tol) {
  Reference r;
  double t_lo = -kInf;
  double t_hi = kInf;
  bool grazing = false;
  for (const Plane& p : planes) {
    const double a = p.n.dot(u);
    const double h = p.h - p.n.dot(v);
    if (std::abs(a) <= defaults::kParallelSin) {
      if (h < -tol) {
        r.ambiguous = h >= -kAmbiguous;
        return r;
      }
      if (h <= tol) grazing = true;
      continue;
    }
    const double t = h / a;
    if (a > 0.0) {
      t_hi = std::min(t_hi, t);
    } else {
      t_lo = std::max(t_lo, t);
    }
  }
  if (!(t_lo > -kInf) || !(t_hi < kInf)) return r;
  if (t_lo > t_hi + tol) {
    r.ambiguous = t_lo - t_hi <= kAmbiguous;
    return r;
  }
  if (t_lo > t_hi) t_lo = t_hi = 0.5 * (t_lo + t_hi);
  r.hit = true;
  r.t_lo = t_lo;
  r.t_hi = t_hi;
  if (t_lo > tol) {
    r.mdd = t_lo;
  } else if (t_hi < -tol) {
    r.mdd = -t_hi;
  } else if (grazing || t_lo >= -tol || t_hi <= tol) {
    r.mdd = 0.0;
  } else {
    r.mdd = -t_lo < t_hi ? t_lo : -t_hi;
  }
  if (t_hi >= -tol) {
    r.in_contact = t_lo <= tol;
    r.toi = r.in_contact ? 0.0 : t_lo;
  }
  r.overlapping = !grazing && t_lo < -tol && t_hi > tol;
  r.ambiguous = std::abs(t_hi) <= kAmbiguous;
  return r;
}

Eigen::Isometry3d pose(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}

/// Classifies the faces of M0 by the vertex pairs behind their vertices.
void classifyFaces(const MinkowskiDifference& md, OrientationInfo* info) {
  const ConvexPolytope& m = md.polytope;
  info->faces = m.numFaces();
  for (int f = 0; f < m.numFaces(); ++f) {
    const IndexRange loop = m.faceVertices(f);
    bool one_a = true;
    bool one_b = true;
    const std::pair<int, int> first = md.source[loop[0]];
    for (int k : loop) {
      one_a = one_a && md.source[k].first == first.first;
      one_b = one_b && md.source[k].second == first.second;
    }
    if (one_a) {
      ++info->vf_faces;
    } else if (one_b) {
      ++info->fv_faces;
    } else {
      ++info->ee_faces;
    }
  }
}

/// Translation v of B with signed distance `delta` between A and B + v: a ray
/// from the interior point c of M0 along w leaves M0 at q on face f; outside
/// (delta >= 0) v = q + delta n_f, whose closest point in M0 is q; inside,
/// bisection on [q, c] for depth(v) = -delta (depth is concave, 0 at q and
/// above -delta at c, so the crossing is unique).
Eigen::Vector3d placeB(const std::vector<Plane>& planes, const Eigen::Vector3d& c, const Eigen::Vector3d& w,
                       double delta, Eigen::Vector3d* normal) {
  double t_exit = kInf;
  for (const Plane& p : planes) {
    const double a = p.n.dot(w);
    if (a <= 0.0) continue;
    const double t = (p.h - p.n.dot(c)) / a;
    if (t < t_exit) {
      t_exit = t;
      *normal = p.n;
    }
  }
  const Eigen::Vector3d q = c + t_exit * w;
  if (delta >= 0.0) return q + delta * *normal;
  double lo = 0.0;  // fraction of the way from q to c: depth(lo) < -delta
  double hi = 1.0;  // depth(hi) >= -delta
  for (int it = 0; it < 200 && hi - lo > 1e-16; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (depth(planes, q + mid * (c - q)) < -delta) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return q + hi * (c - q);
}

Eigen::Vector3d turn(const Eigen::Vector3d& u, double degrees, generators::Rng& rng) {
  Eigen::Vector3d axis = generators::randomUnitVector(rng).cross(u);
  while (axis.norm() < 1e-6) axis = generators::randomUnitVector(rng).cross(u);
  return (Eigen::AngleAxisd(degrees * kPi / 180.0, axis.normalized()) * u).normalized();
}

std::string fmt(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

/// Self-check of one placement against the library's brute force: the sign
/// of the distance (bruteForceIntersect) and, separated, the distance itself
/// (bruteForceMdd along -n: B moves straight back to the contact point).
void checkPlacement(const PairScene& s, const Query& q, double delta, const Eigen::Vector3d& n, SceneChecks* checks) {
  ++checks->placements_checked;
  const IntersectResult ir = bruteForceIntersect({&s.a, q.X_WA, &s.b, q.X_WB});
  const IntersectStatus want = delta < 0.0    ? IntersectStatus::kPenetrating
                               : delta == 0.0 ? IntersectStatus::kTouching
                                              : IntersectStatus::kSeparated;
  bool ok = ir.status == want;
  double got = delta;
  if (delta > 0.0) {
    DirectionalInput in{&s.a, q.X_WA, &s.b, q.X_WB, -n};
    got = bruteForceMdd(in).distance;
    ok = ok && std::abs(got - delta) <= kExactRel * kScale;
  }
  if (!ok) {
    ++checks->placements_failed;
    checks->messages.push_back(s.spec.name() + ": placement delta=" + fmt(delta) + " gives " + toString(ir.status) +
                               ", distance along -n " + fmt(got) + "; query " + describeQuery(s, q));
  }
}

/// Self-check of the own clipping against bruteForceMdd / bruteForceToi.
void checkReference(const PairScene& s, const Query& q, const Reference& r, SceneChecks* checks) {
  ++checks->references_checked;
  const DirectionalInput in{&s.a, q.X_WA, &s.b, q.X_WB, q.s_W};
  const MddResult m = bruteForceMdd(in);
  const ToiResult t = bruteForceToi(in);
  auto same = [](double x, double y) {
    return (std::isnan(x) && std::isnan(y)) || x == y || std::abs(x - y) <= kExactRel * kScale;
  };
  const bool ok = (m.status != ContactStatus::kNoContact) == r.hit && same(m.distance, r.mdd) && same(m.t_lo, r.t_lo) &&
                  same(m.t_hi, r.t_hi) && same(t.toi, r.toi);
  if (!ok) {
    ++checks->references_failed;
    checks->messages.push_back(s.spec.name() + ": reference mismatch: brute force mdd " + fmt(m.distance) + " toi " +
                               fmt(t.toi) + ", own clipping mdd " + fmt(r.mdd) + " toi " + fmt(r.toi) + "; query " +
                               describeQuery(s, q));
  }
}

}  // namespace

std::vector<PairSpec> paperPairs() {
  return {{"P1", "P2"}, {"P1", "P3"}, {"P4", "P5"}, {"P4", "P6"}, {"P1", "P1"},
          {"P2", "P2"}, {"P3", "P3"}, {"P4", "P4"}, {"P5", "P5"}, {"P6", "P6"}};
}

PairScene buildScene(const PairSpec& spec, const Protocol& protocol, int pair_index) {
  PairScene s;
  s.spec = spec;
  s.a = ConvexPolytope::fromPoints(generators::paperPolytope(spec.a));
  s.b = ConvexPolytope::fromPoints(generators::paperPolytope(spec.b));
  s.protocol = protocol;
  const int P = protocol.placements;
  const int D = protocol.directions;
  for (int k = 0; k < P; ++k) {
    const double f = P > 1 ? static_cast<double>(k) / (P - 1) : 0.5;
    double delta = protocol.min_delta + f * (protocol.max_delta - protocol.min_delta);
    if (std::abs(delta) < 1e-12) delta = 0.0;  // the touching placement is exactly 0
    s.deltas.push_back(delta);
  }
  std::seed_seq seq{static_cast<std::uint32_t>(protocol.seed), static_cast<std::uint32_t>(protocol.seed >> 32),
                    static_cast<std::uint32_t>(pair_index)};
  generators::Rng rng(seq);
  for (int o = 0; o < protocol.orientations; ++o) {
    OrientationInfo info;
    info.R_A = generators::randomRotation(rng);
    info.R_B = generators::randomRotation(rng);
    const Eigen::Isometry3d X_WA = pose(info.R_A, Eigen::Vector3d::Zero());
    const MinkowskiDifference md = MinkowskiDifference::build(s.a, X_WA, s.b, pose(info.R_B, Eigen::Vector3d::Zero()));
    classifyFaces(md, &info);
    const std::vector<Plane> planes = planesOf(md.polytope);
    const Eigen::Vector3d c = md.polytope.centroid();
    info.centre_depth = depth(planes, c);
    s.checks.centre_depth_min = std::min(s.checks.centre_depth_min, info.centre_depth);
    if (info.centre_depth <= -protocol.min_delta) {
      s.checks.messages.push_back(s.spec.name() + ": orientation " + std::to_string(o) + ": centroid depth " +
                                  fmt(info.centre_depth) + " is not deeper than " + fmt(-protocol.min_delta) +
                                  " (the deepest placements are clamped)");
    }
    s.orientations.push_back(info);
    for (int k = 0; k < P; ++k) {
      Eigen::Vector3d n;
      const Eigen::Vector3d v = placeB(planes, c, generators::randomUnitVector(rng), s.deltas[k], &n);
      Query base;
      base.X_WA = X_WA;
      base.X_WB = pose(info.R_B, v);
      base.orientation = o;
      base.placement = k;
      auto add = [&](const Query& q, std::vector<Query>* qs, std::vector<Reference>* refs) {
        const double tol = touchTolerance(s.a, q.X_WA, s.b, q.X_WB);
        if (refs != nullptr) refs->push_back(clipReference(planes, q.X_WB.translation(), q.s_W, tol));
        qs->push_back(q);
      };
      for (int d = 0; d < D; ++d) {
        Query q = base;
        q.s_W = generators::randomUnitVector(rng);
        add(q, &s.cold, &s.cold_ref);
      }
      // Warm sequence: primer, then D coherent steps (see Protocol).
      Query q = base;
      q.s_W = generators::randomUnitVector(rng);
      add(q, &s.primers, nullptr);
      for (int d = 0; d < D; ++d) {
        q.X_WB.translation() += protocol.warm_step * generators::randomUnitVector(rng);
        q.s_W = turn(q.s_W, protocol.warm_turn_deg, rng);
        add(q, &s.warm, &s.warm_ref);
      }
      if (protocol.verify && o == 0) checkPlacement(s, base, s.deltas[k], n, &s.checks);
      if (protocol.verify && D > 0 && (o == 0 || k == o % P)) {
        const size_t i = s.cold.size() - static_cast<size_t>(D);
        checkReference(s, s.cold[i], s.cold_ref[i], &s.checks);
      }
    }
  }
  return s;
}

std::string describeQuery(const PairScene& scene, const Query& q) {
  return toJsonLine(DirectionalInput{&scene.a, q.X_WA, &scene.b, q.X_WB, q.s_W});
}

}  // namespace mddual::bench
