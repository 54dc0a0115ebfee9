// Bvh construction: a top-down median split of the pieces' centres, each
// node's volumes (oriented box, sphere, axis-aligned box and, for small
// nodes, the hull) fitted to its pieces' points, so that they contain the
// children's.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "bvh_internal.h"
#include "constants.h"
#include "mddual/bvh.h"
#include "mddual/error.h"

namespace mddual {
namespace {

using detail::kInf;
using detail::kPadRel;
using detail::magnitude;
using detail::nodeScale;

/// The OBB of a node minimises (h_x + s)(h_y + s)(h_z + s), s = this fraction
/// of its longest half extent (so that flat boxes compare by area).
constexpr double kObbScoreFlatRel = 1e-3;

/// Orthonormal, right-handed columns from `m` (Gram-Schmidt); false when m is
/// not close to a rotation or reflection.
bool orthonormalise(Eigen::Matrix3d* m) {
  Eigen::Vector3d a = m->col(0), b = m->col(1);
  if (!a.allFinite() || !b.allFinite() || a.norm() < 0.5 || b.norm() < 0.5) return false;
  a.normalize();
  b -= b.dot(a) * a;
  if (b.norm() < 0.5) return false;
  b.normalize();
  m->col(0) = a;
  m->col(1) = b;
  m->col(2) = a.cross(b);
  return true;
}

/// The box with the given axes that holds `points` (grown by the pad).
Obb fitObb(const std::vector<Eigen::Vector3d>& points, const Eigen::Matrix3d& axes) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInf), hi = Eigen::Vector3d::Constant(-kInf);
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d y = axes.transpose() * p;
    lo = lo.cwiseMin(y);
    hi = hi.cwiseMax(y);
  }
  Obb b;
  b.axes_F = axes;
  b.centre_F = axes * (0.5 * (lo + hi));
  b.half = 0.5 * (hi - lo);
  b.half.array() += kPadRel * (magnitude(b.centre_F, b.half) + lo.cwiseAbs().maxCoeff() + hi.cwiseAbs().maxCoeff());
  return b;
}

double obbScore(const Obb& b) {
  const double s = kObbScoreFlatRel * b.half.maxCoeff();
  return (b.half.x() + s) * (b.half.y() + s) * (b.half.z() + s);
}

/// First and second moments of a point set (for the principal axes).
struct Moments {
  double n = 0.0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  void add(const Eigen::Vector3d& p) {
    n += 1.0;
    sum += p;
    outer += p * p.transpose();
  }
  void add(const Moments& o) {
    n += o.n;
    sum += o.sum;
    outer += o.outer;
  }
  /// Principal axes (eigenvectors of the covariance); false when degenerate.
  bool axes(Eigen::Matrix3d* out) const {
    if (n < 1.0) return false;
    const Eigen::Vector3d mean = sum / n;
    const Eigen::Matrix3d cov = outer / n - mean * mean.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    eig.computeDirect(cov);
    if (eig.info() != Eigen::Success) return false;
    *out = eig.eigenvectors();
    return orthonormalise(out);
  }
};

/// The best-scoring box over the candidate axes.
Obb bestObb(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Matrix3d>& candidates) {
  Obb best = fitObb(points, Eigen::Matrix3d::Identity());
  double best_score = obbScore(best);
  for (const Eigen::Matrix3d& axes : candidates) {
    const Obb b = fitObb(points, axes);
    const double s = obbScore(b);
    if (s < best_score) {
      best = b;
      best_score = s;
    }
  }
  return best;
}

/// Smallest sphere holding spheres (c1, r1) and (c2, r2).
void encloseSpheres(const Eigen::Vector3d& c1, double r1, const Eigen::Vector3d& c2, double r2, Eigen::Vector3d* c,
                    double* r) {
  const double d = (c2 - c1).norm();
  if (d + r2 <= r1) {
    *c = c1;
    *r = r1;
  } else if (d + r1 <= r2) {
    *c = c2;
    *r = r2;
  } else {
    *r = 0.5 * (d + r1 + r2);
    *c = c1 + (*r - r1) / d * (c2 - c1);
  }
}

}  // namespace

