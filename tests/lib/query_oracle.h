// Test oracle: runs mdd(), toi() and intersect() against the brute-force
// reference on one posed pair and many directions, checks the contact point
// and normal geometrically, and prints any failing query as a JSON line of the
// CLI's input format (paste it into a test or into `mddual query`).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "mddual/brute_force.h"
#include "mddual/query.h"
#include "pair.h"

namespace mddual::testing {

/// Counts of what a family's sample contained (for non-degeneracy guards).
struct Tally {
  int queries = 0;
  int separated = 0;
  int touching = 0;
  int penetrating = 0;
  int no_contact = 0;
  int planar = 0;
  int intersecting = 0;
  int scenes = 0;
  void add(ContactStatus s) {
    ++queries;
    if (s == ContactStatus::kSeparated) ++separated;
    if (s == ContactStatus::kTouching) ++touching;
    if (s == ContactStatus::kPenetrating) ++penetrating;
    if (s == ContactStatus::kNoContact) ++no_contact;
  }
  double fraction(int n) const { return queries > 0 ? static_cast<double>(n) / queries : 0.0; }
};

/// Largest violation of the half-spaces bounding polytope P posed at X by the
/// point p (the face planes, and for a flat polygon also its edge planes):
/// <= 0 inside, about the distance outside.
inline double outsideOf(const ConvexPolytope& p, const Eigen::Isometry3d& X, const Eigen::Vector3d& p_W) {
  const Eigen::Vector3d q = X.inverse() * p_W;
  double worst = -std::numeric_limits<double>::infinity();
  for (int f = 0; f < p.numFaces(); ++f) worst = std::max(worst, p.faceNormal(f).dot(q) - p.faceOffset(f));
  if (p.isFlat()) {
    for (int e = 0; e < p.numEdges(); ++e) {
      const Eigen::Vector3d m = p.edge(e).wedge_left_P.normalized();
      worst = std::max(worst, m.dot(q - p.vertex(p.edge(e).v0)));
    }
  }
  return worst;
}

/// Round-off of world coordinates of the pair: 16 ulps of the largest
/// coordinate magnitude of their local origins plus their size.
inline double worldRoundoff(const ConvexPolytope& a, const Eigen::Isometry3d& X_WA, const ConvexPolytope& b,
                            const Eigen::Isometry3d& X_WB) {
  const double magnitude = std::max((X_WA * a.p_PL()).cwiseAbs().maxCoeff(), (X_WB * b.p_PL()).cwiseAbs().maxCoeff()) +
                           a.radius() + b.radius() + (X_WA * a.p_PL() - X_WB * b.p_PL()).norm();
  return 16.0 * std::numeric_limits<double>::epsilon() * magnitude;
}

/// The body-frame points and both poses, to full precision: a failure can
/// depend on the frames' round-off, which the world points of toJsonLine
/// lose (a repro from them may pass).
inline std::string describeFrames(const ConvexPolytope& a, const Eigen::Isometry3d& X_WA, const ConvexPolytope& b,
                                  const Eigen::Isometry3d& X_WB) {
  std::ostringstream o;
  o.precision(17);
  const auto body = [&](const char* name, const ConvexPolytope& p, const Eigen::Isometry3d& X) {
    o << "\n  " << name << " body points:";
    for (int v = 0; v < p.numVertices(); ++v) {
      o << (v > 0 ? ", " : " ") << "{" << p.vertex(v).x() << ", " << p.vertex(v).y() << ", " << p.vertex(v).z() << "}";
    }
    o << "\n  X_W" << name << " rows (R | p):";
    for (int r = 0; r < 3; ++r) {
      o << (r > 0 ? "; " : " ") << X.matrix()(r, 0) << ", " << X.matrix()(r, 1) << ", " << X.matrix()(r, 2) << " | "
        << X.matrix()(r, 3);
    }
  };
  body("A", a, X_WA);
  body("B", b, X_WB);
  return o.str();
}

class QueryOracle {
 public:
  /// rel_tol: agreement required, relative to the pair's length scale.
  explicit QueryOracle(double rel_tol = 1e-9) : rel_tol_(rel_tol) {}

