// The OMPL checkers built on MDD-DUAL: MddStateValidityChecker and
// MddMotionValidator, over an MddScene (robot, world, broad phase, warm
// starts) and a PlanningSpace (state <-> pose, OMPL's interpolation).
//
// Typical set-up:
//   auto space = PlanningSpace::se3(bounds);
//   auto si = std::make_shared<ompl::base::SpaceInformation>(space->stateSpace());
//   auto scene = std::make_shared<MddScene>(robot, world);
//   si->setStateValidityChecker(std::make_shared<MddStateValidityChecker>(si, space, scene));
//   si->setMotionValidator(std::make_shared<MddMotionValidator>(si, space, scene));
//   si->setup();
// On a SpaceInformation the user made (own SE2/SE3/R^2/R^3 space, or a
// compound with such a pose part), exact_checking.h does the same in one call:
//   auto installed = useExactChecking(si, robot, world);
//
// Both are thread-safe: OMPL may call their const methods from several
// threads (per-thread warm starts live in the MddScene; counters are atomic;
// OMPL's own valid/invalid motion counters are updated under a mutex).
#pragma once

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/util/ClassForward.h>
#include <atomic>
#include <memory>
#include <mutex>
#include <utility>

#include "mddual/planning/counters.h"
#include "mddual/planning/mdd_scene.h"
#include "mddual/planning/state_space.h"

namespace mddual::planning {

OMPL_CLASS_FORWARD(MddStateValidityChecker);
OMPL_CLASS_FORWARD(MddMotionValidator);

/// State validity on MDD-DUAL. isValid(s) is true iff the state satisfies the
/// space's bounds (si->satisfiesBounds) and no robot piece touches or overlaps
/// a world piece at pose(s) (MddScene::collides: the broad phase's candidate
/// pairs, each with mddual::intersect).
///
/// clearance(s) is exact (specs().clearanceComputationType == EXACT, so
/// OMPL's MaximizeMinClearanceObjective and clearance-based samplers use it):
/// sceneDistance() at pose(s) (scene_distance.h), i.e. the smallest Euclidean
/// distance between a robot piece and a world piece when the robot is free,
/// 0 when it only touches, minus the largest penetration depth over the
/// overlapping pairs when it collides, +infinity in an empty world. It
/// ignores the space's bounds.
class MddStateValidityChecker : public ompl::base::StateValidityChecker {
 public:
  /// Throws InvalidInputError for a null argument or when si's state space is
  /// not space->stateSpace().
  MddStateValidityChecker(const ompl::base::SpaceInformationPtr& si, PlanningSpacePtr space,
                          std::shared_ptr<const MddScene> scene);

  bool isValid(const ompl::base::State* state) const override;
  /// See the class comment. Counts one state check and its pair queries.
  double clearance(const ompl::base::State* state) const override;

  CheckerCounts counts() const { return counters_.read(); }
  void resetCounts() { counters_.reset(); }
  /// Whether counts().seconds is measured (see CheckerCounters::setTiming).
  void setTiming(bool on) { counters_.setTiming(on); }
  const MddScene& scene() const { return *scene_; }
  const PlanningSpace& planningSpace() const { return *space_; }

