// The checkers of the soundness suite, each on its own SpaceInformation over
// the case's space: five for rigid bodies, four for the arm family (the arm
// checkers of the same names as `mddual bench` installs them). hull-cast is
// the Bullet cast over OMPL's segments (Tesseract's motion validator, what
// `mddual bench` plans with), hull-cast-edge one cast between the edge's two
// ends (MoveIt's cast between two states). On the mesh families
// fcl-continuous-obb and fcl-continuous-rss are FCL's conservative advancement
// on BVHModel<OBB> and BVHModel<RSS> (fcl_bvh.h), fcl-continuous being
// FclScene's on BVHModel<OBBRSS>.
#include <ompl/base/DiscreteMotionValidator.h>

#include <chrono>
#include <stdexcept>

#include "cases.h"
#include "fcl_bvh.h"
#include "mddual/error.h"
#include "mddual/planning/arm_checkers.h"
#include "mddual/planning/fcl_checkers.h"
#include "mddual/planning/hull_cast_checkers.h"
#include "mddual/planning/mdd_checkers.h"

namespace mddual::soundness {

namespace ob = ompl::base;
using namespace mddual::planning;

const std::vector<std::string>& checkerNames() {
  static const std::vector<std::string> names = {"mdd", "fcl", "fcl-continuous", "hull-cast", "hull-cast-edge"};
  return names;
}

bool meshFamily(const std::string& family) {
  return family == "obb-hierarchy" || family == "sliver-mesh";
}

const std::vector<std::string>& checkerNames(const std::string& family) {
  static const std::vector<std::string> arm = {"mdd", "fcl", "hull-cast", "hull-cast-edge"};
  static const std::vector<std::string> mesh = {
      "mdd", "fcl", "fcl-continuous", "fcl-continuous-obb", "fcl-continuous-rss", "hull-cast", "hull-cast-edge"};
  if (family == "arm-rotating-link") return arm;
  return meshFamily(family) ? mesh : checkerNames();
}

namespace {

CastSegments castSegments(const std::string& checker) {
  return checker == "hull-cast-edge" ? CastSegments::kWholeEdge : CastSegments::kResolution;
}

ob::SpaceInformationPtr makeArmChecker(const std::string& checker, const Scene& s) {
  auto si = std::make_shared<ob::SpaceInformation>(s.arm_space->stateSpace());
  if (checker == "mdd") {
    useExactChecking(si, s.arm_space, s.arm);
  } else {
    si->setStateValidityChecker(
        std::make_shared<FclArmStateValidityChecker>(si, s.arm_space, std::make_shared<FclArmScene>(s.arm)));
    if (checker == "fcl") {
      si->setMotionValidator(std::make_shared<ob::DiscreteMotionValidator>(si));
    } else if (checker == "hull-cast" || checker == "hull-cast-edge") {
      si->setMotionValidator(std::make_shared<ArmHullCastMotionValidator>(
          si, s.arm_space, std::make_shared<ArmHullCastScene>(s.arm), castSegments(checker)));
    } else {
      throw InvalidInputError("soundness: unknown arm checker '" + checker + "'");
    }
  }
  si->setup();
  return si;
}

}  // namespace

ob::SpaceInformationPtr makeChecker(const std::string& checker, const Scene& s) {
  if (s.arm) return makeArmChecker(checker, s);
  auto si = std::make_shared<ob::SpaceInformation>(s.space->stateSpace());
  if (checker == "mdd") {
    auto scene = std::make_shared<MddScene>(s.robot, s.world);
    si->setStateValidityChecker(std::make_shared<MddStateValidityChecker>(si, s.space, scene));
    si->setMotionValidator(std::make_shared<MddMotionValidator>(si, s.space, scene));
  } else {
    auto fcl = std::make_shared<FclScene>(s.robot, s.world);
    si->setStateValidityChecker(std::make_shared<FclStateValidityChecker>(si, s.space, fcl));
    if (checker == "fcl") {
      // OMPL's default: states at the space's resolution (1% of its extent).
      si->setMotionValidator(std::make_shared<ob::DiscreteMotionValidator>(si));
    } else if (checker == "fcl-continuous") {
      si->setMotionValidator(std::make_shared<FclContinuousMotionValidator>(si, s.space, fcl));
    } else if (checker == "fcl-continuous-obb" || checker == "fcl-continuous-rss") {
      si->setMotionValidator(
          makeFclBvhContinuous(si, s, checker == "fcl-continuous-obb" ? FclBvh::kObb : FclBvh::kRss));
    } else if (checker == "hull-cast" || checker == "hull-cast-edge") {
      auto hull = std::make_shared<HullCastScene>(s.robot, s.world);
      si->setMotionValidator(std::make_shared<HullCastMotionValidator>(si, s.space, hull, castSegments(checker)));
    } else {
      throw InvalidInputError("soundness: unknown checker '" + checker + "'");
    }
  }
  si->setup();
  return si;
}

CheckerRun runChecker(const ob::SpaceInformation& si, const Case& c, const Scene& s) {
  CheckerRun run;
  const ob::MotionValidatorPtr& motion = si.getMotionValidator();
  std::vector<ob::State*> states;
  for (int e = 0; e < c.numEdges(); ++e) {
    const auto [a, b] = makeEdgeStates(c, s, e);
    states.push_back(a);
    states.push_back(b);
  }
  // An untimed pass first: what a checker builds on first use (the MDD
  // scene's enlarged pieces for rotating edges) is paid once per scene in a
  // planner's thousands of checks, not per edge. Then the timed pass.
  std::vector<bool> first;
  for (std::size_t i = 0; i < states.size(); i += 2) first.push_back(motion->checkMotion(states[i], states[i + 1]));
  for (std::size_t i = 0; i < states.size(); i += 2) {
    const auto start = std::chrono::steady_clock::now();
    const bool valid = motion->checkMotion(states[i], states[i + 1]);
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    if (valid != first[i / 2]) throw std::logic_error("soundness: '" + c.family + "': a checker changed its answer");
    run.valid.push_back(valid);
    run.seconds.push_back(elapsed.count());
  }
  for (ob::State* state : states) si.freeState(state);
  return run;
}

}  // namespace mddual::soundness
