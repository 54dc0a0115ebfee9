// Public entry points of the penetration-depth module (penetration.h):
// penetrationDepth(), polyhedralPenetrationDepth() and width() as numbered
// phases (setup, overlap test, closest facet by the chosen method, result),
// the brute-force references, and PolyhedralMetric.
#include "mddual/penetration.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mddual/brute_force.h"
#include "mddual/defaults.h"
#include "mddual/error.h"
#include "pair.h"
#include "penetration_internal.h"

namespace mddual {

const char* toString(PenetrationMethod method) {
  switch (method) {
    case PenetrationMethod::kExact: return "exact";
    case PenetrationMethod::kShallow: return "shallow";
    case PenetrationMethod::kApprox: return "approx";
    case PenetrationMethod::kBruteForce: return "brute";
  }
  return "?";
}

const char* toString(PenetrationStatus status) {
  switch (status) {
    case PenetrationStatus::kSeparated: return "separated";
    case PenetrationStatus::kTouching: return "touching";
    case PenetrationStatus::kPenetrating: return "penetrating";
  }
  return "?";
}

namespace {

using detail::PairGeometry;
using detail::PdPlane;

/// The delta a method runs with: the input's, or the method's default when 0;
/// 0 for the methods without one. A delta other than 0 must be in range for
/// every method (a NaN or negative one given to kExact was ignored silently).
double methodDelta(PenetrationMethod method, double delta, const char* what) {
  if (delta != 0.0) detail::checkDelta(delta, what);
  if (method != PenetrationMethod::kApprox && method != PenetrationMethod::kShallow) return 0.0;
  if (delta == 0.0) return method == PenetrationMethod::kApprox ? defaults::kApproxPdDelta : defaults::kShallowPdDelta;
  return delta;
}

void checkMethod(PenetrationMethod method, const char* what) {
  switch (method) {
    case PenetrationMethod::kExact:
    case PenetrationMethod::kShallow:
    case PenetrationMethod::kApprox:
    case PenetrationMethod::kBruteForce: return;
  }
  throw InvalidInputError(std::string(what) + ": unknown method");
}

PenetrationStatus fromIntersect(IntersectStatus s) {
  switch (s) {
    case IntersectStatus::kSeparated: return PenetrationStatus::kSeparated;
    case IntersectStatus::kTouching: return PenetrationStatus::kTouching;
    case IntersectStatus::kPenetrating: return PenetrationStatus::kPenetrating;
  }
  return PenetrationStatus::kSeparated;
}

/// The features of A and B spanning a facet of M (penetration.h).
void featuresOf(const FaceOfM& face, Feature* fa, Feature* fb) {
  switch (face.kind) {
    case FaceOfM::Kind::kFV:
      *fa = {FeatureType::kFace, face.a};
      *fb = {FeatureType::kVertex, face.b};
      break;
    case FaceOfM::Kind::kVF:
      *fa = {FeatureType::kVertex, face.a};
      *fb = {FeatureType::kFace, face.b};
      break;
    case FaceOfM::Kind::kEE:
      *fa = {FeatureType::kEdge, face.a};
      *fb = {FeatureType::kEdge, face.b};
      break;
    case FaceOfM::Kind::kNone: break;
  }
}

/// The closest facet of M by a fast method; the origin is inside M.
PdPlane closestFacet(const PairGeometry& pair, PenetrationMethod method, double delta, PenetrationStats* stats) {
  switch (method) {
    case PenetrationMethod::kShallow: return detail::shallowClosestFacet(pair, delta, stats);
    case PenetrationMethod::kApprox: return detail::approxClosestFacet(pair, delta, stats).best;
    default: return detail::exactClosestFacet(pair, stats);
  }
}

/// Whether the plane n . x = h of M (A's frame) supports M: h_A(n) +
/// h_-B(n) = h within the touch tolerance.
bool supportsM(const PairGeometry& pair, const PdPlane& p, PenetrationStats* stats) {
  SearchStats s;
  const detail::MPoint m = pair.supportM(p.n_A, p.va, p.vb, &s);
  stats->support_vertices += s.support_vertices;
  return p.n_A.dot(m.p_A) <= p.h + pair.touchTolerance();
}

/// The closest facet of the explicit M (world frame; features unknown).
PdPlane bruteClosestFacet(const BruteForce& brute) {
  const ConvexPolytope& m = brute.minkowskiDifference().polytope;
  PdPlane best;
  for (int f = 0; f < m.numFaces(); ++f) {
    if (m.faceOffset(f) < best.h) {
      best.h = m.faceOffset(f);
      best.n_A = m.faceNormal(f);
    }
  }
  return best;
}

[[noreturn]] void rethrowWithPair(const NumericalError& e, const ConvexPolytope* a, const Eigen::Isometry3d& X_WA,
                                  const ConvexPolytope* b, const Eigen::Isometry3d& X_WB) {
  throw NumericalError(std::string(e.what()) +
                       "\n  pair: " + toJsonLine(DirectionalInput{a, X_WA, b, X_WB, Eigen::Vector3d::UnitX()}));
}

/// Phase 4 of penetrationDepth(): status and fields from the closest facet
/// (normal_W already in the world frame).
void finish(const PdPlane& p, const Eigen::Vector3d& normal_W, double tol, PenetrationResult* r) {
  if (!(p.h > tol)) {  // the origin is within tol of the boundary of M
    r->status = PenetrationStatus::kTouching;
    return;
  }
  r->status = PenetrationStatus::kPenetrating;
  r->depth = p.h;
  r->normal_W = normal_W;
  r->translation_W = p.h * normal_W;
  r->facet = p.face;
  featuresOf(p.face, &r->feature_a, &r->feature_b);
}

}  // namespace

PenetrationResult penetrationDepth(const PenetrationInput& input) {
  // 1. Setup: the pair in A's frame, the method's delta.
  checkMethod(input.method, "penetrationDepth");
  const double delta = methodDelta(input.method, input.delta, "penetrationDepth");
  const PairGeometry pair(input.a, input.X_WA, input.b, input.X_WB, "penetrationDepth");
  PenetrationResult r;
  r.delta = delta;
  try {
    if (input.method == PenetrationMethod::kBruteForce) {
      // Reference: M built explicitly, min over its facets.
      const BruteForce brute(input.a, input.X_WA, input.b, input.X_WB);
      r.status = fromIntersect(brute.intersect().status);
      if (r.status != PenetrationStatus::kPenetrating) return r;
      const PdPlane p = bruteClosestFacet(brute);
      finish(p, p.n_A, pair.touchTolerance(), &r);
      return r;
    }
    // 2. Overlap test (core intersect(), paper section 2.2: "if A and B do
    //    not intersect, set PD = 0"). Parallel flat polygons (flat M) have no
    //    interior to overlap: PD = 0, touching when they meet.
    const IntersectResult overlap = intersect(IntersectInput{input.a, input.X_WA, input.b, input.X_WB});
    r.status = fromIntersect(overlap.status);
    if (r.status != PenetrationStatus::kPenetrating || pair.flatM()) return r;
    // 3. The closest facet of M by the chosen method (A's frame).
    const PdPlane p = closestFacet(pair, input.method, delta, &r.stats);
    // 4. Check (exact method): the plane must support M, h_M(n) = h. In exact
    //    arithmetic every enumerated plane does; an edge-edge normal computed
    //    from edges that are parallel to within ~1e-6 can be off by round-off
    //    / sine. Two support queries catch that; the explicit M then answers.
    if (input.method == PenetrationMethod::kExact && !supportsM(pair, p, &r.stats)) {
      ++r.stats.brute_fallbacks;
      const BruteForce brute(input.a, input.X_WA, input.b, input.X_WB);
      const PdPlane q = bruteClosestFacet(brute);
      finish(q, q.n_A, pair.touchTolerance(), &r);
      return r;
    }
    // 5. Result in the world frame.
    finish(p, pair.vectorToWorld(p.n_A), pair.touchTolerance(), &r);
  } catch (const NumericalError& e) {
    rethrowWithPair(e, input.a, input.X_WA, input.b, input.X_WB);
  }
  return r;
}

// ---- Polyhedral metric ------------------------------------------------------------

PolyhedralMetric PolyhedralMetric::fromPoints(const std::vector<Eigen::Vector3d>& points_W) {
  ConvexPolytope k = [&] {
    try {
      return ConvexPolytope::fromPoints(points_W);
    } catch (const InvalidInputError& e) {
      throw InvalidInputError(std::string("polyhedral metric: ") + e.what());
    }
  }();
  if (k.isFlat()) throw InvalidInputError("polyhedral metric: K is flat (its points are coplanar); it must be a solid");
  double radius = 0.0;
  for (const Eigen::Vector3d& v : k.vertices()) radius = std::max(radius, v.norm());
  const double tol = defaults::kMetricSymmetryRel * radius;
  for (int i = 0; i < k.numVertices(); ++i) {
    const Eigen::Vector3d& v = k.vertex(i);
    const bool mirrored = std::any_of(k.vertices().begin(), k.vertices().end(),
                                      [&](const Eigen::Vector3d& w) { return (v + w).norm() <= tol; });
    if (!mirrored) {
      std::ostringstream msg;
      msg.precision(17);
      msg << "polyhedral metric: K is not centrally symmetric about the origin: vertex [" << v.x() << ", " << v.y()
          << ", " << v.z() << "] has no opposite vertex";
      throw InvalidInputError(msg.str());
    }
  }
  return PolyhedralMetric(std::move(k));
}

double PolyhedralMetric::norm(const Eigen::Vector3d& t_W) const {
  // K = {x : n_f . x <= h_f}, the origin inside (h_f > 0): t is in lambda K
  // iff n_f . t <= lambda h_f for every facet.
  double lambda = 0.0;
  for (int f = 0; f < k_.numFaces(); ++f) lambda = std::max(lambda, k_.faceNormal(f).dot(t_W) / k_.faceOffset(f));
  return lambda;
}

PolyhedralResult polyhedralPenetrationDepth(const PolyhedralInput& input) {
  // 1. Setup.
  if (input.metric == nullptr) throw InvalidInputError("polyhedralPenetrationDepth: metric is null");
  if (input.method != PenetrationMethod::kExact && input.method != PenetrationMethod::kBruteForce) {
    throw InvalidInputError(std::string("polyhedralPenetrationDepth: method ") + toString(input.method) +
                            " is not available (exact or brute only)");
  }
  const PairGeometry pair(input.a, input.X_WA, input.b, input.X_WB, "polyhedralPenetrationDepth");
  const PolyhedralMetric& metric = *input.metric;
  PolyhedralResult r;
  auto penetrating = [&](double lambda, int k_vertex, const Eigen::Vector3d& normal_W, const FaceOfM& face) {
    r.status = PenetrationStatus::kPenetrating;
    r.depth = lambda;
    r.k_vertex = k_vertex;
    r.translation_W = lambda * metric.vertices()[static_cast<size_t>(k_vertex)];
    r.euclidean_length = r.translation_W.norm();
    r.normal_W = normal_W;
    r.facet = face;
    featuresOf(face, &r.feature_a, &r.feature_b);
  };
  try {
    if (input.method == PenetrationMethod::kBruteForce) {
      // Reference: min over the facets of M of h / h_K(n), with the vertex
      // of K attaining h_K(n) (docs/algorithms.md section 1, penetration.h).
      const BruteForce brute(input.a, input.X_WA, input.b, input.X_WB);
      r.status = fromIntersect(brute.intersect().status);
      if (r.status != PenetrationStatus::kPenetrating) return r;
      const ConvexPolytope& m = brute.minkowskiDifference().polytope;
      double best = std::numeric_limits<double>::infinity();
      int best_k = -1;
      Eigen::Vector3d best_n = Eigen::Vector3d::Zero();
      for (int f = 0; f < m.numFaces(); ++f) {
        const Eigen::Vector3d& n = m.faceNormal(f);
        int k = 0;
        for (int i = 1; i < static_cast<int>(metric.vertices().size()); ++i) {
          if (n.dot(metric.vertices()[static_cast<size_t>(i)]) > n.dot(metric.vertices()[static_cast<size_t>(k)]))
            k = i;
        }
        const double lambda = m.faceOffset(f) / n.dot(metric.vertices()[static_cast<size_t>(k)]);
        if (lambda < best) {
          best = lambda;
          best_k = k;
          best_n = n;
        }
      }
      penetrating(best, best_k, best_n, FaceOfM{});
      return r;
    }
    // 2. Overlap test.
    const IntersectResult overlap = intersect(IntersectInput{input.a, input.X_WA, input.b, input.X_WB});
    r.status = fromIntersect(overlap.status);
    if (r.status != PenetrationStatus::kPenetrating || pair.flatM()) return r;
    // 3. One ray shot per vertex of K (Corollary 3.5).
    const detail::MetricOutcome out = detail::metricClosestFacet(pair, metric, &r.stats);
    // 4. Result. The origin within tol of the boundary of M: touching.
    if (!(out.exit.h > pair.touchTolerance())) {
      r.status = PenetrationStatus::kTouching;
      return r;
    }
    penetrating(out.lambda, out.k_vertex, pair.vectorToWorld(out.exit.n_A), out.exit.face);
  } catch (const NumericalError& e) {
    rethrowWithPair(e, input.a, input.X_WA, input.b, input.X_WB);
  }
  return r;
}

// ---- Width ------------------------------------------------------------------------

WidthResult width(const WidthInput& input) {
  // 1. Setup: A against itself at the same pose (Proposition 2.1:
  //    width(A) = PD(A, A)); M = A - A is centrally symmetric about the
  //    origin, which is interior unless A is flat.
  checkMethod(input.method, "width");
  const double delta = methodDelta(input.method, input.delta, "width");
  const PairGeometry pair(input.a, input.X_WA, input.a, input.X_WA, "width");
  WidthResult r;
  r.delta = delta;
  // 2. A flat polygon lies in one plane: width 0 across it.
  if (input.a->isFlat()) {
    r.width = 0.0;
    r.direction_W = pair.vectorToWorld(input.a->faceNormal(0));
    return r;
  }
  try {
    // 3. The closest facet of M = A - A; its offset h_A(n) + h_A(-n) is
    //    A's extent along its normal n.
    PdPlane p;
    if (input.method == PenetrationMethod::kBruteForce) {
      const BruteForce brute(input.a, input.X_WA, input.a, input.X_WA);
      p = bruteClosestFacet(brute);
      p.n_A = pair.vectorToA(p.n_A);
    } else {
      p = closestFacet(pair, input.method, delta, &r.stats);
      // The same final check as penetrationDepth() step 4.
      if (input.method == PenetrationMethod::kExact && !supportsM(pair, p, &r.stats)) {
        ++r.stats.brute_fallbacks;
        const BruteForce brute(input.a, input.X_WA, input.a, input.X_WA);
        p = bruteClosestFacet(brute);
        p.n_A = pair.vectorToA(p.n_A);
      }
    }
    // 4. Result.
    r.width = p.h;
    r.direction_W = pair.vectorToWorld(p.n_A);
    r.facet = p.face;
    featuresOf(p.face, &r.feature_a, &r.feature_b);
  } catch (const NumericalError& e) {
    rethrowWithPair(e, input.a, input.X_WA, input.a, input.X_WA);
  }
  return r;
}

}  // namespace mddual