  /// Checks every direction on the pair; failures are reported through gtest
  /// with the query printed. Returns the number of failing queries.
  int check(const ConvexPolytope& a, const Eigen::Isometry3d& X_WA, const ConvexPolytope& b,
            const Eigen::Isometry3d& X_WB, const std::vector<Eigen::Vector3d>& directions, Tally* tally) {
    const BruteForce brute(&a, X_WA, &b, X_WB);
    const detail::PairGeometry pair(&a, X_WA, &b, X_WB, "test");
    const double scale = pair.scale();
    const double tol = rel_tol_ * scale;
    // Checks on world-frame points (contact points, separating planes) cannot
    // be finer than the coordinates' own round-off: about 1e-16 of their
    // magnitude, which dominates far from the origin (1e-8 of the size at an
    // offset of 1e8 sizes). Distances and t values keep `tol`.
    const double world_tol = tol + worldRoundoff(a, X_WA, b, X_WB);
    ++tally->scenes;
    int failures = 0;
    // Intersection test (direction-free).
    {
      IntersectInput in{&a, X_WA, &b, X_WB};
      const IntersectResult fast = intersect(in);
      const IntersectResult ref = brute.intersect();
      if (fast.intersecting) ++tally->intersecting;
      bool ok = fast.status == ref.status || touchingEither(fast.status, ref.status, brute, world_tol);
      if (ok && fast.status == IntersectStatus::kSeparated)
        ok = separates(a, X_WA, b, X_WB, fast.separating_normal_W, world_tol);
      if (!ok) {
        ++failures;
        ADD_FAILURE() << "intersect: fast " << toString(fast.status) << " vs brute " << toString(ref.status)
                      << "\n  query: " << toJsonLine(DirectionalInput{&a, X_WA, &b, X_WB, Eigen::Vector3d::UnitX()})
                      << describeFrames(a, X_WA, b, X_WB);
      }
    }
    for (const Eigen::Vector3d& s : directions) {
      DirectionalInput in{&a, X_WA, &b, X_WB, s};
      const MddResult fast = mdd(in);
      const MddResult ref = brute.mdd(s);
      const ToiResult fast_toi = toi(in);
      const ToiResult ref_toi = brute.toi(s);
      // The yes/no form within a finite max_distance: the same decision as the
      // exact answer, and an early hit's bound is not below the true contact.
      DirectionalInput yes_no = in;
      yes_no.exact_toi = false;
      yes_no.max_distance = std::isfinite(ref_toi.toi) ? 1.5 * ref_toi.toi + tol : scale;
      const ToiResult decided = toi(yes_no);
      const bool hit_within = ref_toi.status != ToiStatus::kNever && ref_toi.toi <= yes_no.max_distance;
      tally->add(ref.status);
      if (fast.stats.planar) ++tally->planar;
      std::ostringstream why;
      if (!agree(fast, ref, brute, s, tol, world_tol, &why) || !agreeToi(fast_toi, ref_toi, ref, tol, &why) ||
          !contactValid(a, X_WA, b, X_WB, s, fast, world_tol, &why) ||
          (fast_toi.status == ToiStatus::kHit &&
           !contactValid(a, X_WA, b, X_WB, s, asMdd(fast_toi), world_tol, &why)) ||
          !decisionAgrees(decided, hit_within, ref_toi, ref, yes_no.max_distance, tol, &why)) {
        ++failures;
        ADD_FAILURE() << why.str() << "\n  fast: " << describe(fast) << "\n  brute: " << describe(ref)
                      << "\n  toi fast " << toString(fast_toi.status) << " " << fast_toi.toi << ", brute "
                      << toString(ref_toi.status) << " " << ref_toi.toi << "\n  query: " << toJsonLine(in)
                      << describeFrames(a, X_WA, b, X_WB);
      }
    }
    return failures;
  }

 private:
  static std::string describe(const MddResult& r) {
    std::ostringstream o;
    o.precision(17);
    o << toString(r.status) << " mdd=" << r.distance << " t=[" << r.t_lo << ", " << r.t_hi << "] n=["
      << r.contact.normal_W.transpose() << "] p=[" << r.contact.point_W.transpose() << "]";
    return o.str();
  }

