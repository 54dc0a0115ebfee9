// The three search phases of MDD-DUAL (paper IV-B):
//
//   SEARCH-FV  climbs over the facets of A, each paired with its supporting
//              vertex of -B (faces of M of type FV), neighbours = facets of A
//              across an edge (the paper takes facets sharing a vertex; edge
//              neighbours evaluate a quarter as many faces per step: with
//              the FV/VF candidate pruning, toi on the paper's P4-P5 pair
//              took 29% less median time, docs/results/tuning.md);
//   SEARCH-VF  the same over the facets of B, starting at a facet incident to
//              the vertex of B where SEARCH-FV ended;
//   SEARCH-EE  starts at the better of the two and climbs over all faces of M
//              around the current one.
//
// Deviation from the paper, for robustness: the paper's SEARCH-EE moves over
// EE faces only and relies on SEARCH-FV/VF having found the best FV and VF
// faces. On degenerate inputs (coplanar facets of M, parallel edges) the FV
// and VF climbs can stop early, so our last phase considers every face of M
// that shares a vertex with the current one: FV faces of the facets of A at
// the current A feature, VF faces of the facets of B at the current B feature,
// and EE faces of the edges there whose Gaussian arcs cross. That set holds
// every face adjacent to the current face, so the climb is a local search on
// the dual polytope M* and ends at the global optimum whatever the first two
// phases did. The current features are read off the face normal with a small
// tie tolerance, so that a face whose supporting feature is an edge or a face
// of A or B (boxes in the same orientation) sees all its neighbours. A generic
// FV face with an edge parallel to an edge of B at its vertex has a VF face
// across that edge (no EE face exists there), VF symmetrically: before such
// a face is taken as the optimum, the other body's facets at its vertex are
// evaluated too. A warm start, which skips SEARCH-FV and SEARCH-VF, relies on
// this last phase alone.
#include "search.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "constants.h"
#include "key_set.h"
#include "mddual/defaults.h"
#include "mddual/error.h"
#include "planar.h"

namespace mddual::detail {
namespace {

std::uint64_t keyOf(FaceOfM::Kind kind, int a, int b) {
  return (static_cast<std::uint64_t>(kind) << 62) | (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 31) |
         static_cast<std::uint32_t>(b);
}

/// An edge of A or B with its direction, Gaussian-arc wedge and a point, all
/// in A's frame.
struct EdgeInA {
  int id = -1;
  int v0 = -1;
  Eigen::Vector3d dir;
  Eigen::Vector3d wedge_left;
  Eigen::Vector3d wedge_right;
  Eigen::Vector3d p0;
};

/// Per-thread scratch memory, so that a query does not allocate once warm.
struct SearchScratch {
  KeySet visited{64};  ///< faces of M visited (paper VI-D: a hash table of visited faces)
  std::vector<int> ties_a;
  std::vector<int> ties_b;
  std::vector<EdgeInA> edges_a;
  std::vector<EdgeInA> edges_b;
};

SearchScratch& searchScratch() {
  thread_local SearchScratch s;
  return s;
}

struct Candidate {
  FaceOfM face;
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  double h = 0.0;
  double phi = -kInf;
  int va = -1;
  int vb = -1;
  /// The face's features are exactly its named ones (no ties: the support
  /// vertex wins by more than the tie tolerance, the arcs cross strictly
  /// inside), so its neighbours on M are the faces across its own edges.
  bool generic = false;
  /// Generic, but only just: the support gap or the arcs' margin is within
  /// round-off of nearly planar faces (defaults::kContactTieMaxRel), so that
  /// the face may have neighbours its edges do not name.
  bool nearly_degenerate = false;
};

class Searcher {
 public:
  Searcher(const PairGeometry& pair, const RayQuery& query, SearchStats* stats)
      : pair_(pair), a_(pair.a()), b_(pair.b()), q_(query), stats_(stats), s_(searchScratch()) {
    s_.visited.clear();
  }

  RayExit run();

 private:
  enum class Phase { kFV, kVF, kEE };

