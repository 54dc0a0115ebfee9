#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "checker_arguments.h"
#include "mddual/error.h"
#include "mddual/planning/hull_cast_checkers.h"

static_assert(sizeof(btScalar) == sizeof(double), "mddual_hull_cast needs Bullet's double-precision build");

namespace mddual::planning {
namespace ob = ompl::base;

namespace {

/// A Bullet hull of `points` (world frame) kept in its own frame: the points
/// relative to their bounding box's centre, which the returned transform
/// places back (as the core's local frames do: far from the origin the hull
/// stays as well conditioned as at the origin). Margin 0: Bullet's default
/// 0.04 pad would grow every shape.
struct LocalHull {
  btConvexHullShape shape;
  btTransform X_W = btTransform::getIdentity();
  Eigen::AlignedBox3d box;  ///< of the points (world frame)

  explicit LocalHull(const std::vector<Eigen::Vector3d>& points) {
    for (const Eigen::Vector3d& p : points) box.extend(p);
    const Eigen::Vector3d c = box.center();
    for (const Eigen::Vector3d& p : points) {
      const Eigen::Vector3d q = p - c;
      shape.addPoint(btVector3(q.x(), q.y(), q.z()), false);
    }
    shape.recalcLocalAabb();
    shape.setMargin(0.0);
    X_W.setOrigin(btVector3(c.x(), c.y(), c.z()));
  }
};

/// Whether two hulls overlap or touch (Bullet's GJK/EPA).
bool overlap(const LocalHull& a, const LocalHull& b) {
  btGjkEpaSolver2::sResults result;
  const btVector3 guess = b.X_W.getOrigin() - a.X_W.getOrigin();
  return btGjkEpaSolver2::Penetration(&a.shape, a.X_W, &b.shape, b.X_W, guess, result);
}

/// Tesseract's continuous motion validator, the peer modelled here: the edge
/// s1 -> s2 is cut into the space's validSegmentCount(s1, s2) segments (OMPL's
/// resolution, as the discrete validator; one for kWholeEdge); segment i is valid when its end
/// state is valid (si's state validity checker: FCL, self pairs included) and
/// `collides(start, end)` (the cast between its end states) is false. On the
/// first failing segment lastValid (when given) is its start state and
/// fraction; an end outside the bounds fails the edge at (s1, 0). Returns
/// whether every segment is valid.
template <class Cast>
bool castSegments(const ob::SpaceInformation& si, CastSegments segments, const ob::State* s1, const ob::State* s2,
                  const Cast& collides, std::pair<ob::State*, double>* lastValid) {
  if (!si.satisfiesBounds(s1) || !si.satisfiesBounds(s2)) {
    if (lastValid) {
      if (lastValid->first) si.copyState(lastValid->first, s1);
      lastValid->second = 0.0;
    }
    return false;
  }
  const ob::StateSpace& space = *si.getStateSpace();
  const unsigned n = segments == CastSegments::kWholeEdge ? 1u : std::max(1u, space.validSegmentCount(s1, s2));
  ob::State* start = si.allocState();
  ob::State* end = si.allocState();
  si.copyState(start, s1);
  bool valid = true;
  unsigned i = 1;
  for (; i <= n; ++i) {
    if (i == n) {
      si.copyState(end, s2);
    } else {
      space.interpolate(s1, s2, static_cast<double>(i) / n, end);
    }
    if (!si.isValid(end) || collides(start, end)) {
      valid = false;
      break;
    }
    std::swap(start, end);
  }
  if (!valid && lastValid) {
    lastValid->second = static_cast<double>(i - 1) / n;
    if (lastValid->first) si.copyState(lastValid->first, start);
  }
  si.freeState(start);
  si.freeState(end);
  return valid;
}

/// A piece swept between two poses: its vertices at both (world frame) and
/// their box, with the Bullet hull made only when a broad phase candidate
/// needs it (most swept pieces meet no world box, and a hull of hundreds of
/// points costs far more than its box).
struct SweptPiece {
  std::vector<Eigen::Vector3d> points;
  Eigen::AlignedBox3d box;
  std::unique_ptr<LocalHull> hull;

