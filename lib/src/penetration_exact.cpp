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
#include <algorithm>
#include <cmath>
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

int otherFace(const ConvexPolytope::Edge& e, int f) {
  return e.face_left == f ? e.face_right : e.face_left;
}

class ExactEnumerator {
 public:
  ExactEnumerator(const PairGeometry& pair, PenetrationStats* stats)
      : pair_(pair), a_(pair.a()), b_(pair.b()), stats_(stats) {
    b_A_.reserve(static_cast<size_t>(b_.numVertices()));
    for (int v = 0; v < b_.numVertices(); ++v) b_A_.push_back(pair.bVertex(v));
    // B's directed edges b_w - b_v in A's frame, aligned with the polytope's
    // adjacency array (the walk reads them for every region it enters), and
    // the squared threshold below which an edge counts as parallel to A's.
    nbr_base_ = b_.vertexNeighbors(0).begin();
    const size_t entries = static_cast<size_t>(b_.vertexNeighbors(b_.numVertices() - 1).end() - nbr_base_);
    edge_A_.resize(entries);
    parallel2_.resize(entries);
    for (int v = 0; v < b_.numVertices(); ++v) {
      const IndexRange nbrs = b_.vertexNeighbors(v);
      for (int k = 0; k < nbrs.size(); ++k) {
        const size_t i = static_cast<size_t>(nbrs.begin() + k - nbr_base_);
        edge_A_[i] = b_A_[static_cast<size_t>(nbrs[k])] - b_A_[static_cast<size_t>(v)];
        parallel2_[i] = defaults::kParallelSin * defaults::kParallelSin * edge_A_[i].squaredNorm();
      }
    }
  }

  PdPlane run() {
    facetVertexAndEdgeEdge();
    vertexFacet();
    return best_;
  }

 private:
  void offer(FaceOfM::Kind kind, int ia, int ib, const Eigen::Vector3d& n, double h, int va, int vb) {
    if (h < best_.h) best_ = PdPlane{{kind, ia, ib}, n, h, va, vb};
  }
  void offerFV(int f, int vb) {
    ++stats_->fv_facets;
    const Eigen::Vector3d& n = a_.faceNormal(f);
    offer(FaceOfM::Kind::kFV, f, vb, n, a_.faceOffset(f) - n.dot(b_A_[vb]), a_.faceVertices(f)[0], vb);
  }
  void facetVertexAndEdgeEdge();
  void vertexFacet();
  int walkArc(int e, int from_face, int vb);
  int walkArcByTesting(int e, int from_face, int vb_hint);

  const PairGeometry& pair_;
  const ConvexPolytope& a_;
  const ConvexPolytope& b_;
  PenetrationStats* stats_;
  std::vector<Eigen::Vector3d> b_A_;  ///< B's vertices in A's frame
  const int* nbr_base_ = nullptr;     ///< start of B's adjacency array
  std::vector<Eigen::Vector3d> edge_A_;  ///< per adjacency entry (v, w): b_w - b_v, A's frame
  std::vector<double> parallel2_;        ///< per adjacency entry: (kParallelSin |b_w - b_v|)^2
  PdPlane best_;
};

void ExactEnumerator::facetVertexAndEdgeEdge() {
  // Breadth-first over the facets of A (across edges): each edge's arc is
  // walked once, from the facet reached first, and hands the region at its
  // far end to the facet there.
  const int m = a_.numFaces();
  std::vector<int> region(static_cast<size_t>(m), -1);
  std::vector<char> walked(static_cast<size_t>(a_.numEdges()), 0);
  std::vector<int> queue;
  queue.reserve(static_cast<size_t>(m));
  SearchStats support;
  region[0] = pair_.supportMinusB(a_.faceNormal(0), -1, &support);
  stats_->support_vertices += support.support_vertices;
  queue.push_back(0);
  for (size_t head = 0; head < queue.size(); ++head) {
    const int f = queue[head];
    offerFV(f, region[static_cast<size_t>(f)]);
    for (int e : a_.faceEdges(f)) {
      if (walked[static_cast<size_t>(e)] != 0) continue;
      walked[static_cast<size_t>(e)] = 1;
      const int g = otherFace(a_.edge(e), f);
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
  const Eigen::Vector3d& a0 = a_.vertex(edge.v0);
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
    const Eigen::Vector3d& bv = b_A_[static_cast<size_t>(vb)];
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
      if (s >= 3.0) s = 0.0;  // x . d < 0 and decreasing: leave now
      if (s < best) {
        best = s;
        best_k = k;
        best_fx = fx;
        best_ft = ft;
      }
    }
    stats_->arc_pairs += nbrs.size();
    if (best_k < 0) return vb;  // the rest of the arc lies in vb's region
    // Cross into the neighbour's region: an EE facet of M with normal x'.
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
  const Eigen::Vector3d& a0 = a_.vertex(ea.v0);
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
    offer(FaceOfM::Kind::kEE, e, j, n, n.dot(a0 - b_A_[static_cast<size_t>(eb.v0)]), ea.v0, eb.v0);
  }
  const int to_face = otherFace(ea, from_face);
  SearchStats support;
  const int vb = pair_.supportMinusB(a_.faceNormal(to_face), vb_hint, &support);
  stats_->support_vertices += support.support_vertices;
  return vb;
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
    const Eigen::Vector3d n = -pair_.bToA(b_.faceNormal(g));
    const int v = va[static_cast<size_t>(g)];
    ++stats_->vf_facets;
    offer(FaceOfM::Kind::kVF, v, g, n, n.dot(a_.vertex(v)) + b_.faceOffset(g) - n.dot(pair_.p_AB()), v,
          b_.faceVertices(g)[0]);
    for (int e : b_.faceEdges(g)) {
      const int h = otherFace(b_.edge(e), g);
      if (va[static_cast<size_t>(h)] >= 0) continue;
      va[static_cast<size_t>(h)] = a_.supportVertexHillClimb(-pair_.bToA(b_.faceNormal(h)), v, &climb);
      queue.push_back(h);
    }
  }
  stats_->support_vertices += climb.vertices_visited;
}

}  // namespace

PdPlane exactClosestFacet(const PairGeometry& pair, PenetrationStats* stats) {
  return ExactEnumerator(pair, stats).run();
}

}  // namespace mddual::detail