// ---- Construction --------------------------------------------------------------------

Bvh::Bvh(const std::vector<std::vector<Eigen::Vector3d>>& pieces_S, const BvhOptions& options) {
  if (options.hull_max_pieces < 0) {
    throw InvalidInputError("Bvh: hull_max_pieces is negative (" + std::to_string(options.hull_max_pieces) + ")");
  }
  const int n = static_cast<int>(pieces_S.size());
  std::vector<std::vector<Eigen::Vector3d>> points = pieces_S;
  std::vector<Eigen::Vector3d> centres(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const std::vector<Eigen::Vector3d>& p = points[static_cast<std::size_t>(k)];
    if (p.empty()) throw InvalidInputError("Bvh: piece " + std::to_string(k) + " has no points");
    Eigen::AlignedBox3d box;
    for (std::size_t v = 0; v < p.size(); ++v) {
      if (!p[v].allFinite()) {
        throw InvalidInputError("Bvh: piece " + std::to_string(k) + ", point " + std::to_string(v) +
                                " has a non-finite coordinate");
      }
      box.extend(p[v]);
    }
    centres[static_cast<std::size_t>(k)] = box.center();
  }
  if (n == 0) return;
  order_.resize(static_cast<std::size_t>(n));
  std::iota(order_.begin(), order_.end(), 0);
  leaf_of_.assign(static_cast<std::size_t>(n), -1);
  nodes_.reserve(static_cast<std::size_t>(2 * n - 1));
  height_ = 0;
  build(points, centres, 0, n, 0, options);
}

Bvh Bvh::fromPolytopes(const std::vector<const ConvexPolytope*>& polytopes, const std::vector<Eigen::Isometry3d>& X_SP,
                       const BvhOptions& options) {
  if (!X_SP.empty() && X_SP.size() != polytopes.size()) {
    throw InvalidInputError("Bvh::fromPolytopes: " + std::to_string(X_SP.size()) + " poses for " +
                            std::to_string(polytopes.size()) + " polytopes");
  }
  std::vector<std::vector<Eigen::Vector3d>> points(polytopes.size());
  for (std::size_t k = 0; k < polytopes.size(); ++k) {
    if (!polytopes[k]) throw InvalidInputError("Bvh::fromPolytopes: polytope " + std::to_string(k) + " is null");
    points[k] = polytopes[k]->vertices();
    if (!X_SP.empty()) {
      for (Eigen::Vector3d& p : points[k]) p = X_SP[k] * p;
    }
  }
  return Bvh(points, options);
}

const ConvexPolytope* Bvh::hull(int n) const {
  const int h = node(n).hull;
  return h < 0 ? nullptr : hulls_[static_cast<std::size_t>(h)].get();
}