  SweptPiece(const std::vector<Eigen::Vector3d>& vertices, const Eigen::Isometry3d& X_a, const Eigen::Isometry3d& X_b) {
    points.reserve(2 * vertices.size());
    for (const Eigen::Vector3d& v : vertices) points.push_back(X_a * v);
    for (const Eigen::Vector3d& v : vertices) points.push_back(X_b * v);
    for (const Eigen::Vector3d& p : points) box.extend(p);
  }
  const LocalHull& shape() {
    if (!hull) hull = std::make_unique<LocalHull>(points);
    return *hull;
  }
};

}  // namespace

struct HullCastScene::Impl {
  std::shared_ptr<const scene::RigidBody> robot;
  std::shared_ptr<const scene::World> world;
  std::vector<std::unique_ptr<LocalHull>> world_hulls;  ///< one per world piece, same index
};

HullCastScene::HullCastScene(std::shared_ptr<const scene::RigidBody> robot, std::shared_ptr<const scene::World> world)
    : impl_(std::make_unique<Impl>()) {
  if (!robot) throw InvalidInputError("HullCastScene: the robot is null");
  if (!world) throw InvalidInputError("HullCastScene: the world is null");
  impl_->robot = std::move(robot);
  impl_->world = std::move(world);
  for (const scene::Piece& piece : impl_->world->pieces()) {
    impl_->world_hulls.push_back(std::make_unique<LocalHull>(piece.polytope.vertices()));
  }
}

HullCastScene::~HullCastScene() = default;

bool HullCastScene::castCollides(const Eigen::Isometry3d& X_a, const Eigen::Isometry3d& X_b, int* pair_queries) const {
  int queries = 0;
  bool hit = false;
  std::vector<int> candidates;
  for (const scene::Piece& piece : impl_->robot->pieces()) {
    SweptPiece swept(piece.polytope.vertices(), X_a, X_b);
    candidates.clear();
    impl_->world->candidates(swept.box, &candidates);
    for (int index : candidates) {
      ++queries;
      if (overlap(swept.shape(), *impl_->world_hulls[static_cast<std::size_t>(index)])) {
        hit = true;
        break;
      }
    }
    if (hit) break;
  }
  if (pair_queries) *pair_queries = queries;
  return hit;
}

// ---- ArmHullCastScene ----------------------------------------------------------

struct ArmHullCastScene::Impl {
  std::vector<std::unique_ptr<LocalHull>> world_hulls;  ///< one per world piece, same index
  std::vector<int> world_links;                         ///< links checked against the world
  std::vector<Eigen::AlignedBox3d> link_boxes;          ///< each link's pieces' box (link frame)
};

namespace {

/// The box of `box` (frame L) placed at X_a and at X_b: the broad phase of a
/// whole link, as a collision library's per-object bounds.
Eigen::AlignedBox3d sweptBox(const Eigen::AlignedBox3d& box, const Eigen::Isometry3d& X_a,
                             const Eigen::Isometry3d& X_b) {
  Eigen::AlignedBox3d out;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d corner = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
    out.extend(X_a * corner);
    out.extend(X_b * corner);
  }
  return out;
}

}  // namespace

ArmHullCastScene::ArmHullCastScene(std::shared_ptr<const ArmScene> scene)
    : scene_(std::move(scene)), impl_(std::make_unique<Impl>()) {
  if (!scene_) throw InvalidInputError("ArmHullCastScene: the scene is null");
  const scene::RobotModel& m = scene_->model();
  for (const scene::Piece& piece : scene_->world().pieces()) {
    impl_->world_hulls.push_back(std::make_unique<LocalHull>(piece.polytope.vertices()));
  }
  for (int k = 0; k < m.numLinks(); ++k) {
    // The pairs ArmScene checks against the world (FclArmScene's too).
    if (!m.link(k).pieces.empty() && !impl_->world_hulls.empty() && !scene_->filter().allowedWithWorld(k)) {
      impl_->world_links.push_back(k);
    }
  }
  impl_->link_boxes.resize(static_cast<std::size_t>(m.numLinks()));
  for (int k = 0; k < m.numLinks(); ++k) {
    for (const scene::Piece& piece : m.link(k).pieces) impl_->link_boxes[static_cast<std::size_t>(k)].extend(piece.box);
  }
}

ArmHullCastScene::~ArmHullCastScene() = default;

bool ArmHullCastScene::castCollides(const double* q0, const double* q1, ArmContact* which, int* pair_queries) const {
  const scene::RobotModel& m = scene_->model();
  std::vector<Eigen::Isometry3d> X0, X1;
  scene_->linkPoses(q0, &X0);
  scene_->linkPoses(q1, &X1);
  // Each link's swept pieces, made when a pair first needs them.
  std::vector<std::vector<SweptPiece>> swept(static_cast<std::size_t>(m.numLinks()));
  const auto sweptOf = [&](int k) -> std::vector<SweptPiece>& {
    auto& pieces = swept[static_cast<std::size_t>(k)];
    if (pieces.empty()) {
      for (const scene::Piece& piece : m.link(k).pieces) {
        pieces.emplace_back(piece.polytope.vertices(), X0[static_cast<std::size_t>(k)],
                            X1[static_cast<std::size_t>(k)]);
      }
    }
    return pieces;
  };
  int queries = 0;
  ArmContact contact;
  bool hit = false;
  std::vector<int> candidates;
  // Each link's box at both poses, once per call (a link is in many self pairs).
  std::vector<Eigen::AlignedBox3d> link_boxes(static_cast<std::size_t>(m.numLinks()));
  for (std::size_t i = 0; i < link_boxes.size(); ++i) {
    if (!impl_->link_boxes[i].isEmpty()) link_boxes[i] = sweptBox(impl_->link_boxes[i], X0[i], X1[i]);
  }
  const auto linkBox = [&](int k) -> const Eigen::AlignedBox3d& { return link_boxes[static_cast<std::size_t>(k)]; };
  for (int k : impl_->world_links) {
    // The whole link first: most links meet no world box.
    candidates.clear();
    scene_->world().candidates(linkBox(k), &candidates);
    if (candidates.empty()) continue;
    for (SweptPiece& piece : sweptOf(k)) {
      candidates.clear();
      scene_->world().candidates(piece.box, &candidates);
      for (int index : candidates) {
        ++queries;
        if (overlap(piece.shape(), *impl_->world_hulls[static_cast<std::size_t>(index)])) {
          contact.link = k;
          contact.world_piece = index;
          hit = true;
          break;
        }
      }
      if (hit) break;
    }
    if (hit) break;
  }
  for (std::size_t p = 0; !hit && p < scene_->selfPairs().size(); ++p) {
    const auto [k, l] = scene_->selfPairs()[p];
    if (!linkBox(k).intersects(linkBox(l))) continue;
    for (SweptPiece& a : sweptOf(k)) {
      for (SweptPiece& b : sweptOf(l)) {
        if (!a.box.intersects(b.box)) continue;
        ++queries;
        if (overlap(a.shape(), b.shape())) {
          contact.link = k;
          contact.other_link = l;
          hit = true;
          break;
        }
      }
      if (hit) break;
    }
  }
  if (which) *which = contact;
  if (pair_queries) *pair_queries = queries;
  return hit;
}

