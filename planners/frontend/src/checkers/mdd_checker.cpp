// mdd: MddStateValidityChecker + MddMotionValidator on one MddScene (exact
// translating edges, sound rotating edges).
#include "mddual/planning/checker_registry.h"

namespace mddual::planning {

namespace {

InstalledChecker installMdd(const RigidCheckerContext& c) {
  auto scene = std::make_shared<MddScene>(c.robot, c.world, c.options.mdd);
  auto states = std::make_shared<MddStateValidityChecker>(c.si, c.space, scene);
  auto motions = std::make_shared<MddMotionValidator>(c.si, c.space, scene);
  states->setTiming(false);
  motions->setTiming(false);
  c.si->setStateValidityChecker(states);
  c.si->setMotionValidator(motions);
  InstalledChecker out = countsOf(states, motions);
  out.set_discarded_last_valid_fraction = [motions](double f) { motions->setDiscardedLastValidFraction(f); };
  out.mdd_scene = scene;
  return out;
}

}  // namespace

RigidChecker mddChecker() {
  return {"mdd", "MDD-DUAL: exact states, exact translating edges, sound rotating edges", &installMdd};
}

}  // namespace mddual::planning
