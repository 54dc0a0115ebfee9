// One-call set-up of the MDD checkers on OMPL objects the user made:
//
//   auto space = std::make_shared<ompl::base::SE3StateSpace>();
//   space->setBounds(bounds);                        // before the call
//   auto si = std::make_shared<ompl::base::SpaceInformation>(space);
//   ExactChecking exact = useExactChecking(si, robot, world);
//   si->setup();                                     // or let the planner do it
//
// useExactChecking() wraps si's state space (PlanningSpace::wrap: SE2, SE3,
// R^2, R^3, or a compound space with one of those as its pose part; the
// accepted layouts and the errors for the others are listed in state_space.h),
// builds an MddScene over the robot and the world, and installs an
// MddStateValidityChecker and an MddMotionValidator on si (replacing any it
// had; OMPL then needs si->setup() again, which planners call themselves).
// The returned handles give the counters, the scene for directed clearance
// queries (clearance.h) and the map between states and poses.
//
// The checkers keep their guarantees (mdd_checkers.h): OMPL's lastValid
// contract and thread-safe const methods; the scene's extra coordinates of a
// compound space only count through the space's bounds.
#pragma once

#include <ompl/base/SpaceInformation.h>
#include <memory>

#include "mddual/planning/mdd_checkers.h"
#include "mddual/planning/mdd_scene.h"
#include "mddual/planning/state_space.h"
#include "mddual/scene/scene.h"

namespace mddual::planning {

/// Options of useExactChecking().
struct ExactCheckingOptions {
  /// Where the pose is in si's state space, and the fixed z / orientation of
  /// an R^2 / R^3 pose part.
  SpaceWrapOptions layout;
  /// The MddScene's options (rotating-edge tolerance).
  MddSceneOptions scene;
};

/// What useExactChecking() installed.
struct ExactChecking {
  PlanningSpacePtr space;  ///< wraps si->getStateSpace(): state <-> pose, OMPL's interpolation
  std::shared_ptr<const MddScene> scene;
  MddStateValidityCheckerPtr state_checker;  ///< installed with si->setStateValidityChecker
  MddMotionValidatorPtr motion_validator;    ///< installed with si->setMotionValidator
};

/// Installs the MDD checkers on `si` (see the file comment). Throws
/// InvalidInputError for a null si, robot or world, a state space whose layout
/// is not accepted (the message names the space and the reason), or bad scene
/// options; si is left untouched then.
ExactChecking useExactChecking(const ompl::base::SpaceInformationPtr& si, std::shared_ptr<const scene::RigidBody> robot,
                               std::shared_ptr<const scene::World> world,
                               const ExactCheckingOptions& options = ExactCheckingOptions());

/// The same over an MddScene already built (shared by several
/// SpaceInformations: its warm starts are per thread and per scene).
ExactChecking useExactChecking(const ompl::base::SpaceInformationPtr& si, std::shared_ptr<const MddScene> scene,
                               const SpaceWrapOptions& layout = SpaceWrapOptions());

}  // namespace mddual::planning
