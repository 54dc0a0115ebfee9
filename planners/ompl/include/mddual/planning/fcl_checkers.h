// The FCL baseline over exactly the same pieces as the MDD checkers, so that
// comparisons measure the method and not the geometry:
//
//   - FclScene: the robot's and the world's kTriangle pieces as one
//     fcl::BVHModel<fcl::OBBRSS<double>> triangle soup per body (as OMPL.app
//     loads meshes; a flat polygon piece is fanned into triangles), each
//     kConvex piece as an fcl::Convex<double> (vertices, and faces from
//     ConvexPolytope::faceVertices, counter-clockwise seen from outside); the
//     world's objects in an fcl::DynamicAABBTreeCollisionManager (broad phase).
//   - FclStateValidityChecker: bounds, then FCL's discrete collide(): what
//     OMPL.app users run, with OMPL's DiscreteMotionValidator at the space's
//     resolution for edges.
//   - FclContinuousMotionValidator: in the style of OMPL.app's
//     FCLContinuousMotionValidator, fcl::continuousCollide per robot object and
//     candidate world object (broad phase on the swept box), with the naive
//     solver (FCL samples num_max_iterations poses along the motion and runs
//     discrete collide() on each) or conservative advancement (libccd GJK).
//     Translation edges use CCDM_TRANS, the motion OMPL executes. Rotating
//     edges use CCDM_SCREW, as OMPL.app does: FCL's screw motion joins the
//     same two poses but is NOT OMPL's interpolation (straight-line position,
//     slerp orientation) unless the rotation axis is parallel to the
//     translation, so on rotating edges this validator checks a different
//     motion; the broad phase then pads the swept box by the screw arc's
//     largest deviation from its chord. Limits (see also the core benchmark:
//     FCL's casts miss contacts or are off by up to a few 1e-1 of the scene
//     there): the naive solver is a discrete check at num_max_iterations
//     samples (10 by default), so it passes thin obstacles; conservative
//     advancement stops within FCL's tolerances and can report a contact
//     time past the true one. checkMotion(s1, s2) first checks s2 with
//     si->isValid like OMPL.app; lastValid is set like MddMotionValidator's
//     (back-off from the reported time of contact, checked with si->isValid).
//
// Thread safety: FCL's geometry and the world's collision objects are shared
// read-only; each thread gets its own robot collision objects (FCL objects
// carry a mutable pose) from a PerThread cache, created under a mutex (FCL's
// CollisionObject constructor writes to the shared geometry).
#pragma once

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/util/ClassForward.h>
#include <Eigen/Geometry>
#include <limits>
#include <memory>
#include <mutex>
#include <utility>

#include "mddual/planning/counters.h"
#include "mddual/planning/state_space.h"
#include "mddual/scene/scene.h"

namespace mddual::planning {

OMPL_CLASS_FORWARD(FclScene);
OMPL_CLASS_FORWARD(FclStateValidityChecker);
OMPL_CLASS_FORWARD(FclContinuousMotionValidator);

/// fcl::continuousCollide's solvers offered by FclContinuousMotionValidator.
enum class FclCcdSolver { kNaive, kConservativeAdvancement };
const char* toString(FclCcdSolver solver);

/// Settings of fcl::ContinuousCollisionRequest (FCL's defaults).
struct FclCcdOptions {
  FclCcdSolver solver = FclCcdSolver::kConservativeAdvancement;
  int num_max_iterations = 10;  ///< naive: poses sampled along the motion
  double toc_err = 1e-4;        ///< naive: at most ceil(1 / toc_err) samples
};

/// FCL's model of a robot and a world built from the same pieces (see above).
/// It models the world's pieces as they are at construction and has no update
/// path: after a world changes (scene::World or MddScene updates), build a new
/// FclScene from the current world (e.g. MddScene::worldPtr()) to keep the
/// baseline on identical geometry.
class FclScene {
 public:
  /// Throws InvalidInputError for a null robot or world.
  FclScene(std::shared_ptr<const scene::RigidBody> robot, std::shared_ptr<const scene::World> world);
  ~FclScene();
  FclScene(const FclScene&) = delete;
  FclScene& operator=(const FclScene&) = delete;

  /// Whether FCL's collide() finds a contact between the robot at X_WR and
  /// the world. pair_queries: narrow-phase collide() calls.
  bool collides(const Eigen::Isometry3d& X_WR, int* pair_queries = nullptr) const;
  /// FCL's distance between the robot at X_WR and the world (smallest over
  /// the object pairs the broad phase reports; +infinity for an empty world);
  /// <= 0 when they collide (FCL's value then is not a penetration depth).
  /// The smaller of the libccd and the independent GJK solvers' answers: FCL
  /// 0.7 overestimates convex-convex distances with either (in the tests'
  /// scenes, up to 2.6x with libccd on extruded polygons, 1.12x with the
  /// independent solver), never both at once there. Triangle-mesh pairs do
  /// not use GJK and are computed once.
  double distance(const Eigen::Isometry3d& X_WR) const;

  /// Result of continuousCollide().
  struct Continuous {
    bool collides = false;
    double time = std::numeric_limits<double>::infinity();  ///< FCL's time of contact in [0, 1]
    int pair_queries = 0;                                   ///< fcl::continuousCollide() calls
  };
  /// The robot moving from X_start to X_end: translation (rotation of X_start
  /// kept) or FCL's screw motion; the earliest contact over all object pairs.
  Continuous continuousCollide(const Eigen::Isometry3d& X_start, const Eigen::Isometry3d& X_end, bool screw,
                               const FclCcdOptions& options) const;

  int robotObjectCount() const;
  int worldObjectCount() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// State validity on FCL: bounds (si->satisfiesBounds), then FclScene::collides.
class FclStateValidityChecker : public ompl::base::StateValidityChecker {
 public:
  /// Throws InvalidInputError for a null argument or mismatched state space.
  FclStateValidityChecker(const ompl::base::SpaceInformationPtr& si, PlanningSpacePtr space,
                          std::shared_ptr<const FclScene> scene);
  bool isValid(const ompl::base::State* state) const override;
  CheckerCounts counts() const { return counters_.read(); }
  void resetCounts() { counters_.reset(); }
  /// Whether counts().seconds is measured (see CheckerCounters::setTiming).
  void setTiming(bool on) { counters_.setTiming(on); }
  const FclScene& scene() const { return *scene_; }

 private:
  PlanningSpacePtr space_;
  std::shared_ptr<const FclScene> scene_;
  mutable CheckerCounters counters_;
};

/// Motion validity with fcl::continuousCollide (see the file comment).
class FclContinuousMotionValidator : public CountedMotionValidator {
 public:
  /// Throws InvalidInputError for a null argument, a mismatched state space
  /// or options out of range (num_max_iterations < 2, toc_err <= 0).
  FclContinuousMotionValidator(const ompl::base::SpaceInformationPtr& si, PlanningSpacePtr space,
                               std::shared_ptr<const FclScene> scene, const FclCcdOptions& options = FclCcdOptions());
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;
  const FclCcdOptions& options() const { return options_; }

 private:
  FclScene::Continuous run(const ompl::base::State* s1, const ompl::base::State* s2) const;

  PlanningSpacePtr space_;
  std::shared_ptr<const FclScene> scene_;
  FclCcdOptions options_;
  mutable std::mutex ompl_counters_mutex_;
};

}  // namespace mddual::planning
