#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>

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

  explicit LocalHull(const std::vector<Eigen::Vector3d>& points) {
    Eigen::AlignedBox3d box;
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
  std::vector<Eigen::Vector3d> points;
  std::vector<int> candidates;
  for (const scene::Piece& piece : impl_->robot->pieces()) {
    const std::vector<Eigen::Vector3d>& vertices = piece.polytope.vertices();
    points.clear();
    for (const Eigen::Vector3d& v : vertices) points.push_back(X_a * v);
    for (const Eigen::Vector3d& v : vertices) points.push_back(X_b * v);
    const LocalHull hull(points);
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3d& p : points) box.extend(p);
    candidates.clear();
    impl_->world->candidates(box, &candidates);
    for (int index : candidates) {
      const LocalHull& other = *impl_->world_hulls[static_cast<std::size_t>(index)];
      btGjkEpaSolver2::sResults result;
      const btVector3 guess = other.X_W.getOrigin() - hull.X_W.getOrigin();
      ++queries;
      if (btGjkEpaSolver2::Penetration(&hull.shape, hull.X_W, &other.shape, other.X_W, guess, result)) {
        hit = true;
        break;
      }
    }
    if (hit) break;
  }
  if (pair_queries) *pair_queries = queries;
  return hit;
}

// ---- HullCastMotionValidator ----------------------------------------------------

HullCastMotionValidator::HullCastMotionValidator(const ob::SpaceInformationPtr& si, PlanningSpacePtr space,
                                                 std::shared_ptr<const HullCastScene> scene)
    : CountedMotionValidator(si), space_(std::move(space)), scene_(std::move(scene)) {
  detail::checkCheckerArguments("HullCastMotionValidator", "HullCastScene", si, space_, scene_.get());
}

bool HullCastMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  CheckerCounters::Timer timer(counters_);
  counters_.addMotionCheck();
  bool valid = si_->satisfiesBounds(s1) && si_->satisfiesBounds(s2);
  if (valid) {
    int queries = 0;
    valid = !scene_->castCollides(space_->pose(s1), space_->pose(s2), &queries);
    counters_.addPairQueries(static_cast<std::uint64_t>(queries));
  }
  countOmpl(valid);
  return valid;
}

bool HullCastMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                          std::pair<ob::State*, double>& lastValid) const {
  const bool valid = checkMotion(s1, s2);
  if (!valid) {
    if (lastValid.first) si_->copyState(lastValid.first, s1);
    lastValid.second = 0.0;
  }
  return valid;
}

}  // namespace mddual::planning
