// distance(): GJK on M = A - B in A's local frame with a certified stop, an
// exact polish from the feature pairs near the supporting planes when GJK
// stalls, and the exact penetration depth for overlapping pairs (see
// distance.h).
#include "mddual/distance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "constants.h"
#include "mddual/defaults.h"
#include "mddual/penetration.h"
#include "pair.h"

namespace mddual {

const char* toString(DistanceStatus status) {
  switch (status) {
    case DistanceStatus::kSeparated: return "separated";
    case DistanceStatus::kTouching: return "touching";
    case DistanceStatus::kPenetrating: return "penetrating";
  }
  return "unknown";
}

namespace detail {
namespace {

using detail::kNaN;

/// A point of M - o (o: the query point) with its vertices of A and B.
struct SimplexPoint {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();  ///< a - b - o, A's local frame
  int va = -1;
  int vb = -1;
};

/// A simplex of up to four points with the weights of its closest point.
struct Simplex {
  std::array<SimplexPoint, 4> pts;
  std::array<double, 4> w = {0.0, 0.0, 0.0, 0.0};
  int size = 0;

  Eigen::Vector3d closest() const {
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    for (int i = 0; i < size; ++i) v += w[static_cast<std::size_t>(i)] * pts[static_cast<std::size_t>(i)].p;
    return v;
  }
  bool contains(int va, int vb) const {
    for (int i = 0; i < size; ++i) {
      const SimplexPoint& q = pts[static_cast<std::size_t>(i)];
      if (q.va == va && q.vb == vb) return true;
    }
    return false;
  }
  /// Keeps the points listed in `keep` (indices into pts) with weights `ws`.
  void reduce(std::initializer_list<int> keep, std::initializer_list<double> ws) {
    std::array<SimplexPoint, 4> np;
    std::array<double, 4> nw = {0.0, 0.0, 0.0, 0.0};
    int n = 0;
    auto wi = ws.begin();
    for (int k : keep) {
      np[static_cast<std::size_t>(n)] = pts[static_cast<std::size_t>(k)];
      nw[static_cast<std::size_t>(n)] = *wi++;
      ++n;
    }
    pts = np;
    w = nw;
    size = n;
  }
};

/// Closest point to the origin of the segment p[i] p[j]: (weight of i, of j).
std::pair<double, double> segmentWeights(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  if (!(len2 > 0.0)) return {1.0, 0.0};
  const double t = std::clamp(-a.dot(ab) / len2, 0.0, 1.0);
  return {1.0 - t, t};
}

/// Closest point to the origin of triangle (a, b, c) by Voronoi regions:
/// returns the weights of a, b, c (some zero when the point is on an edge or
/// a vertex).
std::array<double, 3> triangleWeights(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a;
  const Eigen::Vector3d ac = c - a;
  const double d1 = -ab.dot(a);
  const double d2 = -ac.dot(a);
  if (d1 <= 0.0 && d2 <= 0.0) return {1.0, 0.0, 0.0};
  const double d3 = -ab.dot(b);
  const double d4 = -ac.dot(b);
  if (d3 >= 0.0 && d4 <= d3) return {0.0, 1.0, 0.0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double t = d1 / (d1 - d3);
    return {1.0 - t, t, 0.0};
  }
  const double d5 = -ab.dot(c);
  const double d6 = -ac.dot(c);
  if (d6 >= 0.0 && d5 <= d6) return {0.0, 0.0, 1.0};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double t = d2 / (d2 - d6);
    return {1.0 - t, 0.0, t};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0.0, 1.0 - t, t};
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) {
    // Degenerate (collinear) triangle: the best of its three edges.
    std::array<double, 3> best = {1.0, 0.0, 0.0};
    double best_d = a.squaredNorm();
    const std::array<const Eigen::Vector3d*, 3> p = {&a, &b, &c};
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      const auto [wi, wj] = segmentWeights(*p[static_cast<std::size_t>(i)], *p[static_cast<std::size_t>(j)]);
      const double d = (wi * *p[static_cast<std::size_t>(i)] + wj * *p[static_cast<std::size_t>(j)]).squaredNorm();
      if (d < best_d) {
        best_d = d;
        best = {0.0, 0.0, 0.0};
        best[static_cast<std::size_t>(i)] = wi;
        best[static_cast<std::size_t>(j)] = wj;
      }
    }
    return best;
  }
  return {va / sum, vb / sum, vc / sum};
}