int Bvh::build(std::vector<std::vector<Eigen::Vector3d>>& points, std::vector<Eigen::Vector3d>& centres, int first,
               int count, int depth, const BvhOptions& options) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  height_ = std::max(height_, depth);
  const auto at = [&](int k) { return order_[static_cast<std::size_t>(k)]; };
  if (count == 1) {
    const int piece = at(first);
    const std::vector<Eigen::Vector3d>& p = points[static_cast<std::size_t>(piece)];
    Node leaf;
    leaf.first = first;
    leaf.count = 1;
    Moments m;
    for (const Eigen::Vector3d& v : p) {
      leaf.box.extend(v);
      m.add(v);
      leaf.max_norm = std::max(leaf.max_norm, v.norm());
    }
    std::vector<Eigen::Matrix3d> candidates;
    Eigen::Matrix3d pca;
    if (m.axes(&pca)) candidates.push_back(pca);
    leaf.obb = bestObb(p, candidates);
    // Sphere about the box centre or the mean, whichever is smaller.
    double best = kInf;
    for (const Eigen::Vector3d& c : {Eigen::Vector3d(leaf.box.center()), Eigen::Vector3d(m.sum / m.n)}) {
      double r = 0.0;
      for (const Eigen::Vector3d& v : p) r = std::max(r, (v - c).norm());
      if (r < best) {
        best = r;
        leaf.centre = c;
      }
    }
    const double pad = kPadRel * (leaf.box.max().cwiseAbs().maxCoeff() + leaf.box.min().cwiseAbs().maxCoeff());
    leaf.radius = best + pad;
    leaf.box.min().array() -= pad;
    leaf.box.max().array() += pad;
    leaf.max_norm += pad;
    leaf.scale = std::max({nodeScale(leaf.obb, leaf.centre, leaf.radius), leaf.box.min().cwiseAbs().maxCoeff(),
                           leaf.box.max().cwiseAbs().maxCoeff()});
    if (p.size() == 3) {
      leaf.triangle = static_cast<int>(triangles_.size());
      triangles_.push_back({p[0], p[1], p[2]});
    }
    nodes_[static_cast<std::size_t>(index)] = leaf;
    leaf_of_[static_cast<std::size_t>(piece)] = index;
    return index;
  }
  // Split at the median of the pieces' centres along the longest axis of
  // their bounds (equal halves when they all coincide).
  Eigen::AlignedBox3d cbox;
  for (int k = first; k < first + count; ++k) cbox.extend(centres[static_cast<std::size_t>(at(k))]);
  int axis = 0;
  cbox.sizes().maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                   [&](int x, int y) {
                     const double cx = centres[static_cast<std::size_t>(x)][axis];
                     const double cy = centres[static_cast<std::size_t>(y)][axis];
                     return cx < cy || (cx == cy && x < y);
                   });
  const int left = build(points, centres, first, half, depth + 1, options);
  const int right = build(points, centres, first + half, count - half, depth + 1, options);
  const Node& l = nodes_[static_cast<std::size_t>(left)];
  const Node& r = nodes_[static_cast<std::size_t>(right)];
  Node inner;
  inner.left = left;
  inner.right = right;
  inner.first = first;
  inner.count = count;
  inner.box = l.box.merged(r.box);
  inner.max_norm = std::max(l.max_norm, r.max_norm);
  // The volumes are fitted to the pieces' points (tighter than volumes
  // around the children's volumes): the oriented box over candidate axes
  // (the points' principal axes, the children's axes, the frame's axes), the
  // sphere about the box centre or the mean, or around the children's spheres,
  // whichever is smallest.
  std::vector<Eigen::Vector3d> all;
  Moments m;
  for (int k = first; k < first + count; ++k) {
    for (const Eigen::Vector3d& v : points[static_cast<std::size_t>(at(k))]) {
      all.push_back(v);
      m.add(v);
    }
  }
  std::vector<Eigen::Matrix3d> candidates{l.obb.axes_F, r.obb.axes_F};
  Eigen::Matrix3d pca;
  if (m.axes(&pca)) candidates.push_back(pca);
  inner.obb = bestObb(all, candidates);
  encloseSpheres(l.centre, l.radius, r.centre, r.radius, &inner.centre, &inner.radius);
  for (const Eigen::Vector3d& c : {inner.obb.centre_F, Eigen::Vector3d(m.sum / m.n)}) {
    double radius = 0.0;
    for (const Eigen::Vector3d& v : all) radius = std::max(radius, (v - c).norm());
    if (radius < inner.radius) {
      inner.radius = radius;
      inner.centre = c;
    }
  }
  inner.radius += kPadRel * (inner.centre.cwiseAbs().maxCoeff() + inner.radius);
  inner.scale = std::max({nodeScale(inner.obb, inner.centre, inner.radius), inner.box.min().cwiseAbs().maxCoeff(),
                          inner.box.max().cwiseAbs().maxCoeff()});
  if (options.hull_max_pieces >= 2 && count <= options.hull_max_pieces) {
    try {
      hulls_.push_back(std::make_shared<const ConvexPolytope>(ConvexPolytope::fromPoints(all)));
      inner.hull = static_cast<int>(hulls_.size()) - 1;
    } catch (const Error&) {
      inner.hull = -1;  // no hull for this node: its boxes bound it
    }
  }
  nodes_[static_cast<std::size_t>(index)] = inner;
  return index;
}

}  // namespace mddual
