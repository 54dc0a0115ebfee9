// fcl-continuous: FclStateValidityChecker + FclContinuousMotionValidator with
// FCL's conservative advancement (libccd) by default
// (SetupOptions::continuous_solver selects the naive solver).
#include "mddual/planning/checker_registry.h"

namespace mddual::planning {

namespace {

InstalledChecker installFclContinuous(const RigidCheckerContext& c) {
  auto scene = std::make_shared<FclScene>(c.robot, c.world);
  auto states = std::make_shared<FclStateValidityChecker>(c.si, c.space, scene);
  FclCcdOptions ccd;
  ccd.solver = c.options.continuous_solver;
  auto motions = std::make_shared<FclContinuousMotionValidator>(c.si, c.space, scene, ccd);
  states->setTiming(false);
  motions->setTiming(false);
  c.si->setStateValidityChecker(states);
  c.si->setMotionValidator(motions);
  return countsOf(states, motions);
}

}  // namespace

RigidChecker fclContinuousChecker() {
  return {"fcl-continuous", "FCL states + FCL's continuous collision (conservative advancement) on each edge",
          &installFclContinuous};
}

}  // namespace mddual::planning
