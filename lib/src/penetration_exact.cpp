// Exact penetration depth by enumerating the facets of M = A - B that can be
// closest to the origin (penetration paper section 2.2, "Penetration-Depth",
// step 1 and the superposition of the two normal diagrams it describes).
//
// Every facet of M is one of (MDD-DUAL paper II-C):
//   FV  a facet f of A plus the vertex of -B supporting n(f): offset
//       h = h_A(n) + h_-B(n) = offset(f) - n . b, one per facet of A;
//   VF  the vertex of A supporting n plus a facet g of -B, one per facet of B;
//   EE  an edge of A plus an edge of -B whose Gaussian arcs cross; the
//       crossing point is the facet's normal. There can be m x n of them.
//
// FV and EE together come from one walk over the Gaussian map of A (its
// vertices are the facet normals of A, its arcs the edges of A) overlaid on
// the map of -B (whose regions are the normal cones of B's vertices,
// negated): a breadth-first search over the facets of A walks every arc of A
// once, from a facet whose -B region is known to the facet at the other end.
// Along the arc the region is tracked exactly: the current region is the
// vertex vb of B that minimises x . b (the support of -B at the point x of the
// arc), and the walk leaves it at the first point where a neighbour w becomes
// better, i.e. where f_w(x) = x . (b_w - b_vb) turns negative. That point is
// on the arc of the edge (vb, w) of -B: a crossing of the two maps, hence one
// EE facet (normal x, offset x . (a - b_vb) for any a on the edge of A). The
// walk ends in the region of the facet at the other end of the arc, which
// gives that facet's FV plane without a support query. Cost: O(m + n + K_EE)
// region steps (each costing the degree of a vertex of B), K_EE the number of
// EE facets; the m x n pairs are never tested.
//
// Along the arc, with x the current point, tau = dir x x the direction of
// travel (dir the edge direction, oriented so the rotation about it carries
// the start facet's normal to the end's), a point at angle s further on is
// cos(s) x + sin(s) tau and
//     f_w(s) = (x . d) cos s + (tau . d) sin s,  d = b_w - b_vb.
// Writing f_w = R cos(s - psi), psi = atan2(tau . d, x . d), f_w turns
// negative at s = psi + pi/2; the crossing point itself is
//     x' = ((-tau . d) x + (x . d) tau) / R,  R = |(x . d, tau . d)|,
// which is orthogonal to d and to dir (the EE normal +-(dir x d)/|dir x d|,
// with the sign of the travel). Exits are compared by the pseudo-angle of
// (cos s, sin s) = (-tau . d, x . d) / R, a monotone function of s on
// [0, 2 pi) computed without trigonometry (pseudoAngle below). A tie at the
// current point (x . d = 0: the region is left right here, at a vertex of
// -B's map or at a region boundary the start support happened to pick)
// gives s = 0 when the walk moves into w's side (tau . d < 0): the walk then
// steps to w at once; this is the lexicographic support (x first, tau second)
// and keeps the walk exact on degenerate inputs (boxes in the same
// orientation). An edge of B parallel to the edge of A (R = 0: the arc runs
// along the boundary between the two regions) is never crossed.
//
// VF planes: a breadth-first search over the facets of B with the support
// vertex of A climbed from the neighbouring facet's (O(n) amortised).
//
// Two entry points: enumerateAll() does all of the above (every facet of M,
// counted by the tests); branchAndBound(), what penetrationDepth() runs,
// first bounds every candidate (facet of A, facet of B, arc of A) from below
// in O(1) each, using balls inside A and B, and enumerates exactly only the
// candidates whose bound is below the best offset found so far (the walk
// then runs on the surviving arcs only, starting from a support query). The
// minimum is the same; on the paper's pairs 80 to 97% of the candidates are
// skipped (more the deeper the bodies' centres lie inside each other).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "mddual/defaults.h"
#include "penetration_internal.h"

