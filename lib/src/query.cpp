// Public entry points mdd(), toi() and intersect(): MDD-DUAL's steps as
// numbered phases (setup, quick rejection, planar cases, centre of duality,
// ray searches, result).
#include "mddual/query.h"

#include <cmath>
#include <optional>

#include "centre.h"
#include "constants.h"
#include "mddual/error.h"
#include "overlap.h"
#include "pair.h"
#include "planar.h"
#include "search.h"

namespace mddual {

const char* toString(ContactStatus status) {
  switch (status) {
    case ContactStatus::kSeparated: return "separated";
    case ContactStatus::kTouching: return "touching";
    case ContactStatus::kPenetrating: return "penetrating";
    case ContactStatus::kNoContact: return "no_contact";
  }
  return "?";
}

const char* toString(ToiStatus status) {
  switch (status) {
    case ToiStatus::kHit: return "hit";
    case ToiStatus::kInContact: return "in_contact";
    case ToiStatus::kNever: return "never";
  }
  return "?";
}

const char* toString(IntersectStatus status) {
  switch (status) {
    case IntersectStatus::kSeparated: return "separated";
    case IntersectStatus::kTouching: return "touching";
    case IntersectStatus::kPenetrating: return "penetrating";
  }
  return "?";
}

const char* toString(FeatureType type) {
  switch (type) {
    case FeatureType::kNone: return "none";
    case FeatureType::kVertex: return "vertex";
    case FeatureType::kEdge: return "edge";
    case FeatureType::kFace: return "face";
  }
  return "?";
}

namespace {

using detail::Centre;
using detail::PairGeometry;
using detail::PlanarDifference;
using detail::PlanarSlice;
using detail::RayExit;
using detail::RayQuery;

using detail::kInf;
using detail::kNaN;

/// The line's interval in M with a contact at each end that was computed.
struct LineInterval {
  bool hit = false;
  /// False when the line only meets M's boundary (grazing, or a flat M): the
  /// origin on the interval is then touching, never penetrating.
  bool crosses_interior = true;
  /// Planar paths: a unit normal (world) of the supporting plane holding the
  /// whole interval, valid at every point of it.
  Eigen::Vector3d plane_normal_W = Eigen::Vector3d::Zero();
  std::optional<Contact> lo;  ///< contact at t_lo (entry)
  std::optional<Contact> hi;  ///< contact at t_hi (exit)
};

/// Contact from the exit face of a ray search along the line (t = h / n.u).
Contact contactFromExit(const PairGeometry& pair, const RayExit& exit, const Eigen::Vector3d& u_A) {
  Contact c;
  c.t = exit.h / exit.n_A.dot(u_A);
  const Eigen::Vector3d a = detail::contactPointOnA(pair, exit, c.t * u_A);
  c.normal_W = pair.vectorToWorld(exit.n_A);
  c.point_W = pair.pointToWorld(a);
  switch (exit.face.kind) {
    case FaceOfM::Kind::kFV:
      c.feature_a = {FeatureType::kFace, exit.face.a};
      c.feature_b = {FeatureType::kVertex, exit.vb};
      break;
    case FaceOfM::Kind::kVF:
      c.feature_a = {FeatureType::kVertex, exit.va};
      c.feature_b = {FeatureType::kFace, exit.face.b};
      break;
    case FaceOfM::Kind::kEE:
      c.feature_a = {FeatureType::kEdge, exit.face.a};
      c.feature_b = {FeatureType::kEdge, exit.face.b};
      break;
    case FaceOfM::Kind::kNone: break;
  }
  return c;
}

/// Vertices of a polytope (all, or a tie set), in A's frame.
std::vector<Eigen::Vector3d> pointsInA(const PairGeometry& pair, bool of_b, const std::vector<int>* ids) {
  const ConvexPolytope& p = of_b ? pair.b() : pair.a();
  std::vector<Eigen::Vector3d> out;
  const int n = ids != nullptr ? static_cast<int>(ids->size()) : p.numVertices();
  for (int k = 0; k < n; ++k) {
    const int v = ids != nullptr ? (*ids)[k] : k;
    out.push_back(of_b ? pair.bVertex(v) : p.localVertex(v));
  }
  return out;
}

/// Contacts at both ends of a planar slice {s u} of M, and the plane's normal.
/// The contact normals are `normal_A` when given, else the slice's edge normals.
LineInterval intervalFromSlice(const PairGeometry& pair, const PlanarSlice& slice, const Eigen::Vector3d& plane_A,
                               const Eigen::Vector3d* normal_A) {
  LineInterval out;
  out.hit = slice.hit;
  out.crosses_interior = false;
  out.plane_normal_W = pair.vectorToWorld(plane_A);
  if (!slice.hit) return out;
  Contact lo;
  lo.t = slice.s_lo;
  lo.point_W = pair.pointToWorld(slice.a_lo);
  lo.normal_W = pair.vectorToWorld(normal_A != nullptr ? *normal_A : slice.normal_lo);
  Contact hi;
  hi.t = slice.s_hi;
  hi.point_W = pair.pointToWorld(slice.a_hi);
  hi.normal_W = pair.vectorToWorld(normal_A != nullptr ? *normal_A : slice.normal_hi);
  out.lo = lo;
  out.hi = hi;
  return out;
}

/// The line lies in the supporting plane of M with normal w (grazing): its
/// interval is the slice of that face of M (paper IV-A, case 2).
LineInterval grazingInterval(const PairGeometry& pair, const Centre& centre, const Eigen::Vector3d& u_A,
                             SearchStats* stats) {
  std::vector<int> ties_a;
  std::vector<int> ties_b;
  pair.a().supportTies(centre.w_A, centre.va, pair.tieTolerance(), &ties_a);
  pair.b().supportTies(-pair.aToB(centre.w_A), centre.vb, pair.tieTolerance(), &ties_b);
  const PlanarDifference face(pointsInA(pair, false, &ties_a), pointsInA(pair, true, &ties_b), centre.w_A);
  stats->planar = true;
  return intervalFromSlice(pair, face.slice(Eigen::Vector3d::Zero(), u_A, pair.touchTolerance()), centre.w_A,
                           &centre.w_A);
}

/// A and B are parallel flat polygons: M is a polygon in the plane nu . x = k.
LineInterval flatInterval(const PairGeometry& pair, const Eigen::Vector3d& u_A, SearchStats* stats) {
  stats->planar = true;
  const Eigen::Vector3d& nu = pair.flatNormal();
  const PlanarDifference m(pointsInA(pair, false, nullptr), pointsInA(pair, true, nullptr), nu);
  const double k = nu.dot(pair.a().localVertex(0) - pair.bVertex(0));
  const double tol = pair.touchTolerance();
  const double along = nu.dot(u_A);
  if (std::abs(along) <= defaults::kParallelSin) {
    if (std::abs(k) > tol) return {};
    return intervalFromSlice(pair, m.slice(Eigen::Vector3d::Zero(), u_A, tol), nu, nullptr);
  }
  // The line crosses M's plane once, at t*: a contact iff that point is in M.
  const double t_star = k / along;
  const Eigen::Vector3d x = t_star * u_A;
  const Eigen::Vector3d d =
      nu.cross(std::abs(nu.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()).normalized();
  const PlanarSlice slice = m.slice(x, d, tol);
  if (!slice.hit || slice.s_lo > tol || slice.s_hi < -tol) return {};
  const double lambda = slice.s_hi > slice.s_lo ? std::clamp(-slice.s_lo / (slice.s_hi - slice.s_lo), 0.0, 1.0) : 0.0;
  Contact c;
  c.t = t_star;
  c.point_W = pair.pointToWorld(slice.a_lo + lambda * (slice.a_hi - slice.a_lo));
  LineInterval out;
  out.hit = true;
  out.crosses_interior = false;
  out.lo = c;
  out.hi = c;
  out.lo->normal_W = pair.vectorToWorld(along > 0.0 ? Eigen::Vector3d(-nu) : nu);  // entry: n . u <= 0
  out.hi->normal_W = pair.vectorToWorld(along > 0.0 ? nu : Eigen::Vector3d(-nu));
  return out;
}

/// Signed MDD and status from the computed ends (docs/algorithms.md section 1).
void classify(const LineInterval& line, double tol, MddResult* r) {
  if (!line.hit) return;                        // kNoContact, fields stay NaN
  r->t_lo = line.lo ? line.lo->t + 0.0 : kNaN;  // + 0.0: no negative zero
  r->t_hi = line.hi ? line.hi->t + 0.0 : kNaN;
  if (line.lo && r->t_lo > tol) {
    r->status = ContactStatus::kSeparated;
    r->distance = r->t_lo;
    r->contact = *line.lo;
  } else if (line.hi && r->t_hi < -tol) {
    r->status = ContactStatus::kSeparated;
    r->distance = -r->t_hi;
    r->contact = *line.hi;
  } else if (!line.crosses_interior || r->t_lo >= -tol || r->t_hi <= tol) {
    r->status = ContactStatus::kTouching;
    r->distance = 0.0;
    if (line.lo && std::abs(r->t_lo) <= tol) {
      r->contact = *line.lo;
    } else if (line.hi && std::abs(r->t_hi) <= tol) {
      r->contact = *line.hi;
    } else {
      // The origin inside a planar interval: interpolate the contact at t = 0.
      const double lambda = -r->t_lo / (r->t_hi - r->t_lo);
      r->contact = *line.lo;
      r->contact.t = 0.0;
      r->contact.point_W = (1.0 - lambda) * line.lo->point_W + lambda * line.hi->point_W;
      r->contact.normal_W = line.plane_normal_W;
      r->contact.feature_a = r->contact.feature_b = Feature{};
    }
  } else {
    r->status = ContactStatus::kPenetrating;
    const bool backward = -r->t_lo < r->t_hi;
    r->distance = backward ? r->t_lo : -r->t_hi;
    r->contact = backward ? *line.lo : *line.hi;
  }
}

/// Re-throws an internal failure with the query attached, ready to paste.
[[noreturn]] void rethrowWithQuery(const NumericalError& e, const ConvexPolytope* a, const Eigen::Isometry3d& X_WA,
                                   const ConvexPolytope* b, const Eigen::Isometry3d& X_WB, const Eigen::Vector3d& s_W) {
  throw NumericalError(std::string(e.what()) + "\n  query: " + toJsonLine(DirectionalInput{a, X_WA, b, X_WB, s_W}));
}

bool lineMissesBall(const PairGeometry& pair, const Eigen::Vector3d& u_A) {
  const Eigen::Vector3d& g = pair.interiorPoint();
  return (g - g.dot(u_A) * u_A).norm() > pair.radiusM() + pair.touchTolerance();
}

}  // namespace

MddResult mdd(const DirectionalInput& input, WarmStart* warm) {
  // 1. Setup: B's pose in A's frame, the unit direction, tolerances.
  const PairGeometry pair(input.a, input.X_WA, input.b, input.X_WB, "mdd");
  const Eigen::Vector3d u_A = pair.vectorToA(detail::unitDirection(input.s_W, "mdd"));
  const double tol = pair.touchTolerance();
  MddResult r;
  try {
    // 2. Quick rejection: the line misses the ball around M.
    if (lineMissesBall(pair, u_A)) return r;
    // 3. Planar cases: parallel flat polygons, or a line grazing M.
    if (pair.flatM()) {
      classify(flatInterval(pair, u_A, &r.stats), tol, &r);
      return r;
    }
    const Centre centre = detail::findCentre(pair, u_A, warm, &r.stats);
    if (centre.kind == Centre::Kind::kNoContact) return r;
    if (centre.kind == Centre::Kind::kGrazing) {
      classify(grazingInterval(pair, centre, u_A, &r.stats), tol, &r);
      return r;
    }
    // 4. Ray searches from the centre: toward -u gives t_lo, toward +u t_hi.
    //    The near end decides separation; the far end is needed only when the
    //    origin is in M (paper: d_max, then d_min when they overlap).
    LineInterval line;
    line.hit = true;
    auto search = [&](bool forward) {
      RayQuery q;
      q.c_A = centre.c_A;
      q.w_A = forward ? Eigen::Vector3d(-u_A) : u_A;
      if (warm != nullptr) q.warm = forward ? warm->forward : warm->backward;
      const RayExit exit = detail::searchRay(pair, q, &r.stats);
      if (warm != nullptr) (forward ? warm->forward : warm->backward) = exit.face;
      (forward ? line.lo : line.hi) = contactFromExit(pair, exit, u_A);
    };
    if (centre.tau >= 0.0) {
      search(true);
      if (line.lo->t <= tol) search(false);
    } else {
      search(false);
      if (line.hi->t >= -tol) search(true);
    }
    // 5. Result.
    classify(line, tol, &r);
  } catch (const NumericalError& e) {
    rethrowWithQuery(e, input.a, input.X_WA, input.b, input.X_WB, input.s_W);
  }
  return r;
}

ToiResult toi(const DirectionalInput& input, WarmStart* warm) {
  // 1. Setup.
  const PairGeometry pair(input.a, input.X_WA, input.b, input.X_WB, "toi");
  const Eigen::Vector3d u_A = pair.vectorToA(detail::unitDirection(input.s_W, "toi"));
  detail::checkMaxDistance(input.max_distance, "toi");
  const double tol = pair.touchTolerance();
  const double max_distance = input.max_distance;
  ToiResult r;
  auto fromInterval = [&](const LineInterval& line) {
    if (!line.hit || line.hi->t < -tol) return;  // never
    if (line.lo->t <= tol) {
      r.status = ToiStatus::kInContact;
      r.toi = 0.0;
    } else if (line.lo->t <= max_distance) {
      r.status = ToiStatus::kHit;
      r.toi = line.lo->t;
      r.contact = *line.lo;
    }
  };
  try {
    // 2. Quick rejection.
    if (lineMissesBall(pair, u_A)) return r;
    // 3. Planar cases.
    if (pair.flatM()) {
      fromInterval(flatInterval(pair, u_A, &r.stats));
      return r;
    }
    const Centre centre = detail::findCentre(pair, u_A, warm, &r.stats);
    if (centre.kind == Centre::Kind::kNoContact) return r;
    if (centre.kind == Centre::Kind::kGrazing) {
      fromInterval(grazingInterval(pair, centre, u_A, &r.stats));
      return r;
    }
    // 4. One ray search. Centre ahead of the origin (tau > 0): the entry t_lo
    //    is the answer, and any face farther than max_distance proves kNever
    //    (t_lo >= tau - 1/phi for every face). Centre behind (tau < 0): only
    //    the sign of the exit t_hi matters (t_hi <= tau + 1/phi).
    if (centre.tau == 0.0) {  // the origin is the centre, inside M
      r.status = ToiStatus::kInContact;
      r.toi = 0.0;
      return r;
    }
    // A yes/no check can stop here: the centre is a point of M on the line,
    // so a centre within [0, max_distance] proves a contact on the way.
    if (!input.exact_toi && centre.tau >= 0.0 && centre.tau <= max_distance) {
      r.status = ToiStatus::kHit;
      r.toi = centre.tau + 0.0;
      r.toi_exact = false;
      return r;
    }
    // A portal refinement from the centre toward the origin (along the line)
    // settles most overlapping starts in a few supports: a tetrahedron of M
    // holding the origin means toi = 0; a separating plane with the centre
    // behind the origin means the line leaves M before reaching it (never).
    const bool forward = centre.tau > 0.0;
    const detail::OverlapTest quick = detail::portalOverlapTest(pair, centre.c_A, 0.0, warm, &r.stats);
    if (quick.kind == detail::OverlapTest::Kind::kOverlap) {
      r.status = ToiStatus::kInContact;
      r.toi = 0.0;
      return r;
    }
    if (quick.kind == detail::OverlapTest::Kind::kSeparated && !forward) return r;
    RayQuery q;
    q.c_A = centre.c_A;
    q.w_A = forward ? Eigen::Vector3d(-u_A) : u_A;
    if (warm != nullptr) q.warm = forward ? warm->forward : warm->backward;
    if (forward && centre.tau > max_distance) q.phi_stop = 1.0 / (centre.tau - max_distance);
    if (!forward && -centre.tau - tol > 0.0) q.phi_stop = 1.0 / (-centre.tau - tol);
    const RayExit exit = detail::searchRay(pair, q, &r.stats);
    if (warm != nullptr) (forward ? warm->forward : warm->backward) = exit.face;
    if (exit.stopped) return r;  // beyond max_distance, or behind: never
    // 5. Result.
    const Contact c = contactFromExit(pair, exit, u_A);
    if (!forward) {
      if (c.t >= -tol) {
        r.status = ToiStatus::kInContact;
        r.toi = 0.0;
      }
    } else if (c.t <= tol) {
      r.status = ToiStatus::kInContact;
      r.toi = 0.0;
    } else if (c.t <= max_distance) {
      r.status = ToiStatus::kHit;
      r.toi = c.t;
      r.contact = c;
    }
  } catch (const NumericalError& e) {
    rethrowWithQuery(e, input.a, input.X_WA, input.b, input.X_WB, input.s_W);
  }
  return r;
}

IntersectResult intersect(const IntersectInput& input, WarmStart* warm) {
  // 1. Setup.
  const PairGeometry pair(input.a, input.X_WA, input.b, input.X_WB, "intersect");
  const double tol = pair.touchTolerance();
  const Eigen::Vector3d& g = pair.interiorPoint();
  const double g_norm = g.norm();
  IntersectResult r;
  auto separated = [&](const Eigen::Vector3d& n_A) {
    r.status = IntersectStatus::kSeparated;
    r.intersecting = false;
    r.separating_normal_W = pair.vectorToWorld(n_A.normalized());
    return r;
  };
  auto overlapping = [&](IntersectStatus status) {
    r.status = status;
    r.intersecting = true;
    return r;
  };
  try {
    // 2. Quick rejection: M lies in the ball of radius rA + rB around g.
    if (g_norm > pair.radiusM() + tol) return separated(-g / g_norm);
    // 3. Flat M: the origin must lie in M's plane and inside its polygon.
    if (pair.flatM()) {
      r.stats.planar = true;
      const Eigen::Vector3d& nu = pair.flatNormal();
      const double k = nu.dot(pair.a().localVertex(0) - pair.bVertex(0));
      if (std::abs(k) > tol) return separated(k < 0.0 ? nu : Eigen::Vector3d(-nu));
      const PlanarDifference m(pointsInA(pair, false, nullptr), pointsInA(pair, true, nullptr), nu);
      Eigen::Vector3d edge_normal;
      const double outside = m.outsideDistance(Eigen::Vector3d::Zero(), &edge_normal);
      if (outside > tol) return separated(edge_normal);
      return overlapping(IntersectStatus::kTouching);
    }
    // 4. Two triangles (the pieces of a mesh): the separating-axis test on
    //    their 11 axes settles most separated pairs for a fraction of the
    //    search's cost (the pairs a hierarchy reports whose boxes overlap).
    if (pair.a().numVertices() == 3 && pair.b().numVertices() == 3) {
      const detail::OverlapTest sat = detail::trianglesSeparated(pair, tol);
      if (sat.kind == detail::OverlapTest::Kind::kSeparated) return separated(sat.n_A);
    }
    // 5. The centre of duality is g itself (paper V: any interior point of M
    //    other than the origin); g = 0 means the origin is interior. Before the
    //    search, three supports of M often settle it: a tetrahedron holding
    //    the origin deeper than tol proves penetration, a negative support
    //    value proves separation.
    if (g_norm == 0.0) return overlapping(IntersectStatus::kPenetrating);
    const detail::OverlapTest quick = detail::portalOverlapTest(pair, g, tol, warm, &r.stats);
    if (quick.kind == detail::OverlapTest::Kind::kSeparated) return separated(quick.n_A);
    if (quick.kind == detail::OverlapTest::Kind::kOverlap) return overlapping(IntersectStatus::kPenetrating);
    // 6. Ray search from g through the origin, stopping at the first face of M
    //    with offset h < -tol: its plane separates the origin from M.
    RayQuery q;
    q.c_A = g;
    q.w_A = -g / g_norm;
    q.h_stop = -tol;
    if (warm != nullptr) q.warm = warm->separating;
    const RayExit exit = detail::searchRay(pair, q, &r.stats);
    if (warm != nullptr) warm->separating = exit.face;
    // 7. Result: the face's plane n . x = h separates when h < 0; the origin is
    //    on the boundary of M when the exit face passes within tol of it.
    if (exit.stopped) return separated(exit.n_A);
    if (exit.min_h <= tol) return overlapping(IntersectStatus::kTouching);
    return overlapping(IntersectStatus::kPenetrating);
  } catch (const NumericalError& e) {
    rethrowWithQuery(e, input.a, input.X_WA, input.b, input.X_WB, Eigen::Vector3d::Zero());
  }
}

}  // namespace mddual
