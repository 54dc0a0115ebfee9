// Support-vertex queries: hill climbing on the vertex graph, started from a
// hint or from a direction table built with the Dobkin-Kirkpatrick hierarchy.
//
// Hill climbing is exact on a convex polytope: for a linear objective every
// vertex that is not a maximiser has a strictly better neighbour (the graph of
// a polytope is "monotone" for linear functions), so a climb that stops at a
// vertex with no better neighbour has found a global maximiser.
//
// The hierarchy (Dobkin and Kirkpatrick; the MDD-DUAL paper cites it for its
// support queries) is a sequence of nested polytopes P_0 = P, P_1, ..., P_k,
// each the hull of the vertices of the previous one minus an independent set of
// low-degree vertices, down to a constant size. A query scans P_k, then on
// each level climbs from the previous level's answer. The DK lemma bounds the
// climb on each level by a constant number of steps, so a cold query costs
// O(log n); because each level is itself climbed to a local (hence global)
// maximum, the answer is exact even where ties break the lemma's assumptions.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "mddual/defaults.h"
#include "mddual/error.h"
#include "mddual/polytope.h"
#include "qhull_wrapper.h"

namespace mddual {
namespace {

/// Edges (as local neighbour lists) of the hull of a subset of vertices.
/// Returns false when the subset's hull is flat (then the level is not built).
bool hullAdjacency(const std::vector<Eigen::Vector3d>& points, std::vector<int>* kept,
                   std::vector<std::vector<int>>* adjacency) {
  std::vector<detail::HullFacet> facets;
  try {
    facets = detail::hull3d(points, "support hierarchy level");
  } catch (const std::exception&) {
    return false;
  }
  std::vector<int> local(points.size(), -1);
  kept->clear();
  for (const detail::HullFacet& f : facets) {
    for (int v : f.vertices) {
      if (local[v] < 0) {
        local[v] = static_cast<int>(kept->size());
        kept->push_back(v);
      }
    }
  }
  adjacency->assign(kept->size(), {});
  for (const detail::HullFacet& f : facets) {
    const size_t k = f.vertices.size();
    for (size_t i = 0; i < k; ++i) {
      const int a = local[f.vertices[i]];
      const int b = local[f.vertices[(i + 1) % k]];
      (*adjacency)[a].push_back(b);  // each undirected edge is seen once per direction
    }
  }
  return true;
}

/// A vertex index outside [0, n) given to a support query: named, not read.
[[noreturn]] void throwVertexOutOfRange(const char* what, int v, int n) {
  throw InvalidInputError(std::string(what) + " " + std::to_string(v) + " is not a vertex index (the polytope has " +
                          std::to_string(n) + " vertices)");
}

}  // namespace

int ConvexPolytope::supportVertexHillClimb(const Eigen::Vector3d& d_P, int start, SupportStats* stats,
                                           double* gap) const {
  if (start < 0 || start >= numVertices()) throwVertexOutOfRange("supportVertexHillClimb: start", start, numVertices());
  int best = start;
  double best_value = d_P.dot(vertices_L_[best]);
  int visited = 1;
  double runner_up = -std::numeric_limits<double>::infinity();  // best neighbour of `best`
  for (;;) {
    int next = best;
    double next_value = best_value;
    runner_up = -std::numeric_limits<double>::infinity();
    for (int w : vertexNeighbors(best)) {
      const double value = d_P.dot(vertices_L_[w]);
      ++visited;
      runner_up = std::max(runner_up, value);
      if (value > next_value) {
        next_value = value;
        next = w;
      }
    }
    if (next == best) break;
    best = next;
    best_value = next_value;
  }
  if (stats != nullptr) stats->vertices_visited += visited;
  if (gap != nullptr) *gap = best_value - runner_up;
  return best;
}

int ConvexPolytope::climbLevel(const HierarchyLevel& level, const Eigen::Vector3d& d_P, int local_start,
                               SupportStats* stats) const {
  int best = local_start;
  double best_value = d_P.dot(vertices_L_[level.vertex_ids[best]]);
  int visited = 1;
  for (;;) {
    int next = best;
    for (int i = level.adjacency_begin[best]; i < level.adjacency_begin[best + 1]; ++i) {
      const int w = level.adjacency[i];
      const double value = d_P.dot(vertices_L_[level.vertex_ids[w]]);
      ++visited;
      if (value > best_value) {
        best_value = value;
        next = w;
      }
    }
    if (next == best) break;
    best = next;
  }
  if (stats != nullptr) stats->vertices_visited += visited;
  return best;
}

int ConvexPolytope::descendLevel(const HierarchyLevel& level, const Eigen::Vector3d& d_P, int local,
                                 SupportStats* stats) const {
  // DK step: the maximiser on this level is the coarser level's answer or one
  // of its neighbours that the coarser level dropped; a climb from a better
  // such neighbour settles ties and degenerate cases.
  int best = local;
  double best_value = d_P.dot(vertices_L_[level.vertex_ids[local]]);
  for (int i = level.removed_begin[local]; i < level.removed_begin[local + 1]; ++i) {
    const double value = d_P.dot(vertices_L_[level.vertex_ids[level.removed[i]]]);
    if (value > best_value) {
      best_value = value;
      best = level.removed[i];
    }
  }
  if (stats != nullptr) stats->vertices_visited += level.removed_begin[local + 1] - level.removed_begin[local];
  return best == local ? local : climbLevel(level, d_P, best, stats);
}

int ConvexPolytope::supportVertexHierarchy(const Eigen::Vector3d& d_P, SupportStats* stats, double* gap) const {
  if (levels_.empty()) return supportVertexHillClimb(d_P, 0, stats, gap);
  // Top level: exhaustive scan of a constant number of vertices.
  const HierarchyLevel& top = levels_.back();
  int local = 0;
  double best = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < static_cast<int>(top.vertex_ids.size()); ++i) {
    const double value = d_P.dot(vertices_L_[top.vertex_ids[i]]);
    if (value > best) {
      best = value;
      local = i;
    }
  }
  if (stats != nullptr) stats->vertices_visited += static_cast<int>(top.vertex_ids.size());
  // Descend level by level, checking only the vertices each level dropped.
  for (int k = static_cast<int>(levels_.size()) - 1; k >= 1; --k) {
    local = descendLevel(levels_[k - 1], d_P, levels_[k].below[local], stats);
  }
  // The full polytope: its dropped neighbours, then a climb that certifies
  // the answer (a local maximum of a linear function on a polytope).
  int v = levels_[0].below[local];
  double value = d_P.dot(vertices_L_[v]);
  int start = v;
  for (int i = removed_begin_[v]; i < removed_begin_[v + 1]; ++i) {
    const double w_value = d_P.dot(vertices_L_[removed_[i]]);
    if (w_value > value) {
      value = w_value;
      start = removed_[i];
    }
  }
  if (stats != nullptr) stats->vertices_visited += removed_begin_[v + 1] - removed_begin_[v];
  return supportVertexHillClimb(d_P, start, stats, gap);
}

