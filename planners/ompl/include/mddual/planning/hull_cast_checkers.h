// A peer baseline on Bullet: the "cast" continuous check of MoveIt's and
// Tesseract's Bullet collision plugins, over exactly the same pieces as the
// MDD and FCL checkers.
//
//   - HullCastScene: for an edge from pose A to pose B, each robot piece is
//     replaced by the convex hull of its vertices at A and at B (a
//     btConvexHullShape in the world frame, margin 0: the swept hull that
//     MoveIt's Bullet cast builds from the two poses), and that hull is
//     tested against every world piece the broad phase (scene::World's box
//     tree, on the hull's bounding box) reports, with Bullet's GJK/EPA
//     (btGjkEpaSolver2::Penetration); each world piece is a btConvexHullShape
//     of its vertices (a mesh triangle is a flat hull of three points).
//   - HullCastMotionValidator: an OMPL MotionValidator on it, built as
//     Tesseract's continuous motion validator: the edge is cut into OMPL's
//     validSegmentCount segments (the space's resolution, as the discrete
//     validator's states); each segment's end state goes to si's state
//     validity checker (FCL) and the cast runs between the segment's two
//     end states.
//   - ArmHullCastScene, ArmHullCastMotionValidator: the same cast for an arm
//     (ArmScene): each checked link's pieces at the segment's two end
//     configurations (forward kinematics), each piece's hull of both poses
//     cast against the world pieces and, for the self pairs ArmScene checks,
//     against the other link's swept piece hulls; segments as above.
//
// The hull of the two end poses is the swept volume of a translation, so on
// translating edges the check is exact up to Bullet's GJK tolerance. On a
// rotating segment a point of the robot moves on an arc that leaves that
// hull (a long link turning about one end sweeps the circular sector between
// its end poses, the hull only the triangle), so a collision inside the arc
// and outside the hull is MISSED: this validator is NOT sound on rotating
// edges. Segments shrink the sliver between arc and chord (its depth is
// about r * a^2 / 8 for a turn of a radians at radius r) but do not close it:
// a thin obstacle in it is still called free. The validator exists to
// measure that failure next to the certified MddMotionValidator
// (benchmarks/soundness, docs/results/soundness.md).
//
// lastValid: on an invalid edge, the start of the first failing segment and
// its fraction (Tesseract's answer); the cast gives no time of contact inside
// a segment. An end outside the bounds gives (copy of s1, 0).
//
// Thread safety: the world's Bullet shapes are built once and only read; the
// swept hulls and the segment states are made per call.
//
// registerHullCastCheckers() adds the checker "hull-cast" to both benchmark
// tables (checker_registry.h): FCL's state check with the cast for edges.
#pragma once

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/util/ClassForward.h>
#include <Eigen/Geometry>
#include <memory>
#include <utility>

#include "mddual/planning/arm_checkers.h"
#include "mddual/planning/counters.h"
#include "mddual/planning/state_space.h"
#include "mddual/scene/scene.h"

namespace mddual::planning {

OMPL_CLASS_FORWARD(HullCastScene);
OMPL_CLASS_FORWARD(HullCastMotionValidator);
OMPL_CLASS_FORWARD(ArmHullCastScene);
OMPL_CLASS_FORWARD(ArmHullCastMotionValidator);

/// Where the validators cast: between the end states of OMPL's segments
/// (kResolution, Tesseract's motion validator, the planning peer) or once
/// between the edge's two ends (kWholeEdge, MoveIt's cast between two
/// states; the soundness suite measures both).
enum class CastSegments { kResolution, kWholeEdge };

/// Bullet's model of a robot and a world built from the same pieces (see above).
class HullCastScene {
 public:
  /// Throws InvalidInputError for a null robot or world.
  HullCastScene(std::shared_ptr<const scene::RigidBody> robot, std::shared_ptr<const scene::World> world);
  ~HullCastScene();
  HullCastScene(const HullCastScene&) = delete;
  HullCastScene& operator=(const HullCastScene&) = delete;

  /// Whether the hull of some robot piece at X_a and at X_b overlaps a world
  /// piece (Bullet's GJK/EPA). pair_queries: narrow-phase calls.
  bool castCollides(const Eigen::Isometry3d& X_a, const Eigen::Isometry3d& X_b, int* pair_queries = nullptr) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Motion validity by swept hulls over OMPL's segments (see the file
/// comment): exact on translations, misses contacts of rotating segments
/// that leave their hull. Both ends must satisfy the space's bounds.
class HullCastMotionValidator : public CountedMotionValidator {
 public:
  /// Throws InvalidInputError for a null argument or a mismatched state space.
  HullCastMotionValidator(const ompl::base::SpaceInformationPtr& si, PlanningSpacePtr space,
                          std::shared_ptr<const HullCastScene> scene,
                          CastSegments segments = CastSegments::kResolution);
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  /// On an invalid edge lastValid = the start of the first failing segment.
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;

 private:
  bool check(const ompl::base::State* s1, const ompl::base::State* s2,
             std::pair<ompl::base::State*, double>* lastValid) const;
  PlanningSpacePtr space_;
  std::shared_ptr<const HullCastScene> scene_;
  CastSegments segments_;
};

/// The arm cast (see the file comment) over an ArmScene's links, world and
/// checked pairs.
class ArmHullCastScene {
 public:
  /// Throws InvalidInputError for a null scene.
  explicit ArmHullCastScene(std::shared_ptr<const ArmScene> scene);
  ~ArmHullCastScene();
  ArmHullCastScene(const ArmHullCastScene&) = delete;
  ArmHullCastScene& operator=(const ArmHullCastScene&) = delete;

  /// Whether, for the edge from configuration q0 to q1 (full configurations,
  /// model().numVariables() values), the hull of some checked link piece at
  /// both ends overlaps a world piece, or the swept hulls of a self pair's
  /// pieces overlap. `which` (when not null) receives the pair found;
  /// pair_queries: narrow-phase calls.
  bool castCollides(const double* q0, const double* q1, ArmContact* which = nullptr, int* pair_queries = nullptr) const;
  const ArmScene& scene() const { return *scene_; }

 private:
  struct Impl;
  std::shared_ptr<const ArmScene> scene_;
  std::unique_ptr<Impl> impl_;
};

/// Motion validity of an arm edge by ArmHullCastScene::castCollides over
/// OMPL's segments (under OMPL's interpolation, ArmSpace::edge); both ends
/// must satisfy the bounds. Misses contacts of turning links outside the
/// hulls (see above). Used with FclArmStateValidityChecker for the states.
class ArmHullCastMotionValidator : public CountedMotionValidator {
 public:
  /// Throws InvalidInputError for a null argument, when si's state space is
  /// not space->stateSpace(), or the space's robot is not the scene's.
  ArmHullCastMotionValidator(const ompl::base::SpaceInformationPtr& si, ArmSpacePtr space,
                             std::shared_ptr<const ArmHullCastScene> scene,
                             CastSegments segments = CastSegments::kResolution);
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  /// On an invalid edge lastValid = the start of the first failing segment.
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;

 private:
  bool check(const ompl::base::State* s1, const ompl::base::State* s2,
             std::pair<ompl::base::State*, double>* lastValid) const;
  ArmSpacePtr space_;
  std::shared_ptr<const ArmHullCastScene> scene_;
  CastSegments segments_;
};

/// Appends the "hull-cast" entries to the checker tables (addRigidChecker;
/// planners/frontend/src/checkers/bullet/hull_cast_checker.cpp). Call once at
/// start-up, before the tables are read; a second call does nothing.
void registerHullCastCheckers();

}  // namespace mddual::planning
