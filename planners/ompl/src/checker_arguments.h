// The argument check shared by the MDD and FCL checkers' constructors.
#pragma once

#include <ompl/base/SpaceInformation.h>

#include <string>

#include "mddual/error.h"
#include "mddual/planning/state_space.h"

namespace mddual::planning::detail {

/// Throws InvalidInputError naming `who` when the SpaceInformation, the
/// PlanningSpace or the scene (named `scene_type` in the message) is null, or when
/// the SpaceInformation's state space is not the PlanningSpace's.
inline void checkCheckerArguments(const char* who, const char* scene_type, const ompl::base::SpaceInformationPtr& si,
                                  const PlanningSpacePtr& space, const void* scene) {
  const std::string name(who);
  if (!si) throw InvalidInputError(name + ": the SpaceInformation is null");
  if (!space) throw InvalidInputError(name + ": the PlanningSpace is null");
  if (!scene) throw InvalidInputError(name + ": the " + scene_type + " is null");
  if (si->getStateSpace() != space->stateSpace()) {
    throw InvalidInputError(name + ": the SpaceInformation's state space is not the PlanningSpace's (" +
                            si->getStateSpace()->getName() + " vs " + space->stateSpace()->getName() +
                            "); for a state space made elsewhere, wrap it (PlanningSpace::wrap) or use "
                            "useExactChecking()");
  }
}

}  // namespace mddual::planning::detail
