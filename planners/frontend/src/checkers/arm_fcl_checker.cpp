// Arm fcl and fcl-fine: FclArmStateValidityChecker + OMPL's
// DiscreteMotionValidator, at OMPL's default resolution (what MoveIt runs)
// or with segments of at most ArmCheckerContext::fine_resolution radians.
// Both check the pairs the exact checker does, on the same pieces.
#include <ompl/base/DiscreteMotionValidator.h>

#include <algorithm>

#include "mddual/planning/checker_registry.h"

namespace mddual::planning {

namespace {

InstalledChecker installArmFcl(const ArmCheckerContext& c) {
  auto states = std::make_shared<FclArmStateValidityChecker>(c.si, c.space, c.fcl);
  c.si->setStateValidityChecker(states);
  c.si->setMotionValidator(std::make_shared<ompl::base::DiscreteMotionValidator>(c.si));
  return countsOf(states);
}

InstalledChecker installArmFclFine(const ArmCheckerContext& c) {
  InstalledChecker out = installArmFcl(c);
  const ompl::base::StateSpacePtr& space = c.space->stateSpace();
  space->setup();
  space->setLongestValidSegmentFraction(std::min(1.0, c.fine_resolution / space->getMaximumExtent()));
  return out;
}

}  // namespace

ArmChecker armFclChecker() {
  return {"fcl", "FCL states + OMPL's discrete motion validator at OMPL's default resolution", &installArmFcl};
}

ArmChecker armFclFineChecker() {
  return {"fcl-fine", "FCL states + OMPL's discrete motion validator with segments of at most 1/32 rad",
          &installArmFclFine};
}

}  // namespace mddual::planning
