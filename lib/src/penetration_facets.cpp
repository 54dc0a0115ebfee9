// The facet graph of M = A - B without building M: evaluation of a named
// facet and its neighbours, for the shallow method's breadth-first search
// (penetration paper section 3.2, step 5(ii): "an implicit breadth-first
// search on the boundary of P"). The evaluations and neighbourhoods are those
// of the MDD-DUAL search (search.cpp), restated here because the search keeps
// them private to its hill climb.
#include <algorithm>
#include <cmath>
#include <limits>

#include "mddual/defaults.h"
#include "penetration_internal.h"

namespace mddual::detail {
namespace {

void addEdgesOf(const ConvexPolytope& p, const int* first, const int* last, std::vector<int>* edges) {
  edges->clear();
  for (const int* v = first; v != last; ++v) {
    for (int e : p.vertexEdges(*v)) {
      if (std::find(edges->begin(), edges->end(), e) == edges->end()) edges->push_back(e);
    }
  }
}

void addEdgesOf(const ConvexPolytope& p, const std::vector<int>& vertices, std::vector<int>* edges) {
  addEdgesOf(p, vertices.data(), vertices.data() + vertices.size(), edges);
}

}  // namespace

std::uint64_t FacetGraph::key(const FaceOfM& f) {
  // FV and VF facets are named by their facet alone (the vertex follows).
  const int a = f.kind == FaceOfM::Kind::kVF ? 0 : f.a;
  const int b = f.kind == FaceOfM::Kind::kFV ? 0 : f.b;
  return (static_cast<std::uint64_t>(f.kind) << 62) |
         (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 31) | static_cast<std::uint32_t>(b);
}

FacetGraph::FacetGraph(const PairGeometry& pair, PenetrationStats* stats)
    : pair_(pair), stats_(stats), edges_b_(static_cast<size_t>(pair.b().numEdges())) {
  const ConvexPolytope& a = pair.a();
  const ConvexPolytope& b = pair.b();
  c_B_ = a.localCentroid() - pair.interiorPoint();
  c_A_in_B_ = pair.aToB(a.localCentroid() - pair.p_AB());
  rho_A_ = std::numeric_limits<double>::infinity();
  rho_B_ = std::numeric_limits<double>::infinity();
  for (int f = 0; f < a.numFaces(); ++f)
    rho_A_ = std::min(rho_A_, a.localFaceOffset(f) - a.faceNormal(f).dot(a.localCentroid()));
  for (int g = 0; g < b.numFaces(); ++g)
    rho_B_ = std::min(rho_B_, b.localFaceOffset(g) - b.faceNormal(g).dot(b.localCentroid()));
  rho_A_ = std::max(rho_A_, 0.0);
  rho_B_ = std::max(rho_B_, 0.0);
}

double FacetGraph::lowerBound(const FaceOfM& face) const {
  // The bounds of penetration_exact.cpp (branchAndBound): h_A(n) >= n . c_A
  // + rho_A and h_-B(n) >= -n . c_B + rho_B for unit n.
  const ConvexPolytope& a = pair_.a();
  const ConvexPolytope& b = pair_.b();
  if (face.kind == FaceOfM::Kind::kFV && face.a >= 0 && face.a < a.numFaces()) {
    return a.localFaceOffset(face.a) - a.faceNormal(face.a).dot(c_B_) + rho_B_;
  }
  if (face.kind == FaceOfM::Kind::kVF && face.b >= 0 && face.b < b.numFaces()) {
    return b.localFaceOffset(face.b) - b.faceNormal(face.b).dot(c_A_in_B_) + rho_A_;
  }
  if (face.kind == FaceOfM::Kind::kEE && face.a >= 0 && face.a < a.numEdges()) {
    // rho_B + min over the arc of edge a of n . (a - c_B).
    const ConvexPolytope::Edge& edge = a.edge(face.a);
    const Eigen::Vector3d q = a.localVertex(edge.v0) - c_B_;
    double low = std::min(q.dot(a.faceNormal(edge.face_left)), q.dot(a.faceNormal(edge.face_right)));
    const Eigen::Vector3d q_perp = q - q.dot(edge.dir_P) * edge.dir_P;
    const double norm = q_perp.norm();
    if (norm > 0.0 && -q_perp.dot(edge.wedge_left_P) >= 0.0 && -q_perp.dot(edge.wedge_right_P) >= 0.0) low = -norm;
    return low + rho_B_;
  }
  return -std::numeric_limits<double>::infinity();
}

const FacetGraph::EdgeInA& FacetGraph::edgeInA(int e, bool of_b) {
  const ConvexPolytope::Edge& edge = (of_b ? pair_.b() : pair_.a()).edge(e);
  EdgeInA& x = of_b ? edges_b_[static_cast<size_t>(e)] : edge_a_;
  if (of_b && x.id == e) return x;
  x.id = e;
  if (of_b) {
    x.dir = pair_.bToA(edge.dir_P);
    x.wedge_left = pair_.bToA(edge.wedge_left_P);
    x.wedge_right = pair_.bToA(edge.wedge_right_P);
    x.p0 = pair_.bVertex(edge.v0);
  } else {
    x.dir = edge.dir_P;
    x.wedge_left = edge.wedge_left_P;
    x.wedge_right = edge.wedge_right_P;
    x.p0 = pair_.a().localVertex(edge.v0);
  }
  return x;
}

bool FacetGraph::evalEE(const EdgeInA& ea, const EdgeInA& eb, Node* out) const {
  // Arc crossing (MDD-DUAL paper VI-B) as wedge tests, as in search.cpp:
  // n = +-(dir_a x dir_b) on the arc of ea and -n on the arc of eb.
  const Eigen::Vector3d x = ea.dir.cross(eb.dir);
  const double al = x.dot(ea.wedge_left);
  const double ar = x.dot(ea.wedge_right);
  const double bl = x.dot(eb.wedge_left);
  const double br = x.dot(eb.wedge_right);
  double sign = 0.0;
  if (al >= 0.0 && ar >= 0.0 && bl <= 0.0 && br <= 0.0) sign = 1.0;
  if (sign == 0.0 && al <= 0.0 && ar <= 0.0 && bl >= 0.0 && br >= 0.0) sign = -1.0;
  const double sine = x.norm();
  if (sign == 0.0 || sine <= defaults::kParallelSin) return false;
  const Eigen::Vector3d n = (sign / sine) * x;
  const double margin = std::min({sign * al, sign * ar, -sign * bl, -sign * br}) / sine;
  out->plane.face = {FaceOfM::Kind::kEE, ea.id, eb.id};
  out->plane.n_A = n;
  out->plane.h = n.dot(ea.p0) - n.dot(eb.p0);
  out->plane.va = pair_.a().edge(ea.id).v0;
  out->plane.vb = pair_.b().edge(eb.id).v0;
  out->generic = margin > defaults::kParallelSin;
  return true;
}

bool FacetGraph::evaluate(const Ref& ref, Node* out) {
  const ConvexPolytope& a = pair_.a();
  const ConvexPolytope& b = pair_.b();
  const FaceOfM& f = ref.face;
  SearchStats support;
  double gap = 0.0;
  bool ok = false;
  if (f.kind == FaceOfM::Kind::kFV && f.a >= 0 && f.a < a.numFaces()) {
    // Facet f.a of A plus the vertex of -B supporting its normal.
    const Eigen::Vector3d& n = a.faceNormal(f.a);
    const int vb = pair_.supportMinusB(n, ref.hint_b, &support, &gap);
    out->plane = PdPlane{{FaceOfM::Kind::kFV, f.a, vb},
                         n,
                         a.localFaceOffset(f.a) - n.dot(pair_.bVertex(vb)),
                         a.faceVertices(f.a)[0],
                         vb};
    out->generic = gap > pair_.tieTolerance();
    ok = true;
  } else if (f.kind == FaceOfM::Kind::kVF && f.b >= 0 && f.b < b.numFaces()) {
    // The vertex of A supporting n = -n(f.b) plus facet f.b of -B.
    const Eigen::Vector3d n = -pair_.bToA(b.faceNormal(f.b));
    const int va = pair_.supportA(n, ref.hint_a, &support, &gap);
    out->plane = PdPlane{{FaceOfM::Kind::kVF, va, f.b},
                         n,
                         n.dot(a.localVertex(va)) + b.localFaceOffset(f.b) - n.dot(pair_.p_AB()),
                         va,
                         b.faceVertices(f.b)[0]};
    out->generic = gap > pair_.tieTolerance();
    ok = true;
  } else if (f.kind == FaceOfM::Kind::kEE && f.a >= 0 && f.a < a.numEdges() && f.b >= 0 && f.b < b.numEdges()) {
    const EdgeInA& eb = edgeInA(f.b, true);
    ok = evalEE(edgeInA(f.a, false), eb, out);
  }
  if (stats_ != nullptr) {
    stats_->support_vertices += support.support_vertices;
    if (ok) ++stats_->shallow_facets;
  }
  return ok;
}

void FacetGraph::neighbours(const Node& node, std::vector<Ref>* out) {
  const ConvexPolytope& a = pair_.a();
  const ConvexPolytope& b = pair_.b();
  const PdPlane& p = node.plane;
  const int va = p.va;
  const int vb = p.vb;
  auto fv = [&](int f) { out->push_back({{FaceOfM::Kind::kFV, f, -1}, va, vb}); };
  auto vf = [&](int g) { out->push_back({{FaceOfM::Kind::kVF, -1, g}, va, vb}); };
  auto ee = [&](int ea, int eb) { out->push_back({{FaceOfM::Kind::kEE, ea, eb}, va, vb}); };
  std::vector<int>& ties_a = ties_a_;
  std::vector<int>& ties_b = ties_b_;
  std::vector<int>& edges_a = edges_a_;
  std::vector<int>& edges_b = edges_b_list_;
  ties_a.clear();
  ties_b.clear();
  if (node.generic) {
    // One neighbour across each edge of the facet (MDD-DUAL paper Lemma 7,
    // search.cpp edgeNeighbours): FV(f, v) borders FV(f', v) across an edge
    // e of f, or EE(e, e_b) with e_b at v; VF symmetrically; EE(e_a, e_b)
    // borders the FV facets at e_a, the VF facets at e_b, and the EE facets
    // sharing e_a (with an edge at an end of e_b) or e_b.
    if (p.face.kind == FaceOfM::Kind::kFV) {
      for (int e : a.faceEdges(p.face.a)) fv(a.edge(e).otherFace(p.face.a));
      for (int e : a.faceEdges(p.face.a))
        for (int eb : b.vertexEdges(vb)) ee(e, eb);
    } else if (p.face.kind == FaceOfM::Kind::kVF) {
      for (int e : b.faceEdges(p.face.b)) vf(b.edge(e).otherFace(p.face.b));
      for (int e : b.faceEdges(p.face.b))
        for (int ea : a.vertexEdges(va)) ee(ea, e);
    } else {
      const ConvexPolytope::Edge& edge_a = a.edge(p.face.a);
      const ConvexPolytope::Edge& edge_b = b.edge(p.face.b);
      fv(edge_a.face_left);
      fv(edge_a.face_right);
      vf(edge_b.face_left);
      vf(edge_b.face_right);
      const int ends_b[2] = {edge_b.v0, edge_b.v1};
      addEdgesOf(b, ends_b, ends_b + 2, &edges_b);
      for (int eb : edges_b)
        if (eb != p.face.b) ee(p.face.a, eb);
      const int ends_a[2] = {edge_a.v0, edge_a.v1};
      addEdgesOf(a, ends_a, ends_a + 2, &edges_a);
      for (int ea : edges_a)
        if (ea != p.face.a) ee(ea, p.face.b);
    }
    return;
  }
  // Degenerate facet: every facet sharing a vertex with it, read off the
  // features of A and B that support its normal (search.cpp, searchEE).
  const double tie = pair_.tieTolerance();
  a.supportTies(p.n_A, va, tie, &ties_a);
  b.supportTies(-pair_.aToB(p.n_A), vb, tie, &ties_b);
  for (int v : ties_a)
    for (int f : a.vertexFaces(v)) fv(f);
  for (int v : ties_b)
    for (int g : b.vertexFaces(v)) vf(g);
  addEdgesOf(a, ties_a, &edges_a);
  addEdgesOf(b, ties_b, &edges_b);
  for (int ea : edges_a)
    for (int eb : edges_b) ee(ea, eb);
}

}  // namespace mddual::detail
