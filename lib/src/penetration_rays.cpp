// Ray shots from the origin to the boundary of M = A - B: Approx-Separation,
// Shallow-Penetration (penetration paper section 3 and 3.2) and the
// polyhedral metric (Corollary 3.5). Each shot is a MDD-DUAL ray search
// (search.h) with the centre c = 0: when A and B overlap, the origin is inside
// M and the search's objective phi = (n . u) / (h - n . c) = (n . u) / h is
// maximised by the facet where the ray {s u} leaves M, at s = 1 / phi
// = h / (n . u). Neighbouring directions usually leave through the same or an
// adjacent facet, so each shot starts from the previous shot's exit facet.
#include <algorithm>
#include <cmath>
#include <vector>

#include "key_set.h"
#include "mddual/defaults.h"
#include "penetration_internal.h"
#include "search.h"

namespace mddual::detail {
namespace {

KeySet& visitedSet() {
  thread_local KeySet set(256);
  set.clear();
  return set;
}

/// The exit facet of a search as a PdPlane, its FaceOfM named as in
/// penetration.h (FV: b = vertex of B; VF: a = vertex of A).
PdPlane planeOf(const RayExit& exit) {
  PdPlane p;
  p.face = exit.face;
  if (p.face.kind == FaceOfM::Kind::kFV) p.face.b = exit.vb;
  if (p.face.kind == FaceOfM::Kind::kVF) p.face.a = exit.va;
  p.n_A = exit.n_A;
  p.h = exit.h;
  p.va = exit.va;
  p.vb = exit.vb;
  return p;
}

/// One shot along unit u_A from the origin (inside M), warm-started at `warm`.
RayShot shoot(const PairGeometry& pair, const Eigen::Vector3d& u_A, const FaceOfM& warm, PenetrationStats* stats) {
  RayQuery q;
  q.c_A = Eigen::Vector3d::Zero();
  q.w_A = u_A;
  q.warm = warm;
  const RayExit exit = searchRay(pair, q, &stats->search);
  ++stats->rays;
  RayShot shot;
  shot.u_A = u_A;
  shot.exit = planeOf(exit);
  shot.r = exit.phi > 0.0 ? 1.0 / exit.phi : std::numeric_limits<double>::infinity();
  return shot;
}

}  // namespace

ApproxOutcome approxClosestFacet(const PairGeometry& pair, double delta, PenetrationStats* stats) {
  // Approx-Separation: PD <= (smallest exit offset h) <= (smallest exit
  // distance r) <= (1 + delta) PD. The middle step: every exit facet's plane
  // is a supporting plane of M, so its offset h is at least PD and at most
  // the distance r along the ray (r = h / (n . u) with n . u <= 1).
  const std::vector<Eigen::Vector3d> grid = directionGrid(delta);
  stats->grid_directions += static_cast<int>(grid.size());
  // Warm start: of the exit facets of the last kWarmWindow shots (the
  // grid's order puts the previous direction and the previous ring's
  // neighbours among them), the one whose plane the new ray meets first
  // (largest phi = n . u / h, known without a search) is the closest to its
  // exit facet on the dual polytope, so the climb from it is the shortest.
  constexpr size_t kWarmWindow = 64;
  ApproxOutcome out;
  out.shots.reserve(grid.size());
  for (const Eigen::Vector3d& u : grid) {
    FaceOfM warm;
    double best_phi = -std::numeric_limits<double>::infinity();
    const size_t first = out.shots.size() > kWarmWindow ? out.shots.size() - kWarmWindow : 0;
    for (size_t i = first; i < out.shots.size(); ++i) {
      const PdPlane& p = out.shots[i].exit;
      const double phi = p.n_A.dot(u) / p.h;
      if (phi > best_phi) {
        best_phi = phi;
        warm = p.face;
      }
    }
    out.shots.push_back(shoot(pair, u, warm, stats));
    keepCloser(out.shots.back().exit, &out.best);
  }
  return out;
}

PdPlane shallowClosestFacet(const PairGeometry& pair, double delta, PenetrationStats* stats) {
  // Steps 1-2: the approximation with delta / 4; rho = the smallest exit
  // offset, so PD <= rho <= (1 + delta / 4) PD.
  const ApproxOutcome approx = approxClosestFacet(pair, 0.25 * delta, stats);
  const double rho = approx.best.h;
  // Steps 3-4. G' = grid directions whose ray leaves M within
  // (1 + delta / 4) rho, and the ball of radius R = (1 + delta / 2) rho.
  // Why the search below finds the closest facet f* (foot point x* = PD v):
  // the grid direction u nearest to v is within theta (coveringAngle(delta /
  // 4)) of v, so r(u) <= PD / cos(theta) <= (1 + delta / 4) PD <=
  // (1 + delta / 4) rho: u is in G'. Along the great-circle arc from u to v,
  // every direction w is within theta of v, so the boundary point r(w) w
  // lies within PD / cos(theta) <= (1 + delta / 4) rho < R of the origin (the
  // ray meets f*'s plane by then). That path on the boundary of M runs from
  // u's exit facet to f* through facets that each have a point inside the
  // ball, hence a plane offset h < R; where it crosses a vertex of M, all the
  // facets around it contain that vertex and are in too. So f* is connected
  // to u's exit facet by facets with h < R, adjacent across edges.
  const double limit = (1.0 + 0.5 * delta) * rho;
  const double keep = (1.0 + 0.25 * delta) * rho;
  // Step 5: breadth-first search from the exit facets of G' over the facets
  // of M with h <= R (every facet evaluated counts toward the minimum).
  FacetGraph graph(pair, stats);
  KeySet& visited = visitedSet();
  std::vector<FacetGraph::Node> queue;
  std::vector<FacetGraph::Ref> refs;
  PdPlane best = approx.best;
  auto visit = [&](const FacetGraph::Ref& ref) {
    if (!visited.insert(FacetGraph::key(ref.face))) return;
    // A facet whose lower bound exceeds R is neither closest (PD <= rho < R)
    // nor to be expanded: it need not be evaluated.
    if (graph.lowerBound(ref.face) > limit) return;
    FacetGraph::Node node;
    if (!graph.evaluate(ref, &node)) return;
    keepCloser(node.plane, &best);
    if (node.plane.h <= limit) queue.push_back(node);
  };
  for (const RayShot& shot : approx.shots) {
    if (!(shot.r <= keep)) continue;
    ++stats->shallow_directions;
    visit({shot.exit.face, shot.exit.va, shot.exit.vb});
  }
  for (size_t head = 0; head < queue.size(); ++head) {
    refs.clear();
    graph.neighbours(queue[head], &refs);
    for (const FacetGraph::Ref& ref : refs) visit(ref);
  }
  // Step 6: the minimum over the components is PD.
  return best;
}

MetricOutcome metricClosestFacet(const PairGeometry& pair, const PolyhedralMetric& metric, PenetrationStats* stats) {
  // Corollary 3.5: the largest lambda with lambda K inside M has a vertex of
  // lambda K on the boundary of M, so lambda = min over the vertices k of K
  // of r(k / |k|) / |k| (how far the ray along k stays inside M, in copies
  // of k).
  MetricOutcome out;
  FaceOfM warm;
  const std::vector<Eigen::Vector3d>& ks = metric.vertices();
  stats->grid_directions += static_cast<int>(ks.size());
  for (int i = 0; i < static_cast<int>(ks.size()); ++i) {
    const Eigen::Vector3d k_A = pair.vectorToA(ks[static_cast<size_t>(i)]);
    const double length = k_A.norm();
    const RayShot shot = shoot(pair, k_A / length, warm, stats);
    warm = shot.exit.face;
    const double lambda = shot.r / length;
    if (lambda < out.lambda) {
      out.lambda = lambda;
      out.k_vertex = i;
      out.exit = shot.exit;
    }
  }
  return out;
}

}  // namespace mddual::detail