// ---- ArmHullCastMotionValidator ---------------------------------------------------

ArmHullCastMotionValidator::ArmHullCastMotionValidator(const ob::SpaceInformationPtr& si, ArmSpacePtr space,
                                                       std::shared_ptr<const ArmHullCastScene> scene,
                                                       CastSegments segments)
    : CountedMotionValidator(si), space_(std::move(space)), scene_(std::move(scene)), segments_(segments) {
  const std::string who = "ArmHullCastMotionValidator";
  if (!si) throw InvalidInputError(who + ": the SpaceInformation is null");
  if (!space_) throw InvalidInputError(who + ": the ArmSpace is null");
  if (!scene_) throw InvalidInputError(who + ": the scene is null");
  if (si->getStateSpace() != space_->stateSpace()) {
    throw InvalidInputError(who + ": the SpaceInformation's state space is not the ArmSpace's");
  }
  if (&scene_->scene().model() != &space_->model()) {
    throw InvalidInputError(who + ": the ArmSpace and the scene have different robot models");
  }
}

bool ArmHullCastMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  return check(s1, s2, nullptr);
}

bool ArmHullCastMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                             std::pair<ob::State*, double>& lastValid) const {
  return check(s1, s2, &lastValid);
}

bool ArmHullCastMotionValidator::check(const ob::State* s1, const ob::State* s2,
                                       std::pair<ob::State*, double>* lastValid) const {
  if (s1 == nullptr || s2 == nullptr) throw InvalidInputError("ArmHullCastMotionValidator: a null state");
  CheckerCounters::Timer timer(counters_);
  counters_.addMotionCheck();
  const std::size_t n = space_->fixedConfiguration().size();
  std::vector<double> q0(n), q1(n);
  std::uint64_t queries = 0;
  const bool valid = castSegments(
      *si_, segments_, s1, s2,
      [&](const ob::State* a, const ob::State* b) {
        space_->edge(a, b, q0.data(), q1.data());
        int pair_queries = 0;
        const bool hit = scene_->castCollides(q0.data(), q1.data(), nullptr, &pair_queries);
        queries += static_cast<std::uint64_t>(pair_queries);
        return hit;
      },
      lastValid);
  counters_.addPairQueries(queries);
  countOmpl(valid);
  return valid;
}

// ---- HullCastMotionValidator ----------------------------------------------------

HullCastMotionValidator::HullCastMotionValidator(const ob::SpaceInformationPtr& si, PlanningSpacePtr space,
                                                 std::shared_ptr<const HullCastScene> scene, CastSegments segments)
    : CountedMotionValidator(si), space_(std::move(space)), scene_(std::move(scene)), segments_(segments) {
  detail::checkCheckerArguments("HullCastMotionValidator", "HullCastScene", si, space_, scene_.get());
}

bool HullCastMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  return check(s1, s2, nullptr);
}

bool HullCastMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                          std::pair<ob::State*, double>& lastValid) const {
  return check(s1, s2, &lastValid);
}

bool HullCastMotionValidator::check(const ob::State* s1, const ob::State* s2,
                                    std::pair<ob::State*, double>* lastValid) const {
  CheckerCounters::Timer timer(counters_);
  counters_.addMotionCheck();
  std::uint64_t queries = 0;
  const bool valid = castSegments(
      *si_, segments_, s1, s2,
      [&](const ob::State* a, const ob::State* b) {
        int pair_queries = 0;
        const bool hit = scene_->castCollides(space_->pose(a), space_->pose(b), &pair_queries);
        queries += static_cast<std::uint64_t>(pair_queries);
        return hit;
      },
      lastValid);
  counters_.addPairQueries(queries);
  countOmpl(valid);
  return valid;
}

}  // namespace mddual::planning
