#include "mddual/planning/mdd_checkers.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "checker_arguments.h"
#include "constants.h"
#include "mddual/error.h"
#include "mddual/planning/scene_distance.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;

using detail::kInf;
/// lastValid back-off: first step and growth (fractions of the edge).
constexpr double kFirstBackoff = 1e-9;
constexpr double kBackoffGrowth = 10.0;

}  // namespace

void setLastValid(const ob::SpaceInformation& si, const ob::State* s1, const ob::State* s2, double first_invalid,
                  std::pair<ob::State*, double>& lastValid) {
  // Candidates go to a scratch state: lastValid.first may be s2 itself
  // (KPIECE1 passes the state it sampled as both), which a first rejected
  // candidate would otherwise overwrite before the next is interpolated.
  ob::State* state = si.allocState();
  double t = 0.0;
  if (first_invalid > 0.0) {
    for (double backoff = kFirstBackoff; backoff < first_invalid; backoff *= kBackoffGrowth) {
      const double candidate = first_invalid - backoff;
      si.getStateSpace()->interpolate(s1, s2, candidate, state);
      if (si.isValid(state)) {
        t = candidate;
        break;
      }
    }
  }
  if (lastValid.first) si.copyState(lastValid.first, t == 0.0 ? s1 : state);
  lastValid.second = t;
  si.freeState(state);
}

// ---- MddStateValidityChecker -------------------------------------------------------

MddStateValidityChecker::MddStateValidityChecker(const ob::SpaceInformationPtr& si, PlanningSpacePtr space,
                                                 std::shared_ptr<const MddScene> scene)
    : ob::StateValidityChecker(si), space_(std::move(space)), scene_(std::move(scene)) {
  detail::checkCheckerArguments("MddStateValidityChecker", "scene", si, space_, scene_.get());
  specs_.clearanceComputationType = ob::StateValidityCheckerSpecs::EXACT;
}

namespace {

/// Whether `state` is a state of the space an edge can go to: rotations
/// within their bounds (a yaw within [-pi, pi], unit quaternions) and a finite
/// position (see MddMotionValidator::evaluate).
bool definedState(const PlanningSpace& space, const ob::State* state) {
  return space.rotationsWithinBounds(state) && space.pose(state).translation().allFinite();
}

/// Throws InvalidInputError "<what> is null" for a null state (OMPL's own
/// checkers dereference it).
void requireState(const ob::State* state, const char* what) {
  if (state == nullptr) throw InvalidInputError(std::string(what) + " is null");
}

}  // namespace

bool MddStateValidityChecker::isValid(const ob::State* state) const {
  requireState(state, "MddStateValidityChecker::isValid: the state");
  CheckerCounters::Timer timer(counters_);
  counters_.addStateCheck();
  if (!si_->satisfiesBounds(state)) return false;
  int queries = 0;
  const bool hit = scene_->collides(space_->pose(state), &queries);
  counters_.addPairQueries(static_cast<std::uint64_t>(queries));
  return !hit;
}

double MddStateValidityChecker::clearance(const ob::State* state) const {
  requireState(state, "MddStateValidityChecker::clearance: the state");
  CheckerCounters::Timer timer(counters_);
  counters_.addStateCheck();
  const SceneDistance d = sceneDistance(*scene_, space_->pose(state));
  counters_.addPairQueries(static_cast<std::uint64_t>(d.pair_queries));
  return d.distance;
}

// ---- MddMotionValidator ----------------------------------------------------------

MddMotionValidator::MddMotionValidator(const ob::SpaceInformationPtr& si, PlanningSpacePtr space,
                                       std::shared_ptr<const MddScene> scene)
    : CountedMotionValidator(si), space_(std::move(space)), scene_(std::move(scene)) {
  detail::checkCheckerArguments("MddMotionValidator", "scene", si, space_, scene_.get());
}