  double objective(const Eigen::Vector3d& n, double h) const {
    const double along = n.dot(q_.w_A);
    const double depth = h - n.dot(q_.c_A);
    if (depth > 0.0) return along / depth;
    return along > 0.0 ? kInf : -kInf;  // c on the plane (round-off): exit at c
  }
  /// Evaluate an FV / VF face unless it provably cannot beat `best` (then
  /// false, and no support query was spent on it).
  bool evalFV(int fa, int hint_b, const Candidate& best, Candidate* c) const;
  bool evalVF(int fb, int hint_a, const Candidate& best, Candidate* c) const;
  bool cannotWin(const Eigen::Vector3d& n, double h_lower, const Candidate& best) const;
  bool evalEE(const EdgeInA& ea, const EdgeInA& eb, Candidate* c) const;
  /// Books a newly evaluated face; returns true when an early exit fired.
  bool take(const Candidate& c, Phase phase, Candidate* best);
  void checkSteps();

  Candidate coldStart();
  Candidate warmStart();
  Candidate searchFV(Candidate current);
  Candidate searchVF(const Candidate& fv);
  Candidate searchEE(Candidate current);
  /// Evaluates the faces across the edges of a generic face; true on an early exit.
  bool edgeNeighbours(const Candidate& current, Candidate* best);
  /// Evaluates the faces of M made of the other polytope's facets at the
  /// named vertex of a generic FV or VF face; true on an early exit.
  bool parallelEdgeNeighbours(const Candidate& current, Candidate* best);
  void collectEdges(const std::vector<int>& ties, bool of_b, std::vector<EdgeInA>* out) const;
  EdgeInA edgeInA(int e, bool of_b) const;

