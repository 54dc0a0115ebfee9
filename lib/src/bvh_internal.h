// Shared by the hierarchy's construction (bvh_build.cpp) and its volume
// tests and traversals (bvh.cpp, bvh_nearest.cpp): the volumes' padding, the
// magnitude of a node's coordinates, which scales the slack of the tests on
// it, and the traversals' per-thread scratch with the moving set's posed
// nodes.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "mddual/bvh.h"

namespace mddual::detail {

/// Volumes are grown by this fraction of their coordinates' magnitude so that
/// round-off in fitting them never leaves a point (or a child's volume)
/// outside. Dimensionless; far below any tolerance of the queries (1e-10).
inline constexpr double kPadRel = 1e-13;

/// A bound on the coordinates' absolute values of a box (or a point set)
/// about c with half extents h.
inline double magnitude(const Eigen::Vector3d& c, const Eigen::Vector3d& h) {
  return c.cwiseAbs().maxCoeff() + h.sum();
}

/// The magnitude of a node's coordinates (its volumes'), which scales the
/// slack of the tests on it.
inline double nodeScale(const Obb& obb, const Eigen::Vector3d& centre, double radius) {
  return std::max(magnitude(obb.centre_F, obb.half), centre.cwiseAbs().maxCoeff() + radius);
}

/// Posed volumes of a node of the moving set, cached per query. In two
/// stages (PosedNodes): the sphere, obb's centre and half extents and the
/// scale first; obb's axes and aabb_half only for a node whose sphere test
/// passes.
struct Posed {
  Obb obb;
  Eigen::Vector3d aabb_half;  ///< of the axis-aligned box around obb (second stage)
  Eigen::Vector3d centre;
  double radius = 0.0;
  double scale = 0.0;  ///< nodeScale of the posed volumes
};

/// Per-thread scratch of the traversals (one per nesting depth, so that a
/// callback may run another traversal).
struct Scratch {
  std::vector<std::uint64_t> stamp;      ///< generation whose sphere stage posed[k] holds
  std::vector<std::uint64_t> box_stamp;  ///< generation whose box stage posed[k] holds
  std::vector<Posed> posed;
  std::uint64_t generation = 0;
  std::vector<std::pair<int, int>> stack;
  struct Entry {
    double bound;
    int a, b;
    bool hull_done;
  };
  std::vector<Entry> heap;
};

/// The scratches of this thread (one per nesting depth) and the depth in use.
struct ScratchPool {
  std::vector<std::unique_ptr<Scratch>> scratch;
  std::size_t depth = 0;
};

/// One thread_local, reached once per lease: a lease is taken per traversal,
/// and on a sparse scene a state check's traversal is a single sphere test.
inline ScratchPool& scratchPool() {
  thread_local ScratchPool pool;
  return pool;
}

class ScratchLease {
 public:
  ScratchLease() : pool_(scratchPool()) {
    if (pool_.scratch.size() <= pool_.depth) pool_.scratch.push_back(std::make_unique<Scratch>());
    scratch_ = pool_.scratch[pool_.depth].get();
    ++pool_.depth;
  }
  ~ScratchLease() { --pool_.depth; }
  ScratchLease(const ScratchLease&) = delete;
  ScratchLease& operator=(const ScratchLease&) = delete;
  Scratch& operator*() const { return *scratch_; }
  Scratch* operator->() const { return scratch_; }

 private:
  ScratchPool& pool_;
  Scratch* scratch_;
};

/// The moving set's nodes posed in the fixed set's frame, computed on demand
/// in two stages: sphere(n) (what the sphere tests and the slack need) and
/// box(n) (the oriented box's axes and the axis-aligned box around it: the
/// 3x3 product is most of the posing, and on the small scenes of the planning
/// benchmark most state checks end at the roots' spheres).
class PosedNodes {
 public:
  PosedNodes(const Bvh& b, const Eigen::Isometry3d& X_AB, double margin, Scratch& s)
      : b_(b), X_AB_(X_AB), margin_(margin), s_(s) {
    if (s_.stamp.size() < static_cast<std::size_t>(b.numNodes())) {
      s_.stamp.assign(static_cast<std::size_t>(b.numNodes()), 0);
      s_.box_stamp.assign(static_cast<std::size_t>(b.numNodes()), 0);
      s_.posed.resize(static_cast<std::size_t>(b.numNodes()));
    }
    ++s_.generation;
  }
  /// The sphere (centre, radius), obb.centre_F, obb.half and scale.
  const Posed& sphere(int n) {
    const auto k = static_cast<std::size_t>(n);
    Posed& p = s_.posed[k];
    if (s_.stamp[k] != s_.generation) {
      const Bvh::Node& node = b_.node(n);
      p.obb.centre_F = X_AB_ * node.obb.centre_F;
      p.obb.half = node.obb.half.array() + margin_;
      p.centre = X_AB_ * node.centre;
      p.radius = node.radius + margin_;
      p.scale = nodeScale(p.obb, p.centre, p.radius);
      s_.stamp[k] = s_.generation;
    }
    return p;
  }
  /// Everything: sphere(n) and obb.axes_F and aabb_half (Obb::transformed's box).
  const Posed& box(int n) {
    const auto k = static_cast<std::size_t>(n);
    Posed& p = s_.posed[k];
    if (s_.box_stamp[k] != s_.generation) {
      sphere(n);
      p.obb.axes_F = X_AB_.linear() * b_.node(n).obb.axes_F;
      p.aabb_half = p.obb.aabbHalf();
      s_.box_stamp[k] = s_.generation;
    }
    return p;
  }

 private:
  const Bvh& b_;
  const Eigen::Isometry3d& X_AB_;
  double margin_;
  Scratch& s_;
};

}  // namespace mddual::detail
