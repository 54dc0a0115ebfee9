#include <string>

#include "checker_arguments.h"
#include "mddual/error.h"
#include "mddual/planning/fcl_checkers.h"
#include "mddual/planning/mdd_checkers.h"

namespace mddual::planning {
namespace ob = ompl::base;

// ---- FclStateValidityChecker -----------------------------------------------------

FclStateValidityChecker::FclStateValidityChecker(const ob::SpaceInformationPtr& si, PlanningSpacePtr space,
                                                 std::shared_ptr<const FclScene> scene)
    : ob::StateValidityChecker(si), space_(std::move(space)), scene_(std::move(scene)) {
  detail::checkCheckerArguments("FclStateValidityChecker", "FclScene", si, space_, scene_.get());
}

bool FclStateValidityChecker::isValid(const ob::State* state) const {
  CheckerCounters::Timer timer(counters_);
  counters_.addStateCheck();
  if (!si_->satisfiesBounds(state)) return false;
  int queries = 0;
  const bool hit = scene_->collides(space_->pose(state), &queries);
  counters_.addPairQueries(static_cast<std::uint64_t>(queries));
  return !hit;
}

// ---- FclContinuousMotionValidator ------------------------------------------------

FclContinuousMotionValidator::FclContinuousMotionValidator(const ob::SpaceInformationPtr& si, PlanningSpacePtr space,
                                                           std::shared_ptr<const FclScene> scene,
                                                           const FclCcdOptions& options)
    : CountedMotionValidator(si), space_(std::move(space)), scene_(std::move(scene)), options_(options) {
  detail::checkCheckerArguments("FclContinuousMotionValidator", "FclScene", si, space_, scene_.get());
  if (options_.num_max_iterations < 2) {
    throw InvalidInputError("FclContinuousMotionValidator: num_max_iterations " +
                            std::to_string(options_.num_max_iterations) + " is below 2");
  }
  if (!(options_.toc_err > 0.0)) {
    throw InvalidInputError("FclContinuousMotionValidator: toc_err must be positive");
  }
}

FclScene::Continuous FclContinuousMotionValidator::run(const ob::State* s1, const ob::State* s2) const {
  const EdgeMotion motion = space_->motion(s1, s2);
  const FclScene::Continuous c =
      scene_->continuousCollide(space_->pose(s1), space_->pose(s2), motion.rotates(), options_);
  counters_.addPairQueries(static_cast<std::uint64_t>(c.pair_queries));
  return c;
}

bool FclContinuousMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  CheckerCounters::Timer timer(counters_);
  counters_.addMotionCheck();
  // As OMPL.app: s1 assumed valid, s2 checked as a state first.
  const bool valid = si_->isValid(s2) && !run(s1, s2).collides;
  countOmpl(valid);
  return valid;
}

bool FclContinuousMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                               std::pair<ob::State*, double>& lastValid) const {
  CheckerCounters::Timer timer(counters_);
  counters_.addMotionCheck();
  const FclScene::Continuous c = run(s1, s2);
  double first_invalid = c.collides ? c.time : 2.0;
  if (first_invalid > 1.0 && !si_->isValid(s2)) first_invalid = 1.0;
  if (first_invalid > 1.0) {
    countOmpl(true);
    return true;
  }
  setLastValid(*si_, s1, s2, first_invalid, lastValid);
  countOmpl(false);
  return false;
}

}  // namespace mddual::planning