namespace {
/// Polytopes of at most this many vertices are scanned whole: cheaper than
/// the table and the climb (boxes, triangles, small hulls). On arm7's motion
/// checks (mddual_bench_arm_edges, callgrind) 16 takes 7% fewer instructions
/// than the climb alone, more than 12 or 32 do (docs/results/tuning.md).
constexpr int kScanVertices = 16;
}  // namespace

int ConvexPolytope::supportVertex(const Eigen::Vector3d& d_P, int hint, SupportStats* stats, double* gap) const {
  // Small polytopes: every vertex (the hint cannot save anything).
  if (numVertices() <= kScanVertices) {
    if (hint >= numVertices()) throwVertexOutOfRange("supportVertex: hint", hint, numVertices());
    int best = 0;
    double best_value = d_P.dot(vertices_L_[0]);
    for (int v = 1; v < numVertices(); ++v) {
      const double value = d_P.dot(vertices_L_[v]);
      if (value > best_value) {
        best_value = value;
        best = v;
      }
    }
    if (stats != nullptr) stats->vertices_visited += numVertices();
    if (gap != nullptr) {
      double runner_up = -std::numeric_limits<double>::infinity();
      for (int w : vertexNeighbors(best)) runner_up = std::max(runner_up, d_P.dot(vertices_L_[w]));
      *gap = best_value - runner_up;
    }
    return best;
  }
  // Start from the better of the hint and the direction table's vertex: the
  // hint wins for coherent queries, the table when the direction moved far
  // (or when there is no hint); the climb then makes the answer exact.
  int start = tableStart(d_P);
  if (hint >= numVertices()) throwVertexOutOfRange("supportVertex: hint", hint, numVertices());
  if (hint >= 0 && d_P.dot(vertices_L_[hint]) > d_P.dot(vertices_L_[start])) start = hint;
  if (stats != nullptr) stats->vertices_visited += hint >= 0 ? 2 : 1;
  return supportVertexHillClimb(d_P, start, stats, gap);
}