/// Replaces the simplex by the smallest face holding its point closest to the
/// origin and sets the weights. Returns true when the origin lies inside a
/// tetrahedron (the weights are then its barycentric coordinates).
bool closestOnSimplex(Simplex* s) {
  auto P = [s](int i) -> const Eigen::Vector3d& { return s->pts[static_cast<std::size_t>(i)].p; };
  auto keepNonzero = [s](const std::array<int, 3>& idx, const std::array<double, 3>& w, int n) {
    std::array<SimplexPoint, 4> np;
    std::array<double, 4> nw = {0.0, 0.0, 0.0, 0.0};
    int k = 0;
    for (int i = 0; i < n; ++i) {
      if (w[static_cast<std::size_t>(i)] > 0.0) {
        np[static_cast<std::size_t>(k)] = s->pts[static_cast<std::size_t>(idx[static_cast<std::size_t>(i)])];
        nw[static_cast<std::size_t>(k)] = w[static_cast<std::size_t>(i)];
        ++k;
      }
    }
    if (k == 0) {  // all weights zero cannot happen (they sum to 1); keep the first
      np[0] = s->pts[static_cast<std::size_t>(idx[0])];
      nw[0] = 1.0;
      k = 1;
    }
    s->pts = np;
    s->w = nw;
    s->size = k;
  };
  switch (s->size) {
    case 1: s->w[0] = 1.0; return false;
    case 2: {
      const auto [w0, w1] = segmentWeights(P(0), P(1));
      keepNonzero({0, 1, 0}, {w0, w1, 0.0}, 2);
      return false;
    }
    case 3: {
      keepNonzero({0, 1, 2}, triangleWeights(P(0), P(1), P(2)), 3);
      return false;
    }
    default: break;
  }
  // Tetrahedron: the origin is inside iff it is on the inner side of all four
  // faces. Signed volumes give the barycentric coordinates of the origin.
  const Eigen::Vector3d& a = P(0);
  const Eigen::Vector3d& b = P(1);
  const Eigen::Vector3d& c = P(2);
  const Eigen::Vector3d& d = P(3);
  const double vol = (b - a).cross(c - a).dot(d - a);
  const std::array<double, 4> bary = {b.cross(c).dot(d) - 0.0, -a.cross(c).dot(d), a.cross(b).dot(d),
                                      -a.cross(b).dot(c)};
  // bary[i] / vol: weights of the origin (sum = 1 when vol != 0).
  const double scale3 = std::max({(b - a).norm(), (c - a).norm(), (d - a).norm()});
  const bool solid = std::abs(vol) > 1e-14 * scale3 * scale3 * scale3;
  if (solid) {
    bool inside = true;
    for (double x : bary) inside = inside && (x / vol >= 0.0);
    if (inside) {
      for (std::size_t i = 0; i < 4; ++i) s->w[i] = bary[i] / vol;
      return true;
    }
  }
  // Closest point on the faces (all of them when the tetrahedron is flat).
  static constexpr std::array<std::array<int, 3>, 4> kFaces = {{{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}};
  static constexpr std::array<int, 4> kOpposite = {3, 2, 1, 0};
  double best = std::numeric_limits<double>::infinity();
  std::array<int, 3> best_idx = kFaces[0];
  std::array<double, 3> best_w = {1.0, 0.0, 0.0};
  for (std::size_t f = 0; f < 4; ++f) {
    if (solid && bary[static_cast<std::size_t>(kOpposite[f])] / vol >= 0.0) continue;  // origin on the inner side
    const auto& idx = kFaces[f];
    const std::array<double, 3> w = triangleWeights(P(idx[0]), P(idx[1]), P(idx[2]));
    const double dist = (w[0] * P(idx[0]) + w[1] * P(idx[1]) + w[2] * P(idx[2])).squaredNorm();
    if (dist < best) {
      best = dist;
      best_idx = idx;
      best_w = w;
    }
  }
  keepNonzero(best_idx, best_w, 3);
  return false;
}

/// Outcome of one GJK run toward the point o (A's local frame).
struct GjkOutcome {
  bool contact = false;                           ///< o is in M or within the touch tolerance of it
  bool stalled = false;                           ///< stopped without closing the gap
  double upper = kNaN;                            ///< |closest point - o|
  double lower = 0.0;                             ///< certified lower bound on the distance
  Eigen::Vector3d a_A = Eigen::Vector3d::Zero();  ///< point of A (A's local frame)
  Eigen::Vector3d b_A = Eigen::Vector3d::Zero();  ///< point of B (A's local frame)
  Simplex simplex;
};

GjkOutcome runGjk(const PairGeometry& pair, const Eigen::Vector3d& o_A, const DistanceWarmStart* warm,
                  DistanceStats* stats, double enough = std::numeric_limits<double>::infinity(), double rel_gap = 0.0) {
  SearchStats search;
  GjkOutcome out;
  Simplex& s = out.simplex;
  auto point = [&](int va, int vb) {
    SimplexPoint q;
    q.va = va;
    q.vb = vb;
    q.p = pair.a().localVertex(va) - pair.bVertex(vb) - o_A;
    return q;
  };
  if (warm != nullptr) {
    for (int i = 0; i < std::min(warm->size, 4); ++i) {
      const int va = warm->a[i];
      const int vb = warm->b[i];
      if (va < 0 || vb < 0 || va >= pair.a().numVertices() || vb >= pair.b().numVertices()) continue;
      if (s.contains(va, vb)) continue;
      s.pts[static_cast<std::size_t>(s.size++)] = point(va, vb);
    }
  }
  int hint_a = s.size > 0 ? s.pts[0].va : -1;
  int hint_b = s.size > 0 ? s.pts[0].vb : -1;
  if (s.size == 0) {
    const Eigen::Vector3d d = o_A - pair.interiorPoint();
    const MPoint m = pair.supportM(d.squaredNorm() > 0.0 ? d : Eigen::Vector3d::UnitX(), -1, -1, &search);
    s.pts[0] = point(m.va, m.vb);
    s.size = 1;
    hint_a = m.va;
    hint_b = m.vb;
  }
  const double gap_tol = defaults::kDistanceGapRel * pair.scale();
  const double touch = pair.touchTolerance();
  double best_upper = std::numeric_limits<double>::infinity();
  for (int it = 0;; ++it) {
    if (closestOnSimplex(&s)) {
      out.contact = true;
      break;
    }
    const Eigen::Vector3d v = s.closest();
    const double vn = v.norm();
    if (vn <= touch) {
      out.contact = true;
      break;
    }
    if (it >= defaults::kMaxGjkIterations || !(vn < best_upper)) {
      out.stalled = out.lower < vn - gap_tol;
      break;
    }
    best_upper = vn;
    const MPoint m = pair.supportM(-v, hint_a, hint_b, &search);
    ++stats->gjk_iterations;
    hint_a = m.va;
    hint_b = m.vb;
    const SimplexPoint w = point(m.va, m.vb);
    out.lower = std::max(out.lower, v.dot(w.p) / vn);
    if (vn - out.lower <= std::max(gap_tol, rel_gap * vn) || out.lower >= enough) break;
    if (s.contains(m.va, m.vb)) {
      out.stalled = true;
      break;
    }
    s.pts[static_cast<std::size_t>(s.size++)] = w;
  }
  stats->support_vertices += search.support_vertices;
  for (int i = 0; i < s.size; ++i) {
    const SimplexPoint& q = s.pts[static_cast<std::size_t>(i)];
    const double wi = s.w[static_cast<std::size_t>(i)];
    out.a_A += wi * pair.a().localVertex(q.va);
    out.b_A += wi * pair.bVertex(q.vb);
  }
  out.upper = (out.a_A - out.b_A - o_A).norm();
  if (out.contact) out.lower = 0.0;
  return out;
}

/// Closest points of segments p0 p1 and q0 q1 (Ericson, Real-Time Collision
/// Detection 5.1.9), returned through pa / pb.
void closestSegmentSegment(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                           const Eigen::Vector3d& q1, Eigen::Vector3d* pa, Eigen::Vector3d* pb) {
  const Eigen::Vector3d d1 = p1 - p0;
  const Eigen::Vector3d d2 = q1 - q0;
  const Eigen::Vector3d r = p0 - q0;
  const double a = d1.squaredNorm();
  const double e = d2.squaredNorm();
  const double f = d2.dot(r);
  double s = 0.0;
  double t = 0.0;
  if (a <= 0.0 && e <= 0.0) {
  } else if (a <= 0.0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= 0.0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2);
      const double denom = a * e - b * b;
      s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  *pa = p0 + s * d1;
  *pb = q0 + t * d2;
}

/// The features of one body near its supporting plane: the vertices within
/// the tie tolerance of the support value, and the faces and edges incident
/// to them (sorted, unique).
struct FeatureSet {
  std::vector<int> vertices;
  std::vector<int> faces;
  std::vector<int> edges;
};

FeatureSet featuresAround(const ConvexPolytope& body, const Eigen::Vector3d& d, int support, double tol) {
  FeatureSet f;
  body.supportTies(d, support, tol, &f.vertices);
  if (f.vertices.empty()) f.vertices.push_back(support);
  for (int v : f.vertices) {
    for (int x : body.vertexFaces(v)) f.faces.push_back(x);
    for (int e : body.vertexEdges(v)) f.edges.push_back(e);
  }
  for (std::vector<int>* list : {&f.vertices, &f.faces, &f.edges}) {
    std::sort(list->begin(), list->end());
    list->erase(std::unique(list->begin(), list->end()), list->end());
  }
  return f;
}

/// Exact closest points of separated A and B (A's local frame) near the
/// approximate closest point v_A of M, with the certified lower bound
/// min over M of n . x (n = v / |v|) through `lower`.
///
/// Why the features below contain a closest pair: let a* - b* be the point of
/// M closest to the origin, at distance d* <= |v|. With lo_A = min over A of
/// n . a and hi_B = max over B of n . b, (n . a* - lo_A) + (hi_B - n . b*) =
/// n . (a* - b*) - (lo_A - hi_B) <= |v| - lower =: gap, both terms >= 0. a*
/// lies in a vertex, edge or face of A whose lowest vertex (along n) is at
/// most n . a*, hence within gap of lo_A: a tied vertex, to which that edge
/// or face is incident. The same holds for b* (highest vertex along n). The
/// closest pair of two convex polytopes is a vertex-face or an edge-edge pair
/// (vertex-vertex and vertex-edge pairs are edge-edge pairs too), so it is
/// among: tied vertices of B x faces around A's ties, tied vertices of A x
/// faces around B's ties, edges around A's ties x edges around B's ties. A
/// gap this large costs more pairs, never a wrong answer.
void polish(const PairGeometry& pair, const Eigen::Vector3d& v_A, double* lower, Eigen::Vector3d* best_a,
            Eigen::Vector3d* best_b, DistanceStats* stats) {
  const ConvexPolytope& A = pair.a();
  const ConvexPolytope& B = pair.b();
  SearchStats search;
  const Eigen::Vector3d n = v_A.normalized();
  const int va = pair.supportA(-n, -1, &search);       // lowest vertex of A along n
  const int vb = pair.supportMinusB(-n, -1, &search);  // highest vertex of B along n
  const double lo_a = n.dot(A.localVertex(va));
  const double hi_b = n.dot(pair.bVertex(vb));
  stats->support_vertices += search.support_vertices;
  *lower = std::max(*lower, lo_a - hi_b);
  // The round-off of the dot products (~1e-16 of the coordinates) is covered
  // by the tie tolerance added to the gap.
  const double tol = std::max(v_A.norm() - (lo_a - hi_b), 0.0) + pair.tieTolerance();
  const FeatureSet fa = featuresAround(A, -n, va, tol);
  const FeatureSet fb = featuresAround(B, pair.aToB(n), vb, tol);
  stats->polish_pairs += static_cast<int>(fb.vertices.size() * fa.faces.size() + fa.vertices.size() * fb.faces.size() +
                                          fa.edges.size() * fb.edges.size());

  double best = std::numeric_limits<double>::infinity();
  auto consider = [&](const Eigen::Vector3d& pa, const Eigen::Vector3d& pb) {
    const double d = (pa - pb).squaredNorm();
    if (d < best) {
      best = d;
      *best_a = pa;
      *best_b = pb;
    }
  };
  // Vertex against face: the foot point if it lies in the face polygon.
  auto vertexFace = [&](const ConvexPolytope& body, int f, const Eigen::Vector3d& nf, auto vertexOf,
                        const Eigen::Vector3d& p, bool p_is_b) {
    const IndexRange loop = body.faceVertices(f);
    const Eigen::Vector3d p0 = vertexOf(loop[0]);
    const Eigen::Vector3d foot = p - nf.dot(p - p0) * nf;
    for (int k = 0; k < loop.size(); ++k) {
      const Eigen::Vector3d u = vertexOf(loop[k]);
      const Eigen::Vector3d w = vertexOf(loop[(k + 1) % loop.size()]);
      if ((w - u).cross(foot - u).dot(nf) < 0.0) return;  // outside (the edge pairs cover it)
    }
    if (p_is_b) {
      consider(foot, p);
    } else {
      consider(p, foot);
    }
  };
  auto aVertex = [&](int v) -> Eigen::Vector3d { return A.localVertex(v); };
  auto bVertex = [&](int v) -> Eigen::Vector3d { return pair.bVertex(v); };
  for (int f : fa.faces) {
    for (int v : fb.vertices) vertexFace(A, f, A.faceNormal(f), aVertex, bVertex(v), true);
  }
  for (int f : fb.faces) {
    const Eigen::Vector3d nf = pair.bToA(B.faceNormal(f));
    for (int v : fa.vertices) vertexFace(B, f, nf, bVertex, aVertex(v), false);
  }
  for (int ea : fa.edges) {
    const ConvexPolytope::Edge& x = A.edge(ea);
    for (int eb : fb.edges) {
      const ConvexPolytope::Edge& y = B.edge(eb);
      Eigen::Vector3d pa;
      Eigen::Vector3d pb;
      closestSegmentSegment(aVertex(x.v0), aVertex(x.v1), bVertex(y.v0), bVertex(y.v1), &pa, &pb);
      consider(pa, pb);
    }
  }
}

void saveWarm(const Simplex& s, DistanceWarmStart* warm) {
  if (warm == nullptr) return;
  warm->size = s.size;
  for (int i = 0; i < s.size; ++i) {
    warm->a[i] = s.pts[static_cast<std::size_t>(i)].va;
    warm->b[i] = s.pts[static_cast<std::size_t>(i)].vb;
  }
}

}  // namespace
}  // namespace detail

