// PathVerifier: the independent, strict re-check of a solution path that the
// benchmark applies to every solution of every checker.
//
// A path is a sequence of states joined by OMPL's interpolation (PlanningSpace
// describes that motion). It is checked twice, by two methods that share no
// code with each other:
//
//  (a) exact MDD edge check: every segment with MddScene::checkEdge on a scene
//      of its own (not the planners'), both ends included. Translation
//      segments are exact (one toi per candidate pair). Rotating segments use
//      the sound sub-edge scheme with a much smaller rotation tolerance than
//      the planners' checker: sub-edges at delta = 2^levels * finest, refined
//      down to finest = VerifierOptions::rotation_tolerance_rel (1e-6) of the
//      robot radius. The scheme is sound, so a colliding segment is always
//      flagged; the price is that a rotating segment passing within about
//      1.7 * finest (the enlarged robot's reach) of an obstacle is flagged
//      too, although free. Touching counts as collision (1e-10 of a pair's
//      size, the core's tolerance), as everywhere in mddual.
//
//  (b) dense FCL check: FCL's collide() at states of OMPL's interpolation
//      (StateSpace::interpolate) along every segment, so far apart that no
//      robot point moves more than `step` between two samples, with step =
//      1/resolution_divisor (1/50) of OMPL's default longest valid segment
//      (1% of the position bounds' diagonal). Samples that FCL's distance
//      proves free are skipped: from a state at FCL distance d, no robot
//      point can reach an obstacle before it moves d, so the next sample is
//      0.5 d further on (half, because FCL 0.7's convex distances can be
//      overestimated; the OMPL layer's tests check that half is safe), never
//      less than `step`. Where the distance lets it skip fewer than 16 steps
//      (a path through a narrow passage), the next 32 samples are checked
//      with collide() alone, at every step: a distance query costs 10 to 15
//      collide() calls on mesh scenes. FCL's GJK reports contacts between
//      shapes up to about 1e-6 apart, so a state FCL finds colliding counts
//      only when the brute-force Minkowski difference (qhull, independent of
//      MDD-DUAL and FCL) confirms a penetration deeper than
//      penetration_tolerance_rel (1e-9) of the scene's scale (1 + robot
//      radius + |position|); a touching state is
//      left to check (a).
//
// A path that either check finds in collision (or with a state outside the
// problem's position bounds; x and y for the planar kinds) is invalid. What the dense check cannot see: an obstacle
// thinner than `step` that the robot crosses between samples; (a) sees it.
#pragma once

#include <ompl/base/State.h>
#include <ompl/geometric/PathGeometric.h>
#include <memory>
#include <vector>

#include "mddual/planning/fcl_checkers.h"
#include "mddual/planning/mdd_scene.h"
#include "mddual/planning/state_space.h"

namespace mddual::planning {

struct VerifierOptions {
  /// Finest rotation tolerance of check (a), relative to the robot radius
  /// (MddScene's smallest allowed).
  double rotation_tolerance_rel = 1e-6;
  /// Halvings from the coarse sub-edges to the finest tolerance (0 to 8).
  int refinement_levels = 8;
  /// Check (b)'s step: OMPL's default longest valid segment (1% of the
  /// position bounds' diagonal) divided by this.
  double resolution_divisor = 50.0;
  /// Check (b): least penetration (relative to the scene's scale) that
  /// confirms an FCL collision.
  double penetration_tolerance_rel = 1e-9;
  /// Run check (b) after (a) found a collision (to report both).
  bool always_run_both = true;
};

/// The verdict on one path.
struct VerifyResult {
  bool valid = true;               ///< neither check found a collision, all states within bounds
  bool mdd_collision = false;      ///< check (a) found a colliding segment
  bool fcl_collision = false;      ///< check (b) found a (confirmed) colliding state
  bool out_of_bounds = false;      ///< a state of the path lies outside the position bounds
  int mdd_segment = -1;            ///< first segment (a) flagged
  int fcl_segment = -1;            ///< first segment (b) flagged
  double fcl_fraction = -1.0;      ///< where on it
  long long fcl_samples = 0;       ///< states FCL checked
  long long fcl_unconfirmed = 0;   ///< FCL collisions the brute force found to be touching only
  long long mdd_pair_queries = 0;  ///< core queries of check (a)
  double seconds = 0.0;            ///< time of the whole verification
  double mdd_seconds = 0.0;        ///< of which check (a)
  double fcl_seconds = 0.0;        ///< of which check (b), brute-force confirmations included
};

/// See the file comment. Immutable after construction; verify() may be called
/// from several threads.
class PathVerifier {
 public:
  /// `bounds`: the position bounds of the problem's space. Throws
  /// InvalidInputError for a null robot or world or bad options.
  PathVerifier(std::shared_ptr<const scene::RigidBody> robot, std::shared_ptr<const scene::World> world,
               const Eigen::AlignedBox3d& bounds, const VerifierOptions& options = VerifierOptions());

  /// Verifies the path `states[0] -> states[1] -> ...` of `space`.
  VerifyResult verify(const PlanningSpace& space, const std::vector<const ompl::base::State*>& states) const;
  VerifyResult verify(const PlanningSpace& space, const ompl::geometric::PathGeometric& path) const;

  /// Check (b)'s step (world units).
  double step() const { return step_; }
  const MddScene& mddScene() const { return *mdd_; }
  const FclScene& fclScene() const { return *fcl_; }

  /// Whether the robot at X_WR penetrates a world piece deeper than the
  /// penetration tolerance, by the brute-force Minkowski difference.
  bool bruteForcePenetrates(const Eigen::Isometry3d& X_WR) const;

 private:
  /// Check (b) on one segment: the first confirmed colliding fraction, or -1.
  double denseFcl(const PlanningSpace& space, const ompl::base::State* s1, const ompl::base::State* s2,
                  ompl::base::State* work, VerifyResult* result) const;

  std::shared_ptr<const scene::RigidBody> robot_;
  std::shared_ptr<const scene::World> world_;
  Eigen::AlignedBox3d bounds_;
  VerifierOptions options_;
  std::shared_ptr<MddScene> mdd_;
  std::shared_ptr<FclScene> fcl_;
  double step_ = 0.0;
};

}  // namespace mddual::planning