  const PairGeometry& pair_;
  const ConvexPolytope& a_;
  const ConvexPolytope& b_;
  const RayQuery& q_;
  SearchStats* stats_;
  SearchScratch& s_;
  bool stopped_ = false;
  Candidate stop_face_;
  int steps_ = 0;
  double min_h_ = kInf;
};

bool Searcher::cannotWin(const Eigen::Vector3d& n, double h_lower, const Candidate& best) const {
  // The true offset h is at least h_lower (a vertex's value bounds the
  // support value from below), so phi = (n.w) / (h - n.c) is at most
  // (n.w) / (h_lower - n.c) when that denominator is positive, and at most 0
  // when n.w <= 0. A face that cannot beat `best`, cannot fire an early exit
  // and is not within the touching tolerance is not worth a support query.
  if (h_lower < q_.h_stop || h_lower <= pair_.touchTolerance()) return false;
  const double along = n.dot(q_.w_A);
  if (along <= 0.0) return best.phi >= 0.0;
  const double depth_lower = h_lower - n.dot(q_.c_A);
  if (depth_lower <= 0.0) return false;
  const double bound = along / depth_lower;
  return bound <= best.phi && bound <= q_.phi_stop;
}

bool Searcher::evalFV(int fa, int hint_b, const Candidate& best, Candidate* c) const {
  // FV face: facet fa of A plus the vertex of -B supporting n(fa).
  const Eigen::Vector3d& n = a_.faceNormal(fa);
  if (hint_b >= 0 && cannotWin(n, a_.localFaceOffset(fa) - n.dot(pair_.bVertex(hint_b)), best)) return false;
  c->face = {FaceOfM::Kind::kFV, fa, 0};
  c->n = n;
  double gap = 0.0;
  c->vb = pair_.supportMinusB(c->n, hint_b, stats_, &gap);
  c->generic = gap > pair_.tieTolerance();
  c->nearly_degenerate = gap <= defaults::kContactTieMaxRel * pair_.scale();
  c->va = a_.faceVertices(fa)[0];
  c->h = a_.localFaceOffset(fa) - c->n.dot(pair_.bVertex(c->vb));
  c->phi = objective(c->n, c->h);
  return true;
}

bool Searcher::evalVF(int fb, int hint_a, const Candidate& best, Candidate* c) const {
  // VF face: the vertex of A supporting n plus facet fb of -B, n = -n(fb).
  // Its offset is h_A(n) + h_-B(n) with h_-B(n) = offset(fb) - n . p_AB.
  const Eigen::Vector3d n = -pair_.bToA(b_.faceNormal(fb));
  const double h_b = b_.localFaceOffset(fb) - n.dot(pair_.p_AB());
  if (hint_a >= 0 && cannotWin(n, n.dot(a_.localVertex(hint_a)) + h_b, best)) return false;
  c->face = {FaceOfM::Kind::kVF, 0, fb};
  c->n = n;
  double gap = 0.0;
  c->va = pair_.supportA(c->n, hint_a, stats_, &gap);
  c->generic = gap > pair_.tieTolerance();
  c->nearly_degenerate = gap <= defaults::kContactTieMaxRel * pair_.scale();
  c->vb = b_.faceVertices(fb)[0];
  c->h = c->n.dot(a_.localVertex(c->va)) + h_b;
  c->phi = objective(c->n, c->h);
  return true;
}

bool Searcher::evalEE(const EdgeInA& ea, const EdgeInA& eb, Candidate* c) const {
  // EE face (paper II-C, VI-B): the Gaussian arcs of edge ea of A and of edge
  // -eb of -B cross at n = +-(dir_a x dir_b). n is on the arc of ea when it is
  // in ea's wedge, and on the arc of -eb when -n is in eb's wedge.
  // The sign tests need no normalisation, so most pairs (which do not
  // cross) cost a cross product and four dot products.
  const Eigen::Vector3d x = ea.dir.cross(eb.dir);
  const double al = x.dot(ea.wedge_left);
  const double ar = x.dot(ea.wedge_right);
  const double bl = x.dot(eb.wedge_left);
  const double br = x.dot(eb.wedge_right);
  double sign = 0.0;
  if (al >= 0.0 && ar >= 0.0 && bl <= 0.0 && br <= 0.0) sign = 1.0;
  if (sign == 0.0 && al <= 0.0 && ar <= 0.0 && bl >= 0.0 && br >= 0.0) sign = -1.0;
  if (sign == 0.0) return false;
  const double sine = x.norm();
  if (sine <= defaults::kParallelSin) return false;  // parallel edges: no EE face
  const Eigen::Vector3d n = (sign / sine) * x;
  const double margin = std::min({sign * al, sign * ar, -sign * bl, -sign * br}) / sine;
  c->face = {FaceOfM::Kind::kEE, ea.id, eb.id};
  c->n = n;
  c->generic = margin > defaults::kParallelSin;
  c->nearly_degenerate = margin <= defaults::kContactTieMaxRel || sine < defaults::kEdgeEdgeWellConditionedSin;
  c->h = n.dot(ea.p0) - n.dot(eb.p0);
  c->va = ea.v0;
  c->vb = eb.v0;
  if (sine < defaults::kEdgeEdgeWellConditionedSin) {
    // Nearly parallel edges: n carries a relative error of about 1e-16 /
    // sine, and the plane through the edges with that normal can cut into M
    // (a better phi than the true exit face's, a shorter distance). The
    // support values of A and B along n give a plane that bounds M whatever
    // the error in n; its features are read off as ties.
    c->va = pair_.supportA(n, ea.v0, stats_);
    c->vb = pair_.supportMinusB(n, eb.v0, stats_);
    c->h = n.dot(a_.localVertex(c->va)) - n.dot(pair_.bVertex(c->vb));
    c->generic = false;
  }
  c->phi = objective(n, c->h);
  return true;
}

bool Searcher::take(const Candidate& c, Phase phase, Candidate* best) {
  if (stats_ != nullptr) {
    if (phase == Phase::kFV) ++stats_->fv_faces;
    if (phase == Phase::kVF) ++stats_->vf_faces;
    if (phase == Phase::kEE) {
      ++stats_->ee_faces;
      if (c.face.kind == FaceOfM::Kind::kEE) ++stats_->ee_edge_faces;
    }
  }
  min_h_ = std::min(min_h_, c.h);
  if (c.phi > best->phi) *best = c;
  if (c.phi > q_.phi_stop || c.h < q_.h_stop) {
    stopped_ = true;
    stop_face_ = c;
  }
  return stopped_;
}

void Searcher::checkSteps() {
  if (stats_ != nullptr) ++stats_->steps;
  if (++steps_ > defaults::kMaxSearchSteps) {
    throw NumericalError("MDD-DUAL search: no optimum after " + std::to_string(defaults::kMaxSearchSteps) +
                         " steps (round-off cycling)");
  }
}

Candidate Searcher::coldStart() {
  // Paper VI-A: start at the facet of A whose normal is closest to the ray
  // direction, found among the facets at A's support vertex in that direction.
  const int v = pair_.supportA(q_.w_A, -1, stats_);
  int best_face = a_.vertexFaces(v)[0];
  double best_dot = -kInf;
  for (int f : a_.vertexFaces(v)) {
    const double d = a_.faceNormal(f).dot(q_.w_A);
    if (d > best_dot) {
      best_dot = d;
      best_face = f;
    }
  }
  Candidate c;
  evalFV(best_face, -1, Candidate{}, &c);
  s_.visited.insert(keyOf(c.face.kind, c.face.a, c.face.b));
  Candidate none;
  take(c, Phase::kFV, &none);
  return c;
}

Candidate Searcher::warmStart() {
  const FaceOfM& w = q_.warm;
  Candidate c;
  bool ok = false;
  if (w.kind == FaceOfM::Kind::kFV && w.a >= 0 && w.a < a_.numFaces()) {
    evalFV(w.a, w.b >= 0 && w.b < b_.numVertices() ? w.b : -1, Candidate{}, &c);
    ok = true;
  } else if (w.kind == FaceOfM::Kind::kVF && w.b >= 0 && w.b < b_.numFaces()) {
    evalVF(w.b, w.a >= 0 && w.a < a_.numVertices() ? w.a : -1, Candidate{}, &c);
    ok = true;
  } else if (w.kind == FaceOfM::Kind::kEE && w.a >= 0 && w.a < a_.numEdges() && w.b >= 0 && w.b < b_.numEdges()) {
    // The edge pair may no longer cross after the motion: then fall back to
    // the FV face of a facet of A at that edge.
    ok = evalEE(edgeInA(w.a, false), edgeInA(w.b, true), &c);
    if (!ok) {
      evalFV(a_.edge(w.a).face_left, b_.edge(w.b).v0, Candidate{}, &c);
      ok = true;
    }
  }
  if (!ok) return coldStart();
  s_.visited.insert(keyOf(c.face.kind, c.face.a, c.face.b));
  Candidate none;
  take(c, Phase::kEE, &none);
  return c;
}

Candidate Searcher::searchFV(Candidate current) {
  for (;;) {
    Candidate best = current;
    for (int e : a_.faceEdges(current.face.a)) {
      const int f = a_.edge(e).otherFace(current.face.a);
      if (!s_.visited.insert(keyOf(FaceOfM::Kind::kFV, f, 0))) continue;
      Candidate c;
      if (evalFV(f, current.vb, best, &c) && take(c, Phase::kFV, &best)) return best;
    }
    if (!(best.phi > current.phi)) return current;
    current = best;
    checkSteps();
  }
}

Candidate Searcher::searchVF(const Candidate& fv) {
  // Start: the best facet of B at the vertex of B where SEARCH-FV ended.
  Candidate current;
  for (int f : b_.vertexFaces(fv.vb)) {
    if (!s_.visited.insert(keyOf(FaceOfM::Kind::kVF, 0, f))) continue;
    Candidate c;
    if (evalVF(f, fv.va, current, &c) && take(c, Phase::kVF, &current)) return current;
  }
  if (current.face.kind == FaceOfM::Kind::kNone) return fv;
  for (;;) {
    Candidate best = current;
    for (int e : b_.faceEdges(current.face.b)) {
      const int f = b_.edge(e).otherFace(current.face.b);
      if (!s_.visited.insert(keyOf(FaceOfM::Kind::kVF, 0, f))) continue;
      Candidate c;
      if (evalVF(f, current.va, best, &c) && take(c, Phase::kVF, &best)) return best;
    }
    if (!(best.phi > current.phi)) return current;
    current = best;
    checkSteps();
  }
}

EdgeInA Searcher::edgeInA(int e, bool of_b) const {
  const ConvexPolytope::Edge& edge = (of_b ? b_ : a_).edge(e);
  EdgeInA x;
  x.id = e;
  x.v0 = edge.v0;
  if (of_b) {
    x.dir = pair_.bToA(edge.dir_P);
    x.wedge_left = pair_.bToA(edge.wedge_left_P);
    x.wedge_right = pair_.bToA(edge.wedge_right_P);
    x.p0 = pair_.bVertex(edge.v0);
  } else {
    x.dir = edge.dir_P;
    x.wedge_left = edge.wedge_left_P;
    x.wedge_right = edge.wedge_right_P;
    x.p0 = a_.localVertex(edge.v0);
  }
  return x;
}

void Searcher::collectEdges(const std::vector<int>& ties, bool of_b, std::vector<EdgeInA>* out) const {
  out->clear();
  const ConvexPolytope& p = of_b ? b_ : a_;
  for (int v : ties) {
    for (int e : p.vertexEdges(v)) {
      if (std::any_of(out->begin(), out->end(), [e](const EdgeInA& x) { return x.id == e; })) continue;
      out->push_back(edgeInA(e, of_b));
    }
  }
}

bool Searcher::edgeNeighbours(const Candidate& current, Candidate* best) {
  // A generic face of M has one neighbour across each of its edges (paper
  // Lemma 7 and Fig. 10-11): FV(f, v) borders FV(f', v) across an edge e of f
  // or EE(e, e_b) with e_b at v; VF symmetrically; EE(e_a, e_b) borders the FV
  // faces of the two facets at e_a, the VF faces at e_b, and EE faces sharing
  // e_a (with an edge at an end of e_b) or e_b (with an edge at an end of e_a).
  auto fv = [&](int f) {
    if (!s_.visited.insert(keyOf(FaceOfM::Kind::kFV, f, 0))) return false;
    Candidate c;
    return evalFV(f, current.vb, *best, &c) && take(c, Phase::kEE, best);
  };
  auto vf = [&](int f) {
    if (!s_.visited.insert(keyOf(FaceOfM::Kind::kVF, 0, f))) return false;
    Candidate c;
    return evalVF(f, current.va, *best, &c) && take(c, Phase::kEE, best);
  };
  auto ee = [&](const EdgeInA& ea, const EdgeInA& eb) {
    // The arc test first: it is cheaper than the visited set, and most
    // pairs do not cross (re-testing them in a later step costs less than
    // remembering them).
    Candidate c;
    if (!evalEE(ea, eb, &c) || !s_.visited.insert(keyOf(FaceOfM::Kind::kEE, ea.id, eb.id))) return false;
    return take(c, Phase::kEE, best);
  };
  const FaceOfM& face = current.face;
  if (face.kind == FaceOfM::Kind::kFV) {
    for (int e : a_.faceEdges(face.a))
      if (fv(a_.edge(e).otherFace(face.a))) return true;
    s_.ties_b.assign({current.vb});
    collectEdges(s_.ties_b, true, &s_.edges_b);
    for (int e : a_.faceEdges(face.a)) {
      const EdgeInA ea = edgeInA(e, false);
      for (const EdgeInA& eb : s_.edges_b)
        if (ee(ea, eb)) return true;
    }
  } else if (face.kind == FaceOfM::Kind::kVF) {
    for (int e : b_.faceEdges(face.b))
      if (vf(b_.edge(e).otherFace(face.b))) return true;
    s_.ties_a.assign({current.va});
    collectEdges(s_.ties_a, false, &s_.edges_a);
    for (int e : b_.faceEdges(face.b)) {
      const EdgeInA eb = edgeInA(e, true);
      for (const EdgeInA& ea : s_.edges_a)
        if (ee(ea, eb)) return true;
    }
  } else {
    const ConvexPolytope::Edge& edge_a = a_.edge(face.a);
    const ConvexPolytope::Edge& edge_b = b_.edge(face.b);
    if (fv(edge_a.face_left) || fv(edge_a.face_right) || vf(edge_b.face_left) || vf(edge_b.face_right)) return true;
    const EdgeInA ea = edgeInA(face.a, false);
    const EdgeInA eb = edgeInA(face.b, true);
    s_.ties_b.assign({edge_b.v0, edge_b.v1});
    collectEdges(s_.ties_b, true, &s_.edges_b);
    for (const EdgeInA& other_b : s_.edges_b)
      if (other_b.id != face.b && ee(ea, other_b)) return true;
    s_.ties_a.assign({edge_a.v0, edge_a.v1});
    collectEdges(s_.ties_a, false, &s_.edges_a);
    for (const EdgeInA& other_a : s_.edges_a)
      if (other_a.id != face.a && ee(other_a, eb)) return true;
  }
  return false;
}

bool Searcher::parallelEdgeNeighbours(const Candidate& current, Candidate* best) {
  // An edge e of facet f of A parallel to an edge e_b of B at v: the arcs of
  // e and -e_b lie on one great circle, so they do not cross and there is no
  // EE(e, e_b) face. The face of M across the edge e - v of FV(f, v) is then
  // e + (a facet of -B at v holding e_b): a VF face, which edgeNeighbours
  // does not name (VF symmetrically). Extruded meshes (vertical edges on both
  // bodies) have such pairs everywhere. Every face of M across an edge of
  // FV(f, v) has features containing e (or f') and v, so the facets of B at
  // v complete the set. EE faces need nothing more: an edge of B at an end
  // of e_b parallel to e_a spans with e_b a facet of B at e_b, whose VF face
  // edgeNeighbours already names (A symmetrically).
  if (current.face.kind == FaceOfM::Kind::kFV) {
    for (int f : b_.vertexFaces(current.vb)) {
      if (!s_.visited.insert(keyOf(FaceOfM::Kind::kVF, 0, f))) continue;
      Candidate c;
      if (evalVF(f, current.va, *best, &c) && take(c, Phase::kEE, best)) return true;
    }
  } else if (current.face.kind == FaceOfM::Kind::kVF) {
    for (int f : a_.vertexFaces(current.va)) {
      if (!s_.visited.insert(keyOf(FaceOfM::Kind::kFV, f, 0))) continue;
      Candidate c;
      if (evalFV(f, current.vb, *best, &c) && take(c, Phase::kEE, best)) return true;
    }
  }
  return false;
}

Candidate Searcher::searchEE(Candidate current) {
  // Ties within `tie` name the current face's features. A face that is
  // planar only to round-off (nearly coplanar hull facets, points rounded far
  // from the origin) has vertices below the support value by more than the
  // tie tolerance, and a tie set missing them misses neighbours of the
  // current face: before a non-generic face is taken as the optimum, the
  // tolerance grows (defaults::kContactTieGrowth, up to kContactTieMaxRel)
  // and the larger tie sets' faces are evaluated too.
  const double base_tie = pair_.tieTolerance();
  const double max_tie = defaults::kContactTieMaxRel * pair_.scale();
  double tie = base_tie;
  size_t tied = 0;      // tie set sizes at the last evaluation of this face
  bool verify = false;  // a nearly degenerate local optimum, checked once more through its ties
  for (;;) {
    if (current.generic && !verify) {
      Candidate best = current;
      if (edgeNeighbours(current, &best)) return best;
      // A local optimum over the edge neighbours: before it is taken, the
      // faces across edges parallel to an edge of the other polytope (once
      // per optimum, not per step; a warm start relies on this alone, a cold
      // one usually met them in SEARCH-VF).
      if (!(best.phi > current.phi) && parallelEdgeNeighbours(current, &best)) return best;
      if (!(best.phi > current.phi)) {
        if (!current.nearly_degenerate) return current;
        verify = true;
        continue;
      }
      current = best;
      checkSteps();
      continue;
    }
    // The features of A and B that support the current face's normal.
    s_.ties_a.clear();
    s_.ties_b.clear();
    a_.supportTies(current.n, current.va, tie, &s_.ties_a);
    b_.supportTies(-pair_.aToB(current.n), current.vb, tie, &s_.ties_b);
    if (tie > base_tie && s_.ties_a.size() + s_.ties_b.size() == tied) {
      // A wider tolerance that adds no vertex adds no face.
      if (tie >= max_tie) return current;
      tie *= defaults::kContactTieGrowth;
      continue;
    }
    tied = s_.ties_a.size() + s_.ties_b.size();
    Candidate best = current;
    for (int v : s_.ties_a) {
      for (int f : a_.vertexFaces(v)) {
        if (!s_.visited.insert(keyOf(FaceOfM::Kind::kFV, f, 0))) continue;
        Candidate c;
        if (evalFV(f, current.vb, best, &c) && take(c, Phase::kEE, &best)) return best;
      }
    }
    for (int v : s_.ties_b) {
      for (int f : b_.vertexFaces(v)) {
        if (!s_.visited.insert(keyOf(FaceOfM::Kind::kVF, 0, f))) continue;
        Candidate c;
        if (evalVF(f, current.va, best, &c) && take(c, Phase::kEE, &best)) return best;
      }
    }
    collectEdges(s_.ties_a, false, &s_.edges_a);
    collectEdges(s_.ties_b, true, &s_.edges_b);
    for (const EdgeInA& ea : s_.edges_a) {
      for (const EdgeInA& eb : s_.edges_b) {
        Candidate c;  // arc test first, as in edgeNeighbours
        if (!evalEE(ea, eb, &c) || !s_.visited.insert(keyOf(FaceOfM::Kind::kEE, ea.id, eb.id))) continue;
        if (take(c, Phase::kEE, &best)) return best;
      }
    }
    if (!(best.phi > current.phi)) {
      if (tie >= max_tie) return current;
      tie *= defaults::kContactTieGrowth;
      continue;
    }
    current = best;
    tie = base_tie;
    tied = 0;
    verify = false;
    checkSteps();
  }
}

RayExit Searcher::run() {
  Candidate best;
  if (q_.warm.kind != FaceOfM::Kind::kNone) {
    best = warmStart();
  } else {
    const Candidate start = coldStart();
    const Candidate fv = stopped_ ? start : searchFV(start);
    const Candidate vf = stopped_ ? fv : searchVF(fv);
    best = vf.phi > fv.phi ? vf : fv;
  }
  if (!stopped_) best = searchEE(best);
  if (stopped_) best = stop_face_;
  RayExit out;
  out.face = best.face;
  out.n_A = best.n;
  out.h = best.h;
  out.phi = best.phi;
  out.va = best.va;
  out.vb = best.vb;
  out.stopped = stopped_;
  out.min_h = min_h_;
  return out;
}

}  // namespace

RayExit searchRay(const PairGeometry& pair, const RayQuery& query, SearchStats* stats) {
  if (stats != nullptr) ++stats->rays;
  return Searcher(pair, query, stats).run();
}

Eigen::Vector3d contactPointOnA(const PairGeometry& pair, const RayExit& exit, const Eigen::Vector3d& x_A) {
  // x = a - b with a on A's feature supporting n and b on B's feature
  // supporting -n: decompose x over the polygon conv(ties of A) -
  // conv(ties of B) in the face's plane (this covers FV, VF and EE faces and
  // face-face patches alike). The tie sets must hold the whole face of M that
  // x lies on: a face of A or B that is planar only to round-off (a hull
  // split into nearly coplanar facets, points rounded far from the origin)
  // has vertices farther below the support value than the tie tolerance, and
  // a partial tie set gives a smaller polygon that may miss x (the point
  // returned was then off one of the bodies by a good part of their size).
  // So the tolerance grows until the polygon holds x.
  std::vector<int>& ties_a = searchScratch().ties_a;
  std::vector<int>& ties_b = searchScratch().ties_b;
  const double tol = pair.touchTolerance();
  const double max_delta = defaults::kContactTieMaxRel * pair.scale();
  std::vector<Eigen::Vector3d> pa;
  std::vector<Eigen::Vector3d> pb;
  Eigen::Vector3d best_a = pair.a().localVertex(exit.va);
  double best_outside = kInf;
  for (double delta = pair.tieTolerance();; delta *= defaults::kContactTieGrowth) {
    ties_a.clear();
    ties_b.clear();
    pair.a().supportTies(exit.n_A, exit.va, delta, &ties_a);
    pair.b().supportTies(-pair.aToB(exit.n_A), exit.vb, delta, &ties_b);
    pa.clear();
    pb.clear();
    for (int v : ties_a) pa.push_back(pair.a().localVertex(v));
    for (int v : ties_b) pb.push_back(pair.bVertex(v));
    double outside = kInf;
    const Eigen::Vector3d a = PlanarDifference(pa, pb, exit.n_A).pointOfA(x_A, &outside);
    if (outside < best_outside) {
      best_outside = outside;
      best_a = a;
    }
    if (best_outside <= tol || delta >= max_delta) return best_a;
  }
}

}  // namespace mddual::detail
