// The OMPL checkers for articulated robots: ArmStateValidityChecker and
// ArmMotionValidator over an ArmScene (exact state checks, certified edges)
// and an ArmSpace (states <-> configurations, OMPL's interpolation), the FCL
// baseline on the same link pieces (FclArmScene, FclArmStateValidityChecker,
// used with OMPL's DiscreteMotionValidator), and useExactChecking() for a
// joint-space SpaceInformation the user made.
//
//   auto model = std::make_shared<const scene::RobotModel>(scene::loadRobotModel("arm.urdf"));
//   const scene::Srdf srdf = scene::loadSrdf("arm.srdf");
//   auto space = ArmSpace::make(model, scene::groupVariables(srdf, *model, "arm"));
//   auto si = std::make_shared<ompl::base::SpaceInformation>(space->stateSpace());
//   auto scene = std::make_shared<ArmScene>(model, world, scene::AllowedCollisions(*model, srdf));
//   ArmChecking installed = useExactChecking(si, space, scene);
//
// The motion validator keeps OMPL's contract to the letter: checkMotion(s1,
// s2) is true only when every state of the edge is valid (certified: no
// link touches the world or another checked link anywhere on it, and s2 is
// within the bounds); on an invalid edge, checkMotion(s1, s2, lastValid)
// sets lastValid.second to a fraction whose state, and every state before
// it, is valid, and lastValid.first (when not null) to that state.
//
// Thread safety: const methods may be called from any number of threads.
#pragma once

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/util/ClassForward.h>

#include <memory>
#include <utility>
#include <vector>

#include "mddual/planning/arm_scene.h"
#include "mddual/planning/arm_space.h"
#include "mddual/planning/counters.h"
#include "mddual/planning/fcl_checkers.h"

namespace mddual::planning {

OMPL_CLASS_FORWARD(ArmStateValidityChecker);
OMPL_CLASS_FORWARD(ArmMotionValidator);
OMPL_CLASS_FORWARD(FclArmScene);
OMPL_CLASS_FORWARD(FclArmStateValidityChecker);

/// Valid iff within the bounds and ArmScene::collides is false. clearance()
/// is exact (ArmScene::clearance: smallest signed distance over the checked
/// pairs).
class ArmStateValidityChecker : public ompl::base::StateValidityChecker {
 public:
  /// Throws InvalidInputError for a null argument or when si's state space is
  /// not space->stateSpace(), or the space's robot is not the scene's.
  ArmStateValidityChecker(const ompl::base::SpaceInformationPtr& si, ArmSpacePtr space,
                          std::shared_ptr<const ArmScene> scene);
  bool isValid(const ompl::base::State* state) const override;
  double clearance(const ompl::base::State* state) const override;
  CheckerCounts counts() const { return counters_.read(); }
  void resetCounts() { counters_.reset(); }
  void setTiming(bool on) { counters_.setTiming(on); }

 private:
  ArmSpacePtr space_;
  std::shared_ptr<const ArmScene> scene_;
  mutable CheckerCounters counters_;
};

/// Certified motion validity (see the file comment and ArmScene::checkEdge).
class ArmMotionValidator : public CountedMotionValidator {
 public:
  /// Throws as ArmStateValidityChecker.
  ArmMotionValidator(const ompl::base::SpaceInformationPtr& si, ArmSpacePtr space,
                     std::shared_ptr<const ArmScene> scene);
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;
  /// The edge's result (ArmScene::checkEdge on the configurations of s1 and
  /// s2 under OMPL's interpolation); bounds are not looked at.
  ArmEdgeResult edgeContact(const ompl::base::State* s1, const ompl::base::State* s2, EdgeQuery query,
                            double fraction_tolerance = 0.0) const;

 private:
  ArmSpacePtr space_;
  std::shared_ptr<const ArmScene> scene_;
  mutable std::mutex ompl_counts_mutex_;
};

/// FCL's collide() on the same pairs as an ArmScene: each link's pieces
/// against the world, and each checked link pair, as FclScene objects
/// (fcl_checkers.h) on identical geometry.
class FclArmScene {
 public:
  explicit FclArmScene(std::shared_ptr<const ArmScene> scene);
  /// Whether FCL finds a contact at configuration q.
  bool collides(const double* q) const;
  const ArmScene& scene() const { return *scene_; }

 private:
  std::shared_ptr<const ArmScene> scene_;
  std::vector<std::unique_ptr<FclScene>> world_pairs_;  ///< per link with pieces (null without)
  std::vector<std::unique_ptr<FclScene>> self_pairs_;   ///< per ArmScene::selfPairs() entry: link k vs link l
};

/// State validity on FCL (bounds, then FclArmScene::collides); edges with
/// OMPL's DiscreteMotionValidator at the space's resolution.
class FclArmStateValidityChecker : public ompl::base::StateValidityChecker {
 public:
  FclArmStateValidityChecker(const ompl::base::SpaceInformationPtr& si, ArmSpacePtr space,
                             std::shared_ptr<const FclArmScene> scene);
  bool isValid(const ompl::base::State* state) const override;
  CheckerCounts counts() const { return counters_.read(); }
  void resetCounts() { counters_.reset(); }
  void setTiming(bool on) { counters_.setTiming(on); }

 private:
  ArmSpacePtr space_;
  std::shared_ptr<const FclArmScene> scene_;
  mutable CheckerCounters counters_;
};

/// What useExactChecking() installed on a joint-space SpaceInformation.
struct ArmChecking {
  ArmSpacePtr space;
  std::shared_ptr<const ArmScene> scene;
  ArmStateValidityCheckerPtr state_checker;
  ArmMotionValidatorPtr motion_validator;
};

/// Installs the arm checkers on `si`, whose state space must be
/// space->stateSpace() (ArmSpace::wrap maps a space the user made, joints by
/// name). Throws InvalidInputError for a null argument or a mismatch; si is
/// left untouched then.
ArmChecking useExactChecking(const ompl::base::SpaceInformationPtr& si, ArmSpacePtr space,
                             std::shared_ptr<const ArmScene> scene);

}  // namespace mddual::planning