EdgeContact MddMotionValidator::evaluate(const ob::State* s1, const ob::State* s2, EdgeQuery query) const {
  requireState(s1, "MddMotionValidator: s1");
  requireState(s2, "MddMotionValidator: s2");
  const bool first_contact = query != EdgeQuery::kValidity;
  EdgeContact out;
  if (!si_->satisfiesBounds(s1)) {
    out.collides = true;
    out.start_collides = true;
    out.fraction = 0.0;
    return out;
  }
  if (!definedState(*space_, s2)) {
    // s2 is no state of the space (a yaw beyond pi, a quaternion off unit
    // norm or zero, a position of infinity or NaN): the edge is invalid at
    // its end, as OMPL's discrete check (which tests s2 first) says, and the
    // motion OMPL would interpolate to it is undefined (its SO(3) code
    // aborted on a zero quaternion, a yaw of 1e17 made the search run for
    // minutes, and an infinite position answered false without lastValid and
    // threw with it; an API hunt): no search, a first contact bound of 0
    // (lastValid keeps s1).
    out.collides = true;
    out.exact = false;
    out.fraction = first_contact ? 0.0 : 1.0;
    return out;
  }
  const EdgeMotion motion = space_->motion(s1, s2);
  double bounds_exit = kInf;
  if (!si_->satisfiesBounds(s2)) {
    bounds_exit = space_->boundsExitFraction(s1, s2);
    if (!(bounds_exit <= 1.0)) bounds_exit = 1.0;  // out of bounds otherwise (angle, quaternion norm): s2 only
    if (!first_contact) {
      out.collides = true;
      out.fraction = bounds_exit;
      return out;
    }
  }
  // lastValid: a bound as fine as OMPL's discrete check's (one of its steps).
  // validSegmentCount asserts that every rotation is within its bounds
  // (SO2/SO3StateSpace::distance aborted on a yaw of 10 or a quaternion of
  // norm 2): an s2 with a rotation out of bounds takes the exact first
  // contact instead (s1 satisfies the bounds, checked above; an s2 within
  // the bounds, bounds_exit infinite, needs no look at its rotations).
  const double tolerance = query == EdgeQuery::kLastValid && (bounds_exit == kInf || space_->rotationsWithinBounds(s2))
                               ? 1.0 / std::max(1u, si_->getStateSpace()->validSegmentCount(s1, s2))
                               : 0.0;
  out = scene_->checkEdge(motion, query, tolerance);
  counters_.addPairQueries(static_cast<std::uint64_t>(out.pair_queries));
  counters_.addSubEdges(static_cast<std::uint64_t>(out.sub_edges));
  if (bounds_exit < out.fraction) {
    out.collides = true;
    out.fraction = bounds_exit;
    out.exact = true;
    out.start_collides = false;  // s1 is within bounds and was not found colliding before the exit
    out.contact = PieceContact();
  }
  return out;
}

EdgeContact MddMotionValidator::firstInvalid(const ob::State* s1, const ob::State* s2, EdgeQuery query) const {
  if (query == EdgeQuery::kValidity) {
    throw InvalidInputError(
        "MddMotionValidator::firstInvalid: query kValidity computes no first contact (use "
        "kFirstContact or kLastValid)");
  }
  return evaluate(s1, s2, query);
}

bool MddMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  CheckerCounters::Timer timer(counters_);
  counters_.addMotionCheck();
  const bool valid = !evaluate(s1, s2, EdgeQuery::kValidity).collides;
  countOmpl(valid);
  return valid;
}

void MddMotionValidator::setDiscardedLastValidFraction(double fraction) {
  if (!(fraction >= 0.0 && fraction <= 1.0)) {
    throw InvalidInputError("MddMotionValidator: the discarded lastValid fraction must be in [0, 1], got " +
                            std::to_string(fraction));
  }
  discarded_fraction_.store(fraction, std::memory_order_relaxed);
}

bool MddMotionValidator::blockedEarly(const ob::State* s1, const ob::State* s2) const {
  requireState(s1, "MddMotionValidator: s1");
  requireState(s2, "MddMotionValidator: s2");
  // A rotating edge only (a translation edge's exact sweep costs about what
  // the state test costs), from a start within the bounds (a start outside
  // them takes evaluate's (s1, 0) path; an edge that leaves them before the
  // state tested has its lastValid at most the exit).
  if (!si_->satisfiesBounds(s1) || !definedState(*space_, s2)) return false;  // evaluate's early answers
  const EdgeMotion motion = space_->motion(s1, s2);
  if (!motion.rotates()) return false;
  // The state tested: the planner's discarded fraction, or else one step of
  // OMPL's discrete check into the edge (validSegmentCount asserts that s2's
  // rotations are within their bounds; an edge of one step has none).
  double f = discarded_fraction_.load(std::memory_order_relaxed);
  if (f == 0.0 && space_->rotationsWithinBounds(s2)) {
    const unsigned int steps = si_->getStateSpace()->validSegmentCount(s1, s2);
    if (steps >= 2) f = 1.0 / steps;
  }
  if (f == 0.0) return false;
  int pair_queries = 0;
  const bool hit = scene_->collides(motion.pose(f), &pair_queries);
  counters_.addPairQueries(static_cast<std::uint64_t>(pair_queries));
  return hit;
}

bool MddMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                     std::pair<ob::State*, double>& lastValid) const {
  CheckerCounters::Timer timer(counters_);
  counters_.addMotionCheck();
  // (s1, 0) when the state at the discarded fraction collides (a planner
  // that drops any lastValid at or below it, setDiscardedLastValidFraction),
  // or, for other planners, the state one step into the edge: the first
  // contact is then within one step of the start, so 0 meets the search's
  // one-step guarantee (the search may return a tighter bound). A planner
  // that extends up to lastValid (mdd_rrtconnect) starts most of its blocked
  // edges a fraction of a step from an obstacle.
  if (blockedEarly(s1, s2)) {
    setLastValid(*si_, s1, s2, 0.0, lastValid);
    countOmpl(false);
    return false;
  }
  const EdgeContact e = evaluate(s1, s2, EdgeQuery::kLastValid);
  if (!e.collides) {
    countOmpl(true);
    return true;
  }
  // OMPL's interpolate asserts on an s2 whose quaternion is off unit norm (so
  // does its discrete validator): an edge toward a rotation out of bounds
  // keeps only s1.
  setLastValid(*si_, s1, s2, space_->rotationsWithinBounds(s2) ? e.fraction : 0.0, lastValid);
  countOmpl(false);
  return false;
}

}  // namespace mddual::planning
