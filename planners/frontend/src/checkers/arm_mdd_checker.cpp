// Arm mdd: ArmStateValidityChecker + ArmMotionValidator (exact states,
// certified edges), as useExactChecking installs them.
#include "mddual/planning/checker_registry.h"

namespace mddual::planning {

namespace {

InstalledChecker installArmMdd(const ArmCheckerContext& c) {
  const ArmChecking installed = useExactChecking(c.si, c.space, c.scene);
  return countsOf(installed.state_checker, installed.motion_validator);
}

}  // namespace

ArmChecker armMddChecker() {
  return {"mdd", "exact link states and certified joint-space edges (never a colliding edge called free)",
          &installArmMdd};
}

}  // namespace mddual::planning
