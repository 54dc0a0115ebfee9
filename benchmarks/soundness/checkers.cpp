// The four checkers of the soundness suite, each on its own SpaceInformation
// over the case's space.
#include <ompl/base/DiscreteMotionValidator.h>

#include <chrono>
#include <stdexcept>

#include "cases.h"
#include "mddual/error.h"
#include "mddual/planning/fcl_checkers.h"
#include "mddual/planning/hull_cast_checkers.h"
#include "mddual/planning/mdd_checkers.h"

namespace mddual::soundness {

namespace ob = ompl::base;
using namespace mddual::planning;

const std::vector<std::string>& checkerNames() {
  static const std::vector<std::string> names = {"mdd", "fcl", "fcl-continuous", "hull-cast"};
  return names;
}

ob::SpaceInformationPtr makeChecker(const std::string& checker, const Scene& s) {
  auto si = std::make_shared<ob::SpaceInformation>(s.space->stateSpace());
  if (checker == "mdd") {
    auto scene = std::make_shared<MddScene>(s.robot, s.world);
    si->setStateValidityChecker(std::make_shared<MddStateValidityChecker>(si, s.space, scene));
    si->setMotionValidator(std::make_shared<MddMotionValidator>(si, s.space, scene));
  } else {
    auto fcl = std::make_shared<FclScene>(s.robot, s.world);
    si->setStateValidityChecker(std::make_shared<FclStateValidityChecker>(si, s.space, fcl));
    if (checker == "fcl") {
      // OMPL's default: states at the space's resolution (1% of its extent).
      si->setMotionValidator(std::make_shared<ob::DiscreteMotionValidator>(si));
    } else if (checker == "fcl-continuous") {
      si->setMotionValidator(std::make_shared<FclContinuousMotionValidator>(si, s.space, fcl));
    } else if (checker == "hull-cast") {
      auto hull = std::make_shared<HullCastScene>(s.robot, s.world);
      si->setMotionValidator(std::make_shared<HullCastMotionValidator>(si, s.space, hull));
    } else {
      throw InvalidInputError("soundness: unknown checker '" + checker + "'");
    }
  }
  si->setup();
  return si;
}

CheckerRun runChecker(const ob::SpaceInformation& si, const Case& c, const Scene& s) {
  CheckerRun run;
  const ob::MotionValidatorPtr& motion = si.getMotionValidator();
  std::vector<ob::State*> states;
  for (const auto& [X1, X2] : c.edges) {
    states.push_back(makeState(s, X1));
    states.push_back(makeState(s, X2));
  }
  // An untimed pass first: what a checker builds on first use (the MDD
  // scene's enlarged pieces for rotating edges) is paid once per scene in a
  // planner's thousands of checks, not per edge. Then the timed pass.
  std::vector<bool> first;
  for (std::size_t i = 0; i < states.size(); i += 2) first.push_back(motion->checkMotion(states[i], states[i + 1]));
  for (std::size_t i = 0; i < states.size(); i += 2) {
    const auto start = std::chrono::steady_clock::now();
    const bool valid = motion->checkMotion(states[i], states[i + 1]);
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    if (valid != first[i / 2]) throw std::logic_error("soundness: '" + c.family + "': a checker changed its answer");
    run.valid.push_back(valid);
    run.seconds.push_back(elapsed.count());
  }
  for (ob::State* state : states) s.space->stateSpace()->freeState(state);
  return run;
}

}  // namespace mddual::soundness
