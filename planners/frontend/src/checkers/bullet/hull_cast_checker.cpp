// hull-cast: the Bullet peer (hull_cast_checkers.h) as a checker of the
// benchmark tables. Compiled into mddual_hull_cast, not mddual_planning (the
// tables must build without Bullet), so its entry is appended by
// registerHullCastCheckers() instead of a line in registry.cpp.
//   rigid: FclStateValidityChecker + HullCastMotionValidator;
//   arm:   FclArmStateValidityChecker + ArmHullCastMotionValidator.
#include "mddual/planning/checker_registry.h"
#include "mddual/planning/hull_cast_checkers.h"

namespace mddual::planning {

namespace {

InstalledChecker installHullCast(const RigidCheckerContext& c) {
  auto states = std::make_shared<FclStateValidityChecker>(c.si, c.space, std::make_shared<FclScene>(c.robot, c.world));
  auto motions =
      std::make_shared<HullCastMotionValidator>(c.si, c.space, std::make_shared<HullCastScene>(c.robot, c.world));
  states->setTiming(false);
  motions->setTiming(false);
  c.si->setStateValidityChecker(states);
  c.si->setMotionValidator(motions);
  return countsOf(states, motions);
}

InstalledChecker installArmHullCast(const ArmCheckerContext& c) {
  auto states = std::make_shared<FclArmStateValidityChecker>(c.si, c.space, c.fcl);
  auto motions =
      std::make_shared<ArmHullCastMotionValidator>(c.si, c.space, std::make_shared<ArmHullCastScene>(c.scene));
  c.si->setStateValidityChecker(states);
  c.si->setMotionValidator(motions);
  return countsOf(states, motions);
}

}  // namespace

RigidChecker hullCastChecker() {
  return {"hull-cast",
          "FCL states + Bullet's cast of each piece's hull between OMPL's states (Tesseract's; misses turns)",
          &installHullCast};
}

ArmChecker armHullCastChecker() {
  return {"hull-cast", "FCL states + Bullet's cast of each link piece's hull between OMPL's states (Tesseract's)",
          &installArmHullCast};
}

void registerHullCastCheckers() {
  addRigidChecker(hullCastChecker());
  addArmChecker(armHullCastChecker());
}

}  // namespace mddual::planning