 private:
  PlanningSpacePtr space_;
  std::shared_ptr<const MddScene> scene_;
  mutable CheckerCounters counters_;
};

/// Motion validity on MDD-DUAL, under OMPL's interpolation (PlanningSpace).
///
///   - Translation edges (kR2/kR3 spaces; SE(2)/SE(3) edges that do not rotate):
///     exact. One mddual::toi per candidate pair; the edge is valid iff no
///     state on it (both ends included) touches the world and both ends are
///     within bounds.
///   - Rotating edges: sound, never valid when some interpolated state
///     collides; may be invalid although the motion is free when it passes
///     within delta / 2^levels of an obstacle (MddScene's sub-edge scheme).
///   - checkMotion(s1, s2, lastValid), on an invalid edge: f = the first
///     invalid fraction (a lower bound of the first contact within one step
///     of OMPL's discrete check: on translation edges at most that step
///     before the exact contact, on rotating ones MddScene's kLastValid
///     bound; or where the position leaves the bounds,
///     or 1 when s2 is out of bounds otherwise). lastValid.second = f - b for
///     the smallest b in {1e-9, 1e-8, ...} whose state passes si->isValid;
///     lastValid.first (when not null) receives that state, interpolated by
///     OMPL. Every state before it on the edge is valid. When no such b
///     exists (or f = 0: the start collides or is out of bounds), lastValid =
///     (copy of s1, 0). On a valid edge lastValid is not touched. With
///     setDiscardedLastValidFraction(d) > 0 (for a planner that drops every
///     lastValid at or below d: KPIECE, BKPIECE, LBKPIECE, STRIDE), a rotating
///     edge whose state at d collides gets (copy of s1, 0) at once: what the
///     planner does with it is what it does with f - b, which is then at most
///     d too. Otherwise (d = 0) a rotating edge whose state one step into it
///     (1 / validSegmentCount(s1, s2), on edges of two steps or more whose
///     s2 has its rotations within their bounds) collides gets (copy of s1,
///     0) at once: f = 0 is then within one step of the first contact, as
///     promised above.
///   - s1 is not assumed valid: an edge whose start collides is invalid.
///   - checkMotion(s1, s2) (validity only) first tests s2, the middle state
///     and, on rotating edges, the quarters (mddual::intersect,
///     early exit), as OMPL's discrete validator orders its samples: most
///     invalid edges end after a few cheap state tests.
///     Only then the sweep (rotating edges: sub-edges in bisection order, and a
///     failing coarse sub-edge is settled by a true colliding state before it
///     is refined). These shortcuts only ever return "invalid" for an edge
///     with a colliding state, so both overloads give the same answer.
class MddMotionValidator : public CountedMotionValidator {
 public:
  /// Throws InvalidInputError like MddStateValidityChecker.
  MddMotionValidator(const ompl::base::SpaceInformationPtr& si, PlanningSpacePtr space,
                     std::shared_ptr<const MddScene> scene);

  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;

  /// The first invalid fraction of an edge (bounds included) and its contact
  /// (MddScene::checkEdge's EdgeQuery::kFirstContact). fraction = +inf for a
  /// valid edge. With query = kLastValid: the bound that checkMotion(s1, s2,
  /// lastValid) backs off from (another lower bound, usually coarser), unless
  /// one of its shortcuts gives (s1, 0) first (class comment).
  /// Throws InvalidInputError for kValidity (not a contact query).
  EdgeContact firstInvalid(const ompl::base::State* s1, const ompl::base::State* s2,
                           EdgeQuery query = EdgeQuery::kFirstContact) const;

  const MddScene& scene() const { return *scene_; }
  const PlanningSpace& planningSpace() const { return *space_; }

  /// For a planner that drops every partial motion whose lastValid.second
  /// is at most `fraction` (KPIECE1, BKPIECE1, LBKPIECE1, STRIDE: their
  /// min_valid_path_fraction, see discardedLastValidFraction):
  /// checkMotion(s1, s2, lastValid) on a rotating edge first tests the state
  /// at that fraction, and when it collides returns lastValid = (copy of s1,
  /// 0) without searching for the first contact. The planner decides as it
  /// would have: the first contact is before that state, so the true bound
  /// would be at most `fraction` too. The contract above holds ((s1, 0) as
  /// for a colliding start; the verdict is the same). 0, the default, turns
  /// it off (the first-step shortcut of the class comment applies instead);
  /// translation edges never take it (their exact sweep costs about
  /// what the state test costs). Throws InvalidInputError outside [0, 1].
  /// Set it between planner runs, not during one.
  void setDiscardedLastValidFraction(double fraction);
  double discardedLastValidFraction() const { return discarded_fraction_.load(std::memory_order_relaxed); }

 private:
  EdgeContact evaluate(const ompl::base::State* s1, const ompl::base::State* s2, EdgeQuery query) const;
  /// The shortcuts of checkMotion(s1, s2, lastValid): a rotating edge whose
  /// state at the discarded fraction (setDiscardedLastValidFraction) or, when
  /// that is 0, one step of OMPL's discrete check into the edge collides.
  bool blockedEarly(const ompl::base::State* s1, const ompl::base::State* s2) const;

  PlanningSpacePtr space_;
  std::shared_ptr<const MddScene> scene_;
  std::atomic<double> discarded_fraction_{0.0};
};

/// Sets lastValid per OMPL's contract for an edge whose first invalid fraction
/// is `first_invalid` (in [0, 1]): backs off by 1e-9, 1e-8, ... of the edge
/// until si.isValid() accepts the interpolated state, else (s1, 0). Shared by
/// the motion validators of this layer.
void setLastValid(const ompl::base::SpaceInformation& si, const ompl::base::State* s1, const ompl::base::State* s2,
                  double first_invalid, std::pair<ompl::base::State*, double>& lastValid);

}  // namespace mddual::planning
