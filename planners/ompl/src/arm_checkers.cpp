// The OMPL checkers for articulated robots (arm_checkers.h).
#include "mddual/planning/arm_checkers.h"

#include <algorithm>
#include <limits>
#include <string>

#include "mddual/error.h"
#include "mddual/planning/mdd_checkers.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;

void checkArguments(const char* who, const ob::SpaceInformationPtr& si, const ArmSpacePtr& space, const void* scene,
                    const scene::RobotModel* scene_model) {
  const std::string name(who);
  if (!si) throw InvalidInputError(name + ": the SpaceInformation is null");
  if (!space) throw InvalidInputError(name + ": the ArmSpace is null");
  if (scene == nullptr) throw InvalidInputError(name + ": the scene is null");
  if (si->getStateSpace() != space->stateSpace()) {
    throw InvalidInputError(name + ": the SpaceInformation's state space is not the ArmSpace's (" +
                            si->getStateSpace()->getName() + " vs " + space->stateSpace()->getName() +
                            "); wrap the space with ArmSpace::wrap");
  }
  if (scene_model != &space->model()) {
    throw InvalidInputError(name + ": the ArmSpace and the scene have different robot models");
  }
}

void requireState(const ob::State* state, const char* what) {
  if (state == nullptr) throw InvalidInputError(std::string(what) + " is null");
}

}  // namespace

// ---- ArmStateValidityChecker -------------------------------------------------------

ArmStateValidityChecker::ArmStateValidityChecker(const ob::SpaceInformationPtr& si, ArmSpacePtr space,
                                                 std::shared_ptr<const ArmScene> scene)
    : ob::StateValidityChecker(si), space_(std::move(space)), scene_(std::move(scene)) {
  checkArguments("ArmStateValidityChecker", si, space_, scene_.get(), scene_ ? &scene_->model() : nullptr);
  specs_.clearanceComputationType = ob::StateValidityCheckerSpecs::EXACT;
}

bool ArmStateValidityChecker::isValid(const ob::State* state) const {
  requireState(state, "ArmStateValidityChecker::isValid: the state");
  CheckerCounters::Timer timer(counters_);
  counters_.addStateCheck();
  if (!si_->satisfiesBounds(state)) return false;
  const std::vector<double> q = space_->configuration(state);
  return !scene_->collides(q.data());
}

double ArmStateValidityChecker::clearance(const ob::State* state) const {
  requireState(state, "ArmStateValidityChecker::clearance: the state");
  CheckerCounters::Timer timer(counters_);
  counters_.addStateCheck();
  const std::vector<double> q = space_->configuration(state);
  return scene_->clearance(q.data());
}

// ---- ArmMotionValidator ------------------------------------------------------------

ArmMotionValidator::ArmMotionValidator(const ob::SpaceInformationPtr& si, ArmSpacePtr space,
                                       std::shared_ptr<const ArmScene> scene)
    : CountedMotionValidator(si), space_(std::move(space)), scene_(std::move(scene)) {
  checkArguments("ArmMotionValidator", si, space_, scene_.get(), scene_ ? &scene_->model() : nullptr);
}

ArmEdgeResult ArmMotionValidator::edgeContact(const ob::State* s1, const ob::State* s2, EdgeQuery query,
                                              double fraction_tolerance) const {
  requireState(s1, "ArmMotionValidator: s1");
  requireState(s2, "ArmMotionValidator: s2");
  const std::size_t n = space_->fixedConfiguration().size();
  std::vector<double> q0(n), q1(n);
  space_->edge(s1, s2, q0.data(), q1.data());
  const ArmEdgeResult r = scene_->checkEdge(q0.data(), q1.data(), query, fraction_tolerance);
  counters_.addPairQueries(static_cast<std::uint64_t>(r.distance_queries));
  counters_.addSubEdges(static_cast<std::uint64_t>(r.intervals));
  return r;
}

bool ArmMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  CheckerCounters::Timer timer(counters_);
  counters_.addMotionCheck();
  // Straight segments between states within box bounds stay within them.
  const bool valid =
      si_->satisfiesBounds(s2) && si_->satisfiesBounds(s1) && !edgeContact(s1, s2, EdgeQuery::kValidity).collides;
  countOmpl(valid);
  return valid;
}