void ConvexPolytope::supportTies(const Eigen::Vector3d& d_P, int v, double tol, std::vector<int>* out) const {
  if (v < 0 || v >= numVertices()) throwVertexOutOfRange("supportTies: vertex", v, numVertices());
  const size_t first = out->size();
  const double threshold = d_P.dot(vertices_L_[v]) - tol;
  out->push_back(v);
  // Breadth-first walk over tied vertices. Tie sets are small (a face at
  // most), so membership is a linear scan of what this call appended.
  for (size_t i = first; i < out->size(); ++i) {
    for (int w : vertexNeighbors((*out)[i])) {
      if (d_P.dot(vertices_L_[w]) < threshold) continue;
      if (std::find(out->begin() + static_cast<std::ptrdiff_t>(first), out->end(), w) == out->end()) {
        out->push_back(w);
      }
    }
  }
}

int ConvexPolytope::tableStart(const Eigen::Vector3d& d) const {
  // Cube map: the dominant axis picks the face, the other two coordinates
  // divided by the dominant one pick the cell.
  const Eigen::Vector3d a = d.cwiseAbs();
  int axis = 0;
  if (a.y() > a[axis]) axis = 1;
  if (a.z() > a[axis]) axis = 2;
  const int face = 2 * axis + (d[axis] < 0.0 ? 1 : 0);
  const double inv = 1.0 / a[axis];
  const double s = d[(axis + 1) % 3] * inv;
  const double t = d[(axis + 2) % 3] * inv;
  const int k = table_k_;
  const int i = std::min(k - 1, std::max(0, static_cast<int>((s + 1.0) * 0.5 * k)));
  const int j = std::min(k - 1, std::max(0, static_cast<int>((t + 1.0) * 0.5 * k)));
  return table_[(face * k + i) * k + j];
}

void ConvexPolytope::buildDirectionTable() {
  // A cube map of directions with about one cell per vertex, each cell holding
  // the support vertex of its central direction (found with the hierarchy:
  // O(n log n) to build). A climb from a cell's vertex takes a step or two.
  // On the paper's P4-P4 it cut the vertices a time-of-impact query evaluates
  // from 765 to 367. Small polytopes get at least 2 x 2 cells per face; the
  // table stops growing at 48 x 48 per face (55 KB).
  table_k_ = std::max(2, std::min(48, static_cast<int>(std::ceil(std::sqrt(numVertices() / 6.0)))));
  const int k = table_k_;
  table_.assign(6 * k * k, 0);
  // Without a hierarchy (small polytopes, and prism(), which builds none), a
  // climb from the previous cell's vertex: neighbouring cells' directions are
  // close, so it takes a few steps, where a climb from vertex 0 crossed half
  // the polytope (a prism of 200,000 corners: 12.7 s to build).
  int previous = 0;
  for (int face = 0; face < 6; ++face) {
    const int axis = face / 2;
    const double sign = face % 2 == 0 ? 1.0 : -1.0;
    for (int i = 0; i < k; ++i) {
      for (int j = 0; j < k; ++j) {
        Eigen::Vector3d d;
        d[axis] = sign;
        d[(axis + 1) % 3] = (i + 0.5) / k * 2.0 - 1.0;
        d[(axis + 2) % 3] = (j + 0.5) / k * 2.0 - 1.0;
        previous = levels_.empty() ? supportVertexHillClimb(d, previous) : supportVertexHierarchy(d);
        table_[(face * k + i) * k + j] = previous;
      }
    }
  }
}

