#include "mddual/scene/scene.h"

#include <algorithm>
#include <numeric>

namespace mddual::scene {
namespace {

/// Leaves hold at most this many boxes (a few boxes are cheaper to scan than
/// to descend into).
constexpr int kLeafSize = 4;

}  // namespace

Piece Piece::make(ConvexPolytope polytope, PieceKind kind, std::string origin) {
  Piece p;
  p.polytope = std::move(polytope);
  p.kind = kind;
  p.origin = std::move(origin);
  p.box.setEmpty();
  for (const Eigen::Vector3d& v : p.polytope.vertices()) p.box.extend(v);
  p.centre = p.polytope.centroid();
  p.radius = p.polytope.radius();
  return p;
}

AabbTree::AabbTree(const std::vector<Eigen::AlignedBox3d>& boxes) : boxes_(boxes), order_(boxes.size()) {
  std::iota(order_.begin(), order_.end(), 0);
  if (!boxes_.empty()) {
    nodes_.reserve(2 * boxes_.size());
    build(0, static_cast<int>(boxes_.size()));
  }
}

int AabbTree::build(int first, int count) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::AlignedBox3d box;
  box.setEmpty();
  for (int i = first; i < first + count; ++i) box.extend(boxes_[order_[i]]);
  nodes_[index].box = box;
  if (count <= kLeafSize) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  // Median split of the box centres along the longest axis.
  int axis = 0;
  box.sizes().maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                   [&](int a, int b) { return boxes_[a].center()[axis] < boxes_[b].center()[axis]; });
  const int left = build(first, half);
  const int right = build(first + half, count - half);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

void AabbTree::query(const Eigen::AlignedBox3d& query, std::vector<int>* out) const {
  if (nodes_.empty() || query.isEmpty()) return;
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!node.box.intersects(query)) continue;
    if (node.left < 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        if (boxes_[order_[i]].intersects(query)) out->push_back(order_[i]);
      }
      continue;
    }
    stack[top++] = node.left;
    stack[top++] = node.right;
  }
}

}  // namespace mddual::scene

namespace mddual::scene {

RigidBody::RigidBody(std::vector<Piece> pieces, std::string name) : pieces_(std::move(pieces)), name_(std::move(name)) {
  if (pieces_.empty()) throw SceneError("robot '" + name_ + "': no collision geometry (no pieces)");
  box_.setEmpty();
  for (const Piece& p : pieces_) {
    box_.extend(p.box);
    for (const Eigen::Vector3d& v : p.polytope.vertices()) radius_ = std::max(radius_, v.norm());
  }
}

World::World(std::vector<Piece> pieces, std::string name) : pieces_(std::move(pieces)), name_(std::move(name)) {
  box_.setEmpty();
  std::vector<Eigen::AlignedBox3d> boxes;
  boxes.reserve(pieces_.size());
  for (const Piece& p : pieces_) {
    box_.extend(p.box);
    boxes.push_back(p.box);
  }
  tree_ = AabbTree(boxes);
}

Eigen::AlignedBox3d transformedBox(const Eigen::AlignedBox3d& box, const Eigen::Isometry3d& X_WF) {
  // Arvo's method: the extent along each world axis is |R| times the half sizes.
  const Eigen::Vector3d centre = X_WF * box.center();
  const Eigen::Vector3d half = X_WF.linear().cwiseAbs() * (0.5 * box.sizes());
  return Eigen::AlignedBox3d(centre - half, centre + half);
}

}  // namespace mddual::scene