  static MddResult asMdd(const ToiResult& t) {
    MddResult r;
    r.status = ContactStatus::kSeparated;
    r.distance = t.toi;
    r.contact = t.contact;
    return r;
  }

  /// Signed distance of the point p_W to M = A - B, from the brute force's
  /// explicit M (outsideOf: exact inside, a lower bound on the distance
  /// outside that is 0 on the boundary).
  static double outsideOfM(const BruteForce& brute, const Eigen::Vector3d& p_W) {
    return outsideOf(brute.minkowskiDifference().polytope, Eigen::Isometry3d::Identity(), p_W);
  }

  /// A status mismatch is acceptable only across the touching boundary: one
  /// side says touching and the origin is within the touch tolerance (the
  /// brute force's, plus the check's own `tol`) of M's boundary, as the
  /// brute force's explicit M measures it.
  static bool touchingEither(IntersectStatus x, IntersectStatus y, const BruteForce& brute, double tol) {
    if (x != IntersectStatus::kTouching && y != IntersectStatus::kTouching) return false;
    return std::abs(outsideOfM(brute, Eigen::Vector3d::Zero())) <= brute.touchTolerance() + tol;
  }

  static bool near(double x, double y, double tol) {
    if (std::isnan(x) || std::isnan(y)) return std::isnan(x) && std::isnan(y);
    if (std::isinf(x) || std::isinf(y)) return x == y;
    return std::abs(x - y) <= tol;
  }

  static bool agree(const MddResult& fast, const MddResult& ref, const BruteForce& brute, const Eigen::Vector3d& s,
                    double tol, double world_tol, std::ostringstream* why) {
    if (fast.status != ref.status) {
      const bool contact_f = fast.status != ContactStatus::kNoContact;
      const bool contact_r = ref.status != ContactStatus::kNoContact;
      // Across the touching boundary: both distances within tol of zero.
      const bool across_touch = contact_f && contact_r &&
                                (fast.status == ContactStatus::kTouching || ref.status == ContactStatus::kTouching) &&
                                std::abs(fast.distance) <= tol && std::abs(ref.distance) <= tol;
      // A line grazing M within tolerance: the brute force's contact is of
      // (near) zero length, or the fast query's contact point t u lies within
      // tolerance of the brute force's M (a line that passes that close).
      const bool grazing =
          contact_f != contact_r &&
          (contact_f ? std::isfinite(fast.contact.t) &&
                           outsideOfM(brute, fast.contact.t * s.normalized()) <= brute.touchTolerance() + world_tol
                     : ref.t_hi - ref.t_lo <= tol);
      if (!across_touch && !grazing) {
        *why << "status differs";
        return false;
      }
      return true;
    }
    if (!near(fast.distance, ref.distance, tol)) {
      *why << "mdd differs by " << fast.distance - ref.distance;
      return false;
    }
    // Both ends are required, except the far end of a separated answer
    // (not computed: NaN, or when given, equal to the brute force's).
    const bool separated = fast.status == ContactStatus::kSeparated;
    const bool forward = ref.t_lo > 0.0;
    const auto end_agrees = [&](double f, double r, bool far_end) {
      return (separated && far_end && std::isnan(f)) || near(f, r, tol);
    };
    if (!end_agrees(fast.t_lo, ref.t_lo, !forward)) {
      *why << "t_lo differs by " << fast.t_lo - ref.t_lo;
      return false;
    }
    if (!end_agrees(fast.t_hi, ref.t_hi, forward)) {
      *why << "t_hi differs by " << fast.t_hi - ref.t_hi;
      return false;
    }
    return true;
  }

  static bool agreeToi(const ToiResult& fast, const ToiResult& ref, const MddResult& ref_mdd, double tol,
                       std::ostringstream* why) {
    if (fast.status == ref.status && near(fast.toi, ref.toi, tol)) return true;
    // Near-touching and grazing placements may fall on either side.
    const bool touching_side =
        ref_mdd.status == ContactStatus::kTouching || (!std::isnan(ref_mdd.t_lo) && std::abs(ref_mdd.t_lo) <= tol) ||
        (!std::isnan(ref_mdd.t_hi) && std::abs(ref_mdd.t_hi) <= tol) || (ref_mdd.t_hi - ref_mdd.t_lo <= tol);
    const bool small = (fast.toi <= tol || std::isinf(fast.toi)) && (ref.toi <= tol || std::isinf(ref.toi));
    if (touching_side && (small || near(fast.toi, ref.toi, tol))) return true;
    *why << "toi differs: fast " << toString(fast.status) << " " << fast.toi << " vs brute " << toString(ref.status)
         << " " << ref.toi;
    return false;
  }