void ConvexPolytope::buildHierarchy() {
  levels_.clear();
  removed_begin_.clear();
  removed_.clear();
  if (numVertices() <= defaults::kHierarchyMinVertices) return;

  // Current level: original ids and adjacency lists in local indices.
  std::vector<int> ids(numVertices());
  std::iota(ids.begin(), ids.end(), 0);
  std::vector<std::vector<int>> adjacency(numVertices());
  for (int v = 0; v < numVertices(); ++v) {
    for (int w : vertexNeighbors(v)) adjacency[v].push_back(w);
  }
  while (static_cast<int>(ids.size()) > defaults::kHierarchyTopSize) {
    // Independent set of low-degree vertices, greedily from the lowest
    // degree up (removes more vertices per level than index order).
    const int n = static_cast<int>(ids.size());
    std::vector<int> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](int x, int y) { return adjacency[x].size() < adjacency[y].size(); });
    std::vector<char> removed(n, 0);
    std::vector<char> blocked(n, 0);
    for (int i : order) {
      if (blocked[i] || static_cast<int>(adjacency[i].size()) > defaults::kHierarchyMaxRemovedDegree) continue;
      removed[i] = 1;
      for (int w : adjacency[i]) blocked[w] = 1;
    }
    std::vector<int> survivors;  // local indices in the current level
    for (int i = 0; i < n; ++i)
      if (!removed[i]) survivors.push_back(i);
    if (static_cast<int>(survivors.size()) == n) break;  // nothing removable
    // The current level's neighbours that the next level drops (the only
    // candidates a descent needs to check on this level).
    std::vector<int>& dropped_begin = levels_.empty() ? removed_begin_ : levels_.back().removed_begin;
    std::vector<int>& dropped = levels_.empty() ? removed_ : levels_.back().removed;
    dropped_begin.assign(1, 0);
    dropped.clear();
    for (int i = 0; i < n; ++i) {
      for (int w : adjacency[i])
        if (removed[w]) dropped.push_back(levels_.empty() ? ids[w] : w);
      dropped_begin.push_back(static_cast<int>(dropped.size()));
    }

    HierarchyLevel level;
    std::vector<std::vector<int>> next_adjacency;
    if (flat_) {
      // Subsets of a convex polygon's vertices stay in convex position; the
      // ring order of the survivors is their hull. Level 0's ring is face 0.
      std::vector<int> ring_pos(n, -1);
      if (levels_.empty()) {
        const IndexRange loop = faceVertices(0);
        for (int i = 0; i < loop.size(); ++i) ring_pos[loop[i]] = i;
        std::sort(survivors.begin(), survivors.end(), [&](int a, int b) { return ring_pos[a] < ring_pos[b]; });
      }
      const int m = static_cast<int>(survivors.size());
      next_adjacency.assign(m, {});
      for (int i = 0; i < m; ++i) {
        next_adjacency[i] = {(i + m - 1) % m, (i + 1) % m};
      }
      level.below = survivors;
    } else {
      std::vector<Eigen::Vector3d> points;
      for (int i : survivors) points.push_back(vertices_L_[ids[i]]);
      std::vector<int> kept;
      if (!hullAdjacency(points, &kept, &next_adjacency)) break;
      for (int k : kept) level.below.push_back(survivors[k]);
    }
    for (int b : level.below) level.vertex_ids.push_back(ids[b]);
    // Level 0 maps to the full polytope by original id.
    if (levels_.empty()) level.below = level.vertex_ids;
    level.adjacency_begin.push_back(0);
    for (const std::vector<int>& nbrs : next_adjacency) {
      level.adjacency.insert(level.adjacency.end(), nbrs.begin(), nbrs.end());
      level.adjacency_begin.push_back(static_cast<int>(level.adjacency.size()));
    }
    ids = level.vertex_ids;
    adjacency = std::move(next_adjacency);
    levels_.push_back(std::move(level));
  }
}

}  // namespace mddual