bool ArmMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                     std::pair<ob::State*, double>& lastValid) const {
  CheckerCounters::Timer timer(counters_);
  counters_.addMotionCheck();
  double first_invalid = 0.0;
  if (si_->satisfiesBounds(s1)) {
    // lastValid: a bound as fine as OMPL's discrete check's (one of its steps).
    const double tolerance = 1.0 / std::max(1u, si_->getStateSpace()->validSegmentCount(s1, s2));
    const ArmEdgeResult r = edgeContact(s1, s2, EdgeQuery::kLastValid, tolerance);
    first_invalid = r.collides ? r.fraction : std::numeric_limits<double>::infinity();
    // Bounds: both ends within them keep the whole segment within them;
    // otherwise s2 alone is out, and the contact bound stands below 1.
    if (!si_->satisfiesBounds(s2)) first_invalid = std::min(first_invalid, 1.0);
  }
  if (first_invalid > 1.0) {
    countOmpl(true);
    return true;
  }
  setLastValid(*si_, s1, s2, first_invalid, lastValid);
  countOmpl(false);
  return false;
}

// ---- FCL baseline ------------------------------------------------------------------

FclArmScene::FclArmScene(std::shared_ptr<const ArmScene> scene) : scene_(std::move(scene)) {
  if (!scene_) throw InvalidInputError("FclArmScene: null scene");
  const scene::RobotModel& m = scene_->model();
  auto body = [&](int k) {
    return std::make_shared<const scene::RigidBody>(m.link(k).pieces, m.name() + ": " + m.link(k).name);
  };
  const auto world = std::make_shared<const scene::World>(scene_->world().pieces(), scene_->world().name());
  world_pairs_.resize(static_cast<std::size_t>(m.numLinks()));
  for (int k = 0; k < m.numLinks(); ++k) {
    if (!m.link(k).pieces.empty() && !world->pieces().empty() && !scene_->filter().allowedWithWorld(k)) {
      world_pairs_[static_cast<std::size_t>(k)] = std::make_unique<FclScene>(body(k), world);
    }
  }
  for (const auto& [k, l] : scene_->selfPairs()) {
    const auto other = std::make_shared<const scene::World>(m.link(l).pieces, m.link(l).name);
    self_pairs_.push_back(std::make_unique<FclScene>(body(k), other));
  }
}

bool FclArmScene::collides(const double* q) const {
  std::vector<Eigen::Isometry3d> X_WL;
  scene_->linkPoses(q, &X_WL);
  for (std::size_t k = 0; k < world_pairs_.size(); ++k) {
    if (world_pairs_[k] && world_pairs_[k]->collides(X_WL[k])) return true;
  }
  const auto& pairs = scene_->selfPairs();
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const auto [k, l] = pairs[p];
    // Link k posed in link l's frame.
    if (self_pairs_[p]->collides(X_WL[static_cast<std::size_t>(l)].inverse() * X_WL[static_cast<std::size_t>(k)])) {
      return true;
    }
  }
  return false;
}

FclArmStateValidityChecker::FclArmStateValidityChecker(const ob::SpaceInformationPtr& si, ArmSpacePtr space,
                                                       std::shared_ptr<const FclArmScene> scene)
    : ob::StateValidityChecker(si), space_(std::move(space)), scene_(std::move(scene)) {
  checkArguments("FclArmStateValidityChecker", si, space_, scene_.get(), scene_ ? &scene_->scene().model() : nullptr);
}

bool FclArmStateValidityChecker::isValid(const ob::State* state) const {
  requireState(state, "FclArmStateValidityChecker::isValid: the state");
  CheckerCounters::Timer timer(counters_);
  counters_.addStateCheck();
  if (!si_->satisfiesBounds(state)) return false;
  const std::vector<double> q = space_->configuration(state);
  return !scene_->collides(q.data());
}

ArmChecking useExactChecking(const ob::SpaceInformationPtr& si, ArmSpacePtr space,
                             std::shared_ptr<const ArmScene> scene) {
  ArmChecking out;
  out.state_checker = std::make_shared<ArmStateValidityChecker>(si, space, scene);
  out.motion_validator = std::make_shared<ArmMotionValidator>(si, space, scene);
  si->setStateValidityChecker(out.state_checker);
  si->setMotionValidator(out.motion_validator);
  out.space = std::move(space);
  out.scene = std::move(scene);
  return out;
}

}  // namespace mddual::planning