  /// The yes/no form of toi(): hit or not within max_distance as the exact
  /// answer says (the touching side excepted), and an early hit's bound is at
  /// least the true first contact.
  static bool decisionAgrees(const ToiResult& decided, bool hit_within, const ToiResult& ref, const MddResult& ref_mdd,
                             double max_distance, double tol, std::ostringstream* why) {
    const bool says_hit = decided.status != ToiStatus::kNever;
    const bool near_boundary = std::abs(ref.toi - max_distance) <= tol || ref_mdd.status == ContactStatus::kTouching ||
                               (ref_mdd.t_hi - ref_mdd.t_lo <= tol) ||
                               (!std::isnan(ref_mdd.t_hi) && std::abs(ref_mdd.t_hi) <= tol);
    if (says_hit != hit_within && !near_boundary) {
      *why << "yes/no toi disagrees: " << toString(decided.status) << " within " << max_distance;
      return false;
    }
    if (!decided.toi_exact && says_hit && hit_within && decided.toi < ref.toi - tol) {
      *why << "early hit bound " << decided.toi << " below the first contact " << ref.toi;
      return false;
    }
    if (!decided.toi_exact && !(decided.toi <= max_distance)) {
      *why << "early hit bound beyond max_distance";
      return false;
    }
    return true;
  }

  /// The contact point lies on A and on B translated by t u, and the normal
  /// separates A from the translated B (every vertex on its side).
  static bool contactValid(const ConvexPolytope& a, const Eigen::Isometry3d& X_WA, const ConvexPolytope& b,
                           const Eigen::Isometry3d& X_WB, const Eigen::Vector3d& s, const MddResult& r, double tol,
                           std::ostringstream* why) {
    if (r.status == ContactStatus::kNoContact) return true;
    const Contact& c = r.contact;
    Eigen::Isometry3d X_WBt = X_WB;
    X_WBt.pretranslate(c.t * s.normalized());
    const Eigen::Vector3d& p = c.point_W;
    const Eigen::Vector3d& n = c.normal_W;
    if (!p.allFinite() || !n.allFinite() || std::abs(n.norm() - 1.0) > 1e-9) {
      *why << "contact point or normal not finite / not unit";
      return false;
    }
    if (outsideOf(a, X_WA, p) > tol || outsideOf(b, X_WBt, p) > tol) {
      *why << "contact point off the bodies by " << std::max(outsideOf(a, X_WA, p), outsideOf(b, X_WBt, p));
      return false;
    }
    for (const Eigen::Vector3d& v : a.vertices()) {
      if (n.dot(X_WA * v - p) > tol) {
        *why << "normal does not support A (by " << n.dot(X_WA * v - p) << ")";
        return false;
      }
    }
    for (const Eigen::Vector3d& v : b.vertices()) {
      if (n.dot(X_WBt * v - p) < -tol) {
        *why << "normal does not support B (by " << -n.dot(X_WBt * v - p) << ")";
        return false;
      }
    }
    return true;
  }

  static bool separates(const ConvexPolytope& a, const Eigen::Isometry3d& X_WA, const ConvexPolytope& b,
                        const Eigen::Isometry3d& X_WB, const Eigen::Vector3d& n, double tol) {
    double max_a = -std::numeric_limits<double>::infinity();
    double min_b = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& v : a.vertices()) max_a = std::max(max_a, n.dot(X_WA * v));
    for (const Eigen::Vector3d& v : b.vertices()) min_b = std::min(min_b, n.dot(X_WB * v));
    return n.allFinite() && max_a <= min_b + tol;
  }

  double rel_tol_;
};

}  // namespace mddual::testing