double separationLowerBound(const DistanceInput& input, DistanceWarmStart* warm, double enough, double rel_gap) {
  if (std::isnan(enough)) throw InvalidInputError("separationLowerBound: enough is NaN");
  if (!(rel_gap >= 0.0 && rel_gap < 1.0)) {
    throw InvalidInputError("separationLowerBound: rel_gap must be in [0, 1) (got " + std::to_string(rel_gap) + ")");
  }
  const detail::PairGeometry pair(input.a, input.X_WA, input.b, input.X_WB, "separationLowerBound");
  DistanceStats stats;
  const detail::GjkOutcome g = detail::runGjk(pair, Eigen::Vector3d::Zero(), warm, &stats, enough, rel_gap);
  detail::saveWarm(g.simplex, warm);
  if (g.contact || !(g.upper > pair.touchTolerance())) return 0.0;
  // g.lower is certified whether or not GJK closed its gap.
  return std::max(0.0, std::min(g.lower, g.upper));
}

DistanceResult distance(const DistanceInput& input, DistanceWarmStart* warm) {
  const detail::PairGeometry pair(input.a, input.X_WA, input.b, input.X_WB, "distance");
  DistanceResult r;
  const detail::GjkOutcome g = detail::runGjk(pair, Eigen::Vector3d::Zero(), warm, &r.stats);
  detail::saveWarm(g.simplex, warm);
  if (!g.contact && g.upper > pair.touchTolerance()) {
    Eigen::Vector3d a_A = g.a_A;
    Eigen::Vector3d b_A = g.b_A;
    double dist = g.upper;
    double lower = g.lower;
    if (g.stalled) {
      r.stats.polished = true;
      detail::polish(pair, g.a_A - g.b_A, &lower, &a_A, &b_A, &r.stats);
      dist = (a_A - b_A).norm();
      // The polish evaluates a closest feature pair exactly (up to
      // round-off): its answer is the distance, not just an upper bound.
      lower = dist;
    }
    if (dist > pair.touchTolerance()) {
      r.status = DistanceStatus::kSeparated;
      r.distance = dist;
      r.lower_bound = std::min(lower, dist);
      r.p_WA = pair.pointToWorld(a_A);
      r.p_WB = pair.pointToWorld(b_A);
      r.normal_W = pair.vectorToWorld((b_A - a_A) / dist);
      return r;
    }
  }
  // The origin is in M or within the touch tolerance of it.
  r.stats.penetration = true;
  PenetrationInput pin;
  pin.a = input.a;
  pin.X_WA = input.X_WA;
  pin.b = input.b;
  pin.X_WB = input.X_WB;
  pin.method = PenetrationMethod::kExact;
  const PenetrationResult pd = penetrationDepth(pin);
  if (pd.status != PenetrationStatus::kPenetrating) {
    r.status = DistanceStatus::kTouching;
    r.distance = 0.0;
    r.lower_bound = 0.0;
    r.p_WA = pair.pointToWorld(g.a_A);
    r.p_WB = pair.pointToWorld(g.b_A);
    return r;
  }
  // B translated by t = PD n touches A: the closest points of A and B + t
  // (GJK toward the point t of M) are the deepest pair.
  const Eigen::Vector3d t_A = pair.vectorToA(pd.translation_W);
  const detail::GjkOutcome h = detail::runGjk(pair, t_A, nullptr, &r.stats);
  r.status = DistanceStatus::kPenetrating;
  r.distance = -pd.depth;
  r.lower_bound = r.distance;
  r.p_WA = pair.pointToWorld(h.a_A);
  r.p_WB = pair.pointToWorld(h.b_A);
  r.normal_W = pd.normal_W;
  return r;
}

}  // namespace mddual
