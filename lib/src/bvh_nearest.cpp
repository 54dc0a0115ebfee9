// nearestPair: branch and bound on the smallest signed distance between two
// hierarchies (the clearance queries' traversal), nearest node pair first.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <vector>

#include "bvh_internal.h"
#include "mddual/bvh.h"
#include "mddual/error.h"

namespace mddual {
namespace {

/// A node pair waiting in the queue with its lower bound.
struct NearestEntry {
  double bound;
  int a, b;
};

bool farther(const NearestEntry& x, const NearestEntry& y) {
  return x.bound > y.bound;
}

/// A node of b posed in a's frame: its sphere's centre, its oriented box's
/// centre and the half extents of the axis-aligned box around that box.
struct PosedB {
  Eigen::Vector3d centre, box_centre, box_half;
};

/// The work space of one query: the queue, and b's nodes posed once per
/// query (stamp[n] == generation: posed[n] holds node n at this query's
/// pose), both kept for the thread's next query at the same depth (no
/// allocation per query once they have grown).
struct NearestWork {
  std::vector<NearestEntry> heap;
  std::vector<std::uint64_t> stamp;
  std::vector<PosedB> posed;
  std::uint64_t generation = 0;
};

/// This thread's work spaces, one per nesting depth (a leaf callback may run
/// another nearestPair); a deque, so that a deeper one added does not move
/// the ones in use.
struct NearestPool {
  std::deque<NearestWork> works;
  std::size_t depth = 0;
};

class NearestLease {
 public:
  explicit NearestLease(int b_nodes) : pool_(pool()) {
    if (pool_.works.size() <= pool_.depth) pool_.works.emplace_back();
    work_ = &pool_.works[pool_.depth];
    ++pool_.depth;
    work_->heap.clear();
    ++work_->generation;  // starts at 1: a stamp of 0 is never current
    const std::size_t n = static_cast<std::size_t>(b_nodes);
    if (work_->stamp.size() < n) {
      work_->stamp.resize(n, 0);
      work_->posed.resize(n);
    }
  }
  ~NearestLease() { --pool_.depth; }
  NearestLease(const NearestLease&) = delete;
  NearestLease& operator=(const NearestLease&) = delete;
  NearestWork& operator*() const { return *work_; }

 private:
  static NearestPool& pool() {
    thread_local NearestPool p;
    return p;
  }
  NearestPool& pool_;
  NearestWork* work_;
};

}  // namespace

NearestHit nearestPair(const Bvh& a, const Bvh& b, const Eigen::Isometry3d& X_AB, NearestLeafFn leaf, double upper) {
  // 1. Arguments. A NaN pose would give NaN bounds, which prune nothing and
  //    order nothing: refused, as by the other traversals (finiteness only).
  requireFinitePose(X_AB, "pose X_AB", "nearestPair");
  if (std::isnan(upper)) throw InvalidInputError("nearestPair: upper is NaN");
  NearestHit hit;
  if (a.empty() || b.empty()) return hit;
  double best = upper;
  const NearestLease lease(b.numNodes());
  NearestWork& work = *lease;
  // 2. Bounds: the larger of the spheres' gap and the boxes' (a's box and
  //    the box around b's posed oriented box), each a lower bound of the
  //    signed distance of any two convex pieces inside (bvh.h); the boxes'
  //    only when the spheres' does not prune the pair. b's nodes are posed
  //    once per query (the 3x3 product of the box's axes was most of a
  //    bound: sceneDistance, 2,000 random states per example scene, the
  //    primitives 2.57 -> 2.02 us, the mesh scene 39.7 -> 36.4, the trap 446
  //    -> 411).
  const auto posed = [&](int nb) -> const PosedB& {
    const std::size_t k = static_cast<std::size_t>(nb);
    PosedB& p = work.posed[k];
    if (work.stamp[k] != work.generation) {
      work.stamp[k] = work.generation;
      const Bvh::Node& B = b.node(nb);
      p.centre = X_AB * B.centre;
      p.box_centre = X_AB * B.obb.centre_F;
      p.box_half = (X_AB.linear() * B.obb.axes_F).cwiseAbs() * B.obb.half;
    }
    return p;
  };
  const double pose_scale = X_AB.translation().cwiseAbs().maxCoeff();
  const auto bound = [&](int na, int nb) {
    ++hit.node_pairs;
    const Bvh::Node& A = a.node(na);
    const Bvh::Node& B = b.node(nb);
    const PosedB& p = posed(nb);
    const double slack = kBvhSlackRel * (A.scale + B.scale + pose_scale);
    const double spheres = (A.centre - p.centre).norm() - A.radius - B.radius;
    if (spheres - slack >= best) return spheres - slack;  // pruned already
    const Eigen::Vector3d gap =
        (A.box.min() - p.box_centre - p.box_half).cwiseMax(p.box_centre - p.box_half - A.box.max());
    const double boxes = (gap.array() <= 0.0).all() ? gap.maxCoeff() : gap.cwiseMax(0.0).norm();
    return std::max(spheres, boxes) - slack;
  };
  // 3. Nearest first: a heap on the bounds (NearestWork::heap). Depth first with
  //    the nearer child pair first instead (sceneDistance on 2,000 random
  //    states of the example scenes): 1.3x to 2.2x the pair queries, no
  //    faster anywhere.
  std::vector<NearestEntry>& heap = work.heap;
  const auto push = [&](int na, int nb) {
    const double lb = bound(na, nb);
    if (lb < best) {
      heap.push_back(NearestEntry{lb, na, nb});
      std::push_heap(heap.begin(), heap.end(), farther);
    }
  };
  push(a.root(), b.root());
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), farther);
    const NearestEntry e = heap.back();
    heap.pop_back();
    if (e.bound >= best) break;  // every pair left is bounded below by e.bound
    const Bvh::Node& A = a.node(e.a);
    const Bvh::Node& B = b.node(e.b);
    if (A.isLeaf() && B.isLeaf()) {
      const int pa = a.leafPiece(e.a), pb = b.leafPiece(e.b);
      const double v = leaf(pa, pb, best);
      if (v < best) {
        best = v;
        hit.value = v;
        hit.piece_a = pa;
        hit.piece_b = pb;
      }
      continue;
    }
    // 4. Split the larger node that has children.
    const bool split_a = B.isLeaf() || (!A.isLeaf() && A.radius >= B.radius);
    if (split_a) {
      push(A.left, e.b);
      push(A.right, e.b);
    } else {
      push(e.a, B.left);
      push(e.a, B.right);
    }
  }
  return hit;
}

}  // namespace mddual