namespace mddual::detail {
namespace {

/// A monotone stand-in for atan2(s, c) mapped to [0, 4) instead of [0, 2 pi):
/// 0 at (1, 0), 1 at (0, 1), 2 at (-1, 0), 3 at (0, -1). (c, s) != (0, 0).
double pseudoAngle(double c, double s) {
  const double p = c / (std::abs(c) + std::abs(s));
  return s >= 0.0 ? 1.0 - p : 3.0 + p;
}

/// A candidate of the branch and bound: a facet of A (FV), of B (VF), or an
/// arc of A (its EE facets), with a lower bound on its offset.
struct Item {
  double bound;
  int kind;  // 0: FV facet, 1: VF facet, 2: arc
  int index;
};

/// Per-thread buffers of the enumeration, reused across queries so that a
/// query allocates nothing once the buffers have grown (resize() of a
/// vector that is already large enough neither allocates nor initialises).
struct PenetrationScratch {
  std::vector<Eigen::Vector3d> b_A;
  std::vector<char> ready;
  std::vector<Eigen::Vector3d> edge_A;
  std::vector<double> parallel2;
  std::vector<double> fv_base;
  std::vector<double> vf_base;
  std::vector<int> region;
  std::vector<Item> items;
};

PenetrationScratch& penetrationScratch() {
  thread_local PenetrationScratch s;
  return s;
}

class ExactEnumerator {
 public:
  ExactEnumerator(const PairGeometry& pair, PenetrationStats* stats)
      : pair_(pair),
        a_(pair.a()),
        b_(pair.b()),
        stats_(stats),
        s_(penetrationScratch()),
        b_A_(s_.b_A),
        ready_(s_.ready),
        edge_A_(s_.edge_A),
        parallel2_(s_.parallel2) {
    b_A_.resize(static_cast<size_t>(b_.numVertices()));
    ready_.assign(static_cast<size_t>(b_.numVertices()), 0);
    nbr_base_ = b_.vertexNeighbors(0).begin();
    const size_t entries = static_cast<size_t>(b_.vertexNeighbors(b_.numVertices() - 1).end() - nbr_base_);
    edge_A_.resize(entries);
    parallel2_.resize(entries);
  }

  /// Every FV, VF and EE facet (no pruning).
  PdPlane enumerateAll() {
    facetVertexAndEdgeEdge();
    vertexFacet();
    return best_;
  }
  /// Only the facets whose lower bound is below the best offset found.
  PdPlane branchAndBound();

 private:
  /// B's vertex v and its directed edges b_w - b_v in A's frame, computed on
  /// first use (the walk reads them for every region it enters; a pruned
  /// enumeration touches few of them).
  void prepare(int v) {
    if (ready_[static_cast<size_t>(v)] != 0) return;
    ready_[static_cast<size_t>(v)] = 1;
    b_A_[static_cast<size_t>(v)] = pair_.bVertex(v);
    const IndexRange nbrs = b_.vertexNeighbors(v);
    for (int k = 0; k < nbrs.size(); ++k) {
      const size_t i = static_cast<size_t>(nbrs.begin() + k - nbr_base_);
      edge_A_[i] = pair_.bToA(b_.localVertex(nbrs[k]) - b_.localVertex(v));
      parallel2_[i] = defaults::kParallelSin * defaults::kParallelSin * edge_A_[i].squaredNorm();
    }
  }
  const Eigen::Vector3d& bA(int v) {
    prepare(v);
    return b_A_[static_cast<size_t>(v)];
  }
  void offer(FaceOfM::Kind kind, int ia, int ib, const Eigen::Vector3d& n, double h, int va, int vb) {
    if (h < best_.h) best_ = PdPlane{{kind, ia, ib}, n, h, va, vb};
  }
  void offerFV(int f, int vb) {
    ++stats_->fv_facets;
    const Eigen::Vector3d& n = a_.faceNormal(f);
    offer(FaceOfM::Kind::kFV, f, vb, n, a_.localFaceOffset(f) - n.dot(bA(vb)), a_.faceVertices(f)[0], vb);
  }
  void offerVF(int g, int va) {
    ++stats_->vf_facets;
    const Eigen::Vector3d n = -pair_.bToA(b_.faceNormal(g));
    offer(FaceOfM::Kind::kVF, va, g, n, n.dot(a_.localVertex(va)) + b_.localFaceOffset(g) - n.dot(pair_.p_AB()), va,
          b_.faceVertices(g)[0]);
  }
  int supportMinusB(const Eigen::Vector3d& n, int hint) {
    SearchStats support;
    const int v = pair_.supportMinusB(n, hint, &support);
    stats_->support_vertices += support.support_vertices;
    return v;
  }
  void facetVertexAndEdgeEdge();
  void vertexFacet();
  int walkArc(int e, int from_face, int vb);
  int walkArcByTesting(int e, int from_face, int vb_hint);

