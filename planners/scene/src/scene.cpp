#include "mddual/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "mddual/error.h"

namespace mddual::scene {
namespace {

/// Leaves hold at most this many boxes (a few boxes are cheaper to scan than
/// to descend into).
constexpr int kLeafSize = 4;
/// Smallest overflow (plus stale tree entries) that triggers a rebuild:
/// scanning a few boxes costs less than rebuilding a small tree.
constexpr int kMinOverflow = 16;

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

std::vector<ConvexPolytope> clusterHulls(const std::vector<Piece>& pieces, int max_per_cluster) {
  if (max_per_cluster < 1) throw InvalidInputError("clusterHulls: max_per_cluster must be >= 1");
  if (pieces.empty()) return {};
  std::vector<int> order(pieces.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::vector<ConvexPolytope> out;
  const auto split = [&](auto&& self, std::size_t begin, std::size_t end) -> void {
    if (end - begin <= static_cast<std::size_t>(max_per_cluster)) {
      std::vector<Eigen::Vector3d> points;
      for (std::size_t i = begin; i < end; ++i) {
        const auto& v = pieces[static_cast<std::size_t>(order[i])].polytope.vertices();
        points.insert(points.end(), v.begin(), v.end());
      }
      out.push_back(ConvexPolytope::fromPoints(points));
      return;
    }
    Eigen::AlignedBox3d box;
    for (std::size_t i = begin; i < end; ++i) box.extend(pieces[static_cast<std::size_t>(order[i])].centre);
    int axis = 0;
    box.diagonal().maxCoeff(&axis);
    const std::size_t mid = begin + (end - begin) / 2;
    std::nth_element(
        order.begin() + static_cast<std::ptrdiff_t>(begin), order.begin() + static_cast<std::ptrdiff_t>(mid),
        order.begin() + static_cast<std::ptrdiff_t>(end), [&](int x, int y) {
          return pieces[static_cast<std::size_t>(x)].centre[axis] < pieces[static_cast<std::size_t>(y)].centre[axis];
        });
    self(self, begin, mid);
    self(self, mid, end);
  };
  split(split, 0, order.size());
  return out;
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
  id_of_.resize(pieces_.size());
  std::iota(id_of_.begin(), id_of_.end(), 0);
  index_of_ = id_of_;
  in_tree_.assign(pieces_.size(), 1);
  rebuild();
  rebuilds_ = 0;
}

int World::overflowLimit(int n) {
  return std::max(kMinOverflow, static_cast<int>(2.0 * std::sqrt(static_cast<double>(n))));
}

void World::recomputeBox() {
  box_.setEmpty();
  for (const Piece& p : pieces_) box_.extend(p.box);
}

void World::rebuild() {
  std::vector<Eigen::AlignedBox3d> boxes;
  boxes.reserve(pieces_.size());
  tree_ids_ = id_of_;
  for (const Piece& p : pieces_) boxes.push_back(p.box);
  for (const int id : id_of_) in_tree_[static_cast<std::size_t>(id)] = 1;
  tree_ = AabbTree(boxes);
  overflow_.clear();
  stale_ = 0;
  ++rebuilds_;
  recomputeBox();
}

void World::maybeRebuild() {
  if (static_cast<int>(overflow_.size()) + stale_ > overflowLimit(static_cast<int>(pieces_.size()))) {
    rebuild();
  } else {
    recomputeBox();
  }
}

void World::candidates(const Eigen::AlignedBox3d& query_W, std::vector<int>* out) const {
  const std::size_t first = out->size();
  tree_.query(query_W, out);
  std::size_t kept = first;
  for (std::size_t k = first; k < out->size(); ++k) {
    const int id = tree_ids_[static_cast<std::size_t>((*out)[k])];
    if (!in_tree_[static_cast<std::size_t>(id)]) continue;  // removed, or moved into the overflow
    (*out)[kept++] = index_of_[static_cast<std::size_t>(id)];
  }
  out->resize(kept);
  if (query_W.isEmpty()) return;
  for (const int id : overflow_) {
    const int index = index_of_[static_cast<std::size_t>(id)];
    if (pieces_[static_cast<std::size_t>(index)].box.intersects(query_W)) out->push_back(index);
  }
}

bool World::hasPiece(int id) const {
  return id >= 0 && id < idLimit() && index_of_[static_cast<std::size_t>(id)] >= 0;
}

int World::requireId(int id, const char* what) const {
  if (!hasPiece(id)) {
    throw InvalidInputError("World '" + name_ + "': " + what + ": no piece with id " + std::to_string(id) +
                            (id >= 0 && id < idLimit() ? " (it was removed)" : ""));
  }
  return index_of_[static_cast<std::size_t>(id)];
}

int World::indexOf(int id) const {
  return requireId(id, "indexOf");
}

Eigen::Isometry3d World::piecePose(int id) const {
  requireId(id, "piecePose");
  const auto it = moved_.find(id);
  return it == moved_.end() ? Eigen::Isometry3d::Identity() : it->second.X_WP;
}

int World::addPiece(Piece piece) {
  // A default-made piece has no polytope; the derived fields (box, centre,
  // radius) are recomputed so that a hand-made Piece cannot give the broad
  // phase a box that disagrees with its polytope.
  if (piece.polytope.numVertices() == 0) {
    throw SceneError("World::addPiece: the piece '" + piece.origin + "' has no polytope (no vertices)");
  }
  piece = Piece::make(std::move(piece.polytope), piece.kind, std::move(piece.origin));
  const int id = idLimit();
  const int index = static_cast<int>(pieces_.size());
  pieces_.push_back(std::move(piece));
  id_of_.push_back(id);
  index_of_.push_back(index);
  in_tree_.push_back(0);
  overflow_.push_back(id);
  maybeRebuild();
  return id;
}

void World::removePiece(int id) {
  const int index = requireId(id, "removePiece");
  const int last = static_cast<int>(pieces_.size()) - 1;
  if (index != last) {
    const int last_id = id_of_[static_cast<std::size_t>(last)];
    pieces_[static_cast<std::size_t>(index)] = std::move(pieces_.back());
    id_of_[static_cast<std::size_t>(index)] = last_id;
    index_of_[static_cast<std::size_t>(last_id)] = index;
  }
  pieces_.pop_back();
  id_of_.pop_back();
  index_of_[static_cast<std::size_t>(id)] = -1;
  if (in_tree_[static_cast<std::size_t>(id)]) {
    in_tree_[static_cast<std::size_t>(id)] = 0;
    ++stale_;
  } else {
    overflow_.erase(std::find(overflow_.begin(), overflow_.end(), id));
  }
  moved_.erase(id);
  maybeRebuild();
}

void World::movePiece(int id, const Eigen::Isometry3d& X_WP) {
  const int index = requireId(id, "movePiece");
  if (!X_WP.matrix().allFinite()) {
    throw InvalidInputError("World '" + name_ + "': movePiece: the pose of piece " + std::to_string(id) +
                            " has a non-finite entry");
  }
  // "Moved rigidly": a scaled or reflected pose would change the piece's shape.
  const Eigen::Matrix3d& R = X_WP.linear();
  if (!((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-9 && R.determinant() > 0.0)) {
    throw InvalidInputError("World '" + name_ + "': movePiece: the pose of piece " + std::to_string(id) +
                            " is not a rigid transform (its rotation part must be orthonormal with determinant 1)");
  }
  Piece& piece = pieces_[static_cast<std::size_t>(index)];
  const auto it = moved_.find(id);
  const ConvexPolytope& reference = it == moved_.end() ? piece.polytope : it->second.reference;
  std::vector<Eigen::Vector3d> points;
  points.reserve(reference.vertices().size());
  for (const Eigen::Vector3d& v : reference.vertices()) points.push_back(X_WP * v);
  Piece moved;
  try {
    moved = Piece::make(ConvexPolytope::fromPoints(points), piece.kind, piece.origin);
  } catch (const Error& e) {
    throw SceneError("World '" + name_ + "': movePiece: piece " + std::to_string(id) + " (" + piece.origin +
                     "): cannot build the moved polytope: " + e.what());
  }
  // Committed from here on (nothing below throws but allocation).
  if (it == moved_.end()) {
    Moved m;
    m.reference = std::move(piece.polytope);
    m.X_WP = X_WP;
    moved_.emplace(id, std::move(m));
  } else {
    it->second.X_WP = X_WP;
  }
  piece = std::move(moved);
  if (in_tree_[static_cast<std::size_t>(id)]) {
    in_tree_[static_cast<std::size_t>(id)] = 0;
    ++stale_;
    overflow_.push_back(id);
  }
  maybeRebuild();
}

Eigen::AlignedBox3d transformedBox(const Eigen::AlignedBox3d& box, const Eigen::Isometry3d& X_WF) {
  // Arvo's method: the extent along each world axis is |R| times the half sizes.
  const Eigen::Vector3d centre = X_WF * box.center();
  const Eigen::Vector3d half = X_WF.linear().cwiseAbs() * (0.5 * box.sizes());
  return Eigen::AlignedBox3d(centre - half, centre + half);
}

}  // namespace mddual::scene
