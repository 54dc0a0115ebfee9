// fcl: FclStateValidityChecker + OMPL's DiscreteMotionValidator at the
// space's resolution (what OMPL.app users run).
#include <ompl/base/DiscreteMotionValidator.h>

#include "mddual/planning/checker_registry.h"

namespace mddual::planning {

namespace {

InstalledChecker installFcl(const RigidCheckerContext& c) {
  auto states = std::make_shared<FclStateValidityChecker>(c.si, c.space, std::make_shared<FclScene>(c.robot, c.world));
  states->setTiming(false);
  c.si->setStateValidityChecker(states);
  c.si->setMotionValidator(std::make_shared<ompl::base::DiscreteMotionValidator>(c.si));
  return countsOf(states);
}

}  // namespace

RigidChecker fclChecker() {
  return {"fcl", "FCL states + OMPL's discrete motion validator at the space's resolution", &installFcl};
}

}  // namespace mddual::planning