  const PairGeometry& pair_;
  const ConvexPolytope& a_;
  const ConvexPolytope& b_;
  PenetrationStats* stats_;
  PenetrationScratch& s_;
  std::vector<Eigen::Vector3d>& b_A_;     ///< B's vertices in A's frame (where ready_)
  std::vector<char>& ready_;              ///< per vertex of B: b_A_ and its edges computed
  const int* nbr_base_ = nullptr;         ///< start of B's adjacency array
  std::vector<Eigen::Vector3d>& edge_A_;  ///< per adjacency entry (v, w): b_w - b_v, A's frame
  std::vector<double>& parallel2_;        ///< per adjacency entry: (kParallelSin |b_w - b_v|)^2
  PdPlane best_;
};

PdPlane ExactEnumerator::branchAndBound() {
  // Lower bounds (paper 2.2's facets of M, each bounded before it is
  // computed). A holds the ball of radius rho_A around its centroid c_A
  // (rho_A = the smallest distance from c_A to a face plane), so
  // h_A(n) >= n . c_A + rho_A for every unit n; likewise for B. Hence:
  //   FV facet f of A:  h = offset(f) + h_-B(n_f) >= offset(f) - n_f . c_B + rho_B;
  //   VF facet g of B:  h = h_A(-n_g) + offset(g) (B's frame, n_g its normal)
  //                       >= offset(g) - n_g . c_A + rho_A;
  //   EE facets on the arc of edge e of A (a on e, n on the arc):
  //                     h = n . a + h_-B(n) >= rho_B + min over the arc of n . (a - c_B).
  // n . q over the arc (a piece of the great circle orthogonal to the edge)
  // is smallest at -q_perp / |q_perp| (q_perp: q minus its component along
  // the edge) if that point is on the arc, else at an end, where it is the
  // end facet's FV bound minus rho_B. When c_B lies inside A the interior
  // case cannot happen: on the arc n . (a - c_B) = h_A(n) - n . c_B > 0,
  // while the value at -q_perp / |q_perp| is -|q_perp| <= 0. So then an
  // arc's bound is the smaller of its two facets' FV bounds, and only arcs at
  // a facet that survives need looking at.
  // A candidate whose bound is at least the best offset found so far cannot
  // be closer: it is skipped. The rest is enumerated exactly, the EE facets
  // by walking the arcs as in enumerateAll(), so the minimum is PD.
  const int m = a_.numFaces();
  const int n = b_.numFaces();
  const Eigen::Vector3d c_B = a_.localCentroid() - pair_.interiorPoint();  // B's centroid, A's frame
  const Eigen::Vector3d c_A_in_B = pair_.aToB(a_.localCentroid() - pair_.p_AB());
  const double slack = pair_.tieTolerance();
  // FV bounds without rho_B (fv_base), VF bounds without rho_A; the radii
  // come out of the same loops.
  std::vector<double>& fv_base = s_.fv_base;
  std::vector<double>& vf_base = s_.vf_base;
  fv_base.resize(static_cast<size_t>(m));
  vf_base.resize(static_cast<size_t>(n));
  double rho_A = std::numeric_limits<double>::infinity();
  double rho_B = std::numeric_limits<double>::infinity();
  double min_fv = rho_A;
  double min_vf = rho_A;
  int seed_fv = 0;
  int seed_vf = 0;
  for (int f = 0; f < m; ++f) {
    const Eigen::Vector3d& nf = a_.faceNormal(f);
    const double base = a_.localFaceOffset(f) - nf.dot(c_B);
    rho_A = std::min(rho_A, a_.localFaceOffset(f) - nf.dot(a_.localCentroid()));
    fv_base[static_cast<size_t>(f)] = base;
    if (base < min_fv) {
      min_fv = base;
      seed_fv = f;
    }
  }
  for (int g = 0; g < n; ++g) {
    const Eigen::Vector3d& ng = b_.faceNormal(g);
    const double base = b_.localFaceOffset(g) - ng.dot(c_A_in_B);
    rho_B = std::min(rho_B, b_.localFaceOffset(g) - ng.dot(b_.localCentroid()));
    vf_base[static_cast<size_t>(g)] = base;
    if (base < min_vf) {
      min_vf = base;
      seed_vf = g;
    }
  }
  rho_A = std::max(rho_A, 0.0);
  rho_B = std::max(rho_B, 0.0);
  const bool centre_in_a = min_fv > 0.0;  // c_B strictly inside A
  // Seeds: the FV and VF facets with the smallest bounds, computed exactly.
  std::vector<int>& region = s_.region;
  region.assign(static_cast<size_t>(m), -1);
  int hint_b = -1;
  int hint_a = -1;
  auto regionOf = [&](int f) {
    int& r = region[static_cast<size_t>(f)];
    if (r < 0) r = supportMinusB(a_.faceNormal(f), hint_b);
    hint_b = r;
    return r;
  };
  auto vertexFacet = [&](int g) {
    SearchStats support;
    hint_a = pair_.supportA(-pair_.bToA(b_.faceNormal(g)), hint_a, &support);
    stats_->support_vertices += support.support_vertices;
    offerVF(g, hint_a);
  };
  offerFV(seed_fv, regionOf(seed_fv));
  vertexFacet(seed_vf);
  // The candidates that can still beat the best.
  std::vector<Item>& items = s_.items;
  items.clear();
  const double cut = best_.h + slack;
  for (int f = 0; f < m; ++f) {
    const double bound = fv_base[static_cast<size_t>(f)] + rho_B;
    if (bound < cut && f != seed_fv) items.push_back({bound, 0, f});
  }
  for (int g = 0; g < n; ++g) {
    const double bound = vf_base[static_cast<size_t>(g)] + rho_A;
    if (bound < cut && g != seed_vf) items.push_back({bound, 1, g});
  }
  for (int e = 0; e < a_.numEdges(); ++e) {
    const ConvexPolytope::Edge& edge = a_.edge(e);
    double low = std::min(fv_base[static_cast<size_t>(edge.face_left)], fv_base[static_cast<size_t>(edge.face_right)]);
    if (centre_in_a && low + rho_B >= cut) continue;
    if (!centre_in_a) {
      const Eigen::Vector3d q = a_.localVertex(edge.v0) - c_B;
      const Eigen::Vector3d q_perp = q - q.dot(edge.dir_P) * edge.dir_P;
      const double norm = q_perp.norm();
      if (norm > 0.0 && -q_perp.dot(edge.wedge_left_P) >= 0.0 && -q_perp.dot(edge.wedge_right_P) >= 0.0) low = -norm;
    }
    if (low + rho_B < cut) items.push_back({low + rho_B, 2, e});
  }
  // Order: the kFirst candidates with the lowest bounds first (nth_element,
  // then sorted), which usually brings the best offset down to PD; every
  // candidate whose bound is below PD must be processed anyway, in any order,
  // so the rest is one pass, each candidate checked against the current best.
  const auto lower = [](const Item& x, const Item& y) { return x.bound < y.bound; };
  constexpr size_t kFirst = 16;
  const size_t first = std::min(kFirst, items.size());
  std::nth_element(items.begin(), items.begin() + static_cast<std::ptrdiff_t>(first), items.end(), lower);
  std::sort(items.begin(), items.begin() + static_cast<std::ptrdiff_t>(first), lower);
  int processed = 0;
  for (const Item& it : items) {
    if (it.bound - slack >= best_.h) continue;
    ++processed;
    if (it.kind == 0) {
      offerFV(it.index, regionOf(it.index));
    } else if (it.kind == 1) {
      vertexFacet(it.index);
    } else {
      const ConvexPolytope::Edge& edge = a_.edge(it.index);
      const int from =
          region[static_cast<size_t>(edge.face_left)] >= 0 || region[static_cast<size_t>(edge.face_right)] < 0
              ? edge.face_left
              : edge.face_right;
      const int to = edge.otherFace(from);
      const int end = walkArc(it.index, from, regionOf(from));
      if (region[static_cast<size_t>(to)] < 0) region[static_cast<size_t>(to)] = end;
    }
  }
  stats_->pruned += m + n + a_.numEdges() - 2 - processed;
  return best_;
}

void ExactEnumerator::facetVertexAndEdgeEdge() {
  // Breadth-first over the facets of A (across edges): each edge's arc is
  // walked once, from the facet reached first, and hands the region at its
  // far end to the facet there.
  const int m = a_.numFaces();
  std::vector<int> region(static_cast<size_t>(m), -1);
  std::vector<char> walked(static_cast<size_t>(a_.numEdges()), 0);
  std::vector<int> queue;
  queue.reserve(static_cast<size_t>(m));
  region[0] = supportMinusB(a_.faceNormal(0), -1);
  queue.push_back(0);
  for (size_t head = 0; head < queue.size(); ++head) {
    const int f = queue[head];
    offerFV(f, region[static_cast<size_t>(f)]);
    for (int e : a_.faceEdges(f)) {
      if (walked[static_cast<size_t>(e)] != 0) continue;
      walked[static_cast<size_t>(e)] = 1;
      const int g = a_.edge(e).otherFace(f);
      const int end_region = walkArc(e, f, region[static_cast<size_t>(f)]);
      if (region[static_cast<size_t>(g)] < 0) {
        region[static_cast<size_t>(g)] = end_region;
        queue.push_back(g);
      }
    }
  }
}

int ExactEnumerator::walkArc(int e, int from_face, int vb) {
  const ConvexPolytope::Edge& edge = a_.edge(e);
  const bool forward = from_face == edge.face_left;
  const Eigen::Vector3d dir = forward ? edge.dir_P : Eigen::Vector3d(-edge.dir_P);
  const Eigen::Vector3d& n_end = a_.faceNormal(forward ? edge.face_right : edge.face_left);
  const Eigen::Vector3d& a0 = a_.localVertex(edge.v0);
  Eigen::Vector3d x = a_.faceNormal(from_face);
  Eigen::Vector3d tau = dir.cross(x);
  // A geodesic arc (at most a half circle) enters each convex region of -B's
  // map at most once, so an exact walk takes at most |V(B)| steps; the cap
  // only catches round-off cycling, and the arc is then redone by testing.
  const int cap = b_.numVertices() + defaults::kPdWalkExtraSteps;
  for (int step = 0; step <= cap; ++step) {
    ++stats_->walk_steps;
    // Where the arc ends, as a pseudo-angle from x: in [0, 2] (at most a
    // half circle); round-off past the end (just below 4) means "here".
    double end = pseudoAngle(x.dot(n_end), tau.dot(n_end));
    if (end > 3.0) end = 0.0;
    double best = end;
    int best_k = -1;
    double best_fx = 0.0;
    double best_ft = 0.0;
    const IndexRange nbrs = b_.vertexNeighbors(vb);
    const Eigen::Vector3d& bv = bA(vb);
    const size_t first = static_cast<size_t>(nbrs.begin() - nbr_base_);
    for (int k = 0; k < nbrs.size(); ++k) {
      const Eigen::Vector3d& d = edge_A_[first + static_cast<size_t>(k)];
      const double fx = x.dot(d);
      const double ft = tau.dot(d);
      // Parallel edges: the arc runs along this region boundary, no crossing.
      if (fx * fx + ft * ft <= parallel2_[first + static_cast<size_t>(k)]) continue;
      // vb is not the support at x by more than round-off: the region was
      // lost (never in exact arithmetic); redo the arc by testing.
      if (fx < 0.0 && fx < -defaults::kPdWalkSlackRel * d.norm()) return walkArcByTesting(e, from_face, vb);
      double s = pseudoAngle(-ft, fx);
      // x . d < 0 and decreasing: the crossing is behind x (by round-off), so
      // the region is left here, at x (best_fx = 0 keeps x, see below).
      const bool behind = s >= 3.0;
      if (behind) s = 0.0;
      if (s < best) {
        best = s;
        best_k = k;
        best_fx = behind ? 0.0 : fx;
        best_ft = behind ? -1.0 : ft;
      }
    }
    stats_->arc_pairs += nbrs.size();
    if (best_k < 0) return vb;  // the rest of the arc lies in vb's region
    // Cross into the neighbour's region: an EE facet of M with normal x'.
    // A crossing behind x is taken at x itself. Moving back to it is a step
    // of angle atan(|x . d| / |tau . d|): tiny in general, but for an edge of
    // B within round-off of parallel to this edge of A (x . d and tau . d
    // both ~1e-12 |d|: a prism 1e6 from the origin, whose parallel edges the
    // input's rounding tilts) it is tens of degrees, and the walk then lost
    // its region (regression IdenticalPentagonalPrismsFarFromTheOrigin).
    // Staying at x offers the plane (x, x . (a - b_vb)), which is h_M(x) >= PD
    // up to the round-off by which vb is not the support at x.
    const double r = std::sqrt(best_fx * best_fx + best_ft * best_ft);
    x = ((-best_ft / r) * x + (best_fx / r) * tau).normalized();
    tau = dir.cross(x);
    ++stats_->ee_facets;
    offer(FaceOfM::Kind::kEE, e, b_.vertexEdges(vb)[best_k], x, x.dot(a0 - bv), edge.v0, vb);
    vb = nbrs[best_k];
  }
  return walkArcByTesting(e, from_face, vb);
}

int ExactEnumerator::walkArcByTesting(int e, int from_face, int vb_hint) {
  // Fallback (round-off only): the arc of edge e against the arc of every
  // edge of -B, with the crossing test of the MDD-DUAL search (paper VI-B as
  // wedge tests), then the end region by a support query.
  ++stats_->walk_fallbacks;
  const ConvexPolytope::Edge& ea = a_.edge(e);
  const Eigen::Vector3d& a0 = a_.localVertex(ea.v0);
  for (int j = 0; j < b_.numEdges(); ++j) {
    const ConvexPolytope::Edge& eb = b_.edge(j);
    const Eigen::Vector3d x = ea.dir_P.cross(pair_.bToA(eb.dir_P));
    const double al = x.dot(ea.wedge_left_P);
    const double ar = x.dot(ea.wedge_right_P);
    const double bl = x.dot(pair_.bToA(eb.wedge_left_P));
    const double br = x.dot(pair_.bToA(eb.wedge_right_P));
    ++stats_->arc_pairs;
    double sign = 0.0;
    if (al >= 0.0 && ar >= 0.0 && bl <= 0.0 && br <= 0.0) sign = 1.0;
    if (sign == 0.0 && al <= 0.0 && ar <= 0.0 && bl >= 0.0 && br >= 0.0) sign = -1.0;
    const double sine = x.norm();
    if (sign == 0.0 || sine <= defaults::kParallelSin) continue;
    const Eigen::Vector3d n = (sign / sine) * x;
    ++stats_->ee_facets;
    offer(FaceOfM::Kind::kEE, e, j, n, n.dot(a0 - bA(eb.v0)), ea.v0, eb.v0);
  }
  return supportMinusB(a_.faceNormal(ea.otherFace(from_face)), vb_hint);
}

void ExactEnumerator::vertexFacet() {
  // VF plane of facet g of B: n = -n(g) in A's frame, the vertex of A
  // supporting n, and h = n . a + h_-B(n) with h_-B(n) = offset(g) - n . p_AB
  // (search.cpp, evalVF). Breadth-first over B's facets, each support climbed
  // from the neighbouring facet's.
  const int nb = b_.numFaces();
  std::vector<int> va(static_cast<size_t>(nb), -1);
  std::vector<int> queue;
  queue.reserve(static_cast<size_t>(nb));
  SearchStats support;
  va[0] = pair_.supportA(-pair_.bToA(b_.faceNormal(0)), -1, &support);
  stats_->support_vertices += support.support_vertices;
  queue.push_back(0);
  SupportStats climb;
  for (size_t head = 0; head < queue.size(); ++head) {
    const int g = queue[head];
    const int v = va[static_cast<size_t>(g)];
    offerVF(g, v);
    for (int e : b_.faceEdges(g)) {
      const int h = b_.edge(e).otherFace(g);
      if (va[static_cast<size_t>(h)] >= 0) continue;
      va[static_cast<size_t>(h)] = a_.supportVertexHillClimb(-pair_.bToA(b_.faceNormal(h)), v, &climb);
      queue.push_back(h);
    }
  }
  stats_->support_vertices += climb.vertices_visited;
}

}  // namespace

PdPlane exactClosestFacet(const PairGeometry& pair, PenetrationStats* stats, bool prune) {
  ExactEnumerator enumerator(pair, stats);
  return prune ? enumerator.branchAndBound() : enumerator.enumerateAll();
}

}  // namespace mddual::detail
