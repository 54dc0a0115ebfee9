#include "mddual/planning/exact_checking.h"

#include <utility>

#include "mddual/error.h"

namespace mddual::planning {

ExactChecking useExactChecking(const ompl::base::SpaceInformationPtr& si, std::shared_ptr<const MddScene> scene,
                               const SpaceWrapOptions& layout) {
  if (!si) throw InvalidInputError("useExactChecking: the SpaceInformation is null");
  if (!scene) throw InvalidInputError("useExactChecking: the MddScene is null");
  if (!si->getStateSpace()) throw InvalidInputError("useExactChecking: the SpaceInformation has no state space");
  ExactChecking out;
  out.space = PlanningSpace::wrap(si->getStateSpace(), layout);
  out.scene = std::move(scene);
  out.state_checker = std::make_shared<MddStateValidityChecker>(si, out.space, out.scene);
  out.motion_validator = std::make_shared<MddMotionValidator>(si, out.space, out.scene);
  // Everything that can throw has run: only now change si.
  si->setStateValidityChecker(out.state_checker);
  si->setMotionValidator(out.motion_validator);
  return out;
}

ExactChecking useExactChecking(const ompl::base::SpaceInformationPtr& si, std::shared_ptr<const scene::RigidBody> robot,
                               std::shared_ptr<const scene::World> world, const ExactCheckingOptions& options) {
  if (!si) throw InvalidInputError("useExactChecking: the SpaceInformation is null");
  if (!si->getStateSpace()) throw InvalidInputError("useExactChecking: the SpaceInformation has no state space");
  // The layout first: a refused space costs no scene build.
  PlanningSpace::wrap(si->getStateSpace(), options.layout);
  auto scene = std::make_shared<const MddScene>(std::move(robot), std::move(world), options.scene);
  return useExactChecking(si, std::move(scene), options.layout);
}

}  // namespace mddual::planning
