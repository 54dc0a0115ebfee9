// ArmSpace (arm_space.h).
#include "mddual/planning/arm_space.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>

#include <cmath>
#include <set>

#include "constants.h"
#include "mddual/error.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;

void requireVariables(const scene::RobotModel& model, const std::vector<int>& group) {
  if (group.empty()) throw InvalidInputError("ArmSpace: the group has no joints");
  std::set<int> seen;
  for (int v : group) {
    if (v < 0 || v >= model.numVariables()) {
      throw InvalidInputError("ArmSpace: variable " + std::to_string(v) + " is not one of robot '" + model.name() +
                              "' (it has " + std::to_string(model.numVariables()) + ")");
    }
    if (!seen.insert(v).second) throw InvalidInputError("ArmSpace: joint '" + model.variableName(v) + "' twice");
  }
}

}  // namespace

std::vector<double> ArmSpace::checkedFixed(const scene::RobotModel& model, std::vector<double> fixed) {
  if (fixed.empty()) return model.defaultConfiguration();
  if (static_cast<int>(fixed.size()) != model.numVariables()) {
    throw InvalidInputError("ArmSpace: the fixed configuration has " + std::to_string(fixed.size()) +
                            " values, robot '" + model.name() + "' " + std::to_string(model.numVariables()));
  }
  for (std::size_t v = 0; v < fixed.size(); ++v) {
    if (!std::isfinite(fixed[v])) {
      throw InvalidInputError("ArmSpace: the fixed value of joint '" + model.variableName(static_cast<int>(v)) +
                              "' is not finite");
    }
  }
  return fixed;
}

ArmSpacePtr ArmSpace::make(std::shared_ptr<const scene::RobotModel> model, const std::vector<int>& group,
                           std::vector<double> fixed) {
  if (!model) throw InvalidInputError("ArmSpace: null robot model");
  requireVariables(*model, group);
  bool any_continuous = false;
  for (int v : group) {
    any_continuous |= model->joint(model->variableJoint(v)).type == scene::JointType::kContinuous;
  }
  ob::StateSpacePtr space;
  const auto n = static_cast<unsigned int>(group.size());
  if (!any_continuous) {
    auto rv = std::make_shared<ob::RealVectorStateSpace>(n);
    ob::RealVectorBounds bounds(n);
    for (unsigned int i = 0; i < n; ++i) {
      const scene::Joint& j = model->joint(model->variableJoint(group[i]));
      bounds.setLow(i, j.lower);
      bounds.setHigh(i, j.upper);
      rv->setDimensionName(i, j.name);
    }
    rv->setBounds(bounds);
    space = rv;
  } else {
    auto compound = std::make_shared<ob::CompoundStateSpace>();
    for (int v : group) {
      const scene::Joint& j = model->joint(model->variableJoint(v));
      ob::StateSpacePtr sub;
      if (j.type == scene::JointType::kContinuous) {
        sub = std::make_shared<ob::SO2StateSpace>();
      } else {
        auto rv = std::make_shared<ob::RealVectorStateSpace>(1);
        rv->setBounds(j.lower, j.upper);
        sub = rv;
      }
      sub->setName(j.name);
      compound->addSubspace(sub, 1.0);
    }
    compound->lock();
    space = compound;
  }
  space->setName(model->name() + " joints");
  std::vector<std::string> joints;
  for (int v : group) joints.push_back(model->variableName(v));
  return wrap(space, std::move(model), joints, std::move(fixed));
}

ArmSpacePtr ArmSpace::wrap(ob::StateSpacePtr space, std::shared_ptr<const scene::RobotModel> model,
                           std::vector<std::string> joints, std::vector<double> fixed) {
  if (!space) throw InvalidInputError("ArmSpace::wrap: null state space");
  if (!model) throw InvalidInputError("ArmSpace::wrap: null robot model");
  const std::string who = "ArmSpace::wrap: state space '" + space->getName() + "'";
  // The coordinates: (name, SO2?) in the state's order.
  std::vector<std::pair<std::string, bool>> coordinates;
  if (auto* rv = dynamic_cast<ob::RealVectorStateSpace*>(space.get())) {
    for (unsigned int i = 0; i < rv->getDimension(); ++i) coordinates.emplace_back(rv->getDimensionName(i), false);
  } else if (auto* compound = dynamic_cast<ob::CompoundStateSpace*>(space.get())) {
    for (unsigned int c = 0; c < compound->getSubspaceCount(); ++c) {
      const ob::StateSpacePtr& sub = compound->getSubspace(c);
      if (dynamic_cast<ob::SO2StateSpace*>(sub.get()) != nullptr) {
        coordinates.emplace_back(sub->getName(), true);
      } else if (auto* one = dynamic_cast<ob::RealVectorStateSpace*>(sub.get()); one && one->getDimension() == 1) {
        coordinates.emplace_back(sub->getName(), false);
      } else {
        throw InvalidInputError(who + ": component " + std::to_string(c) + " ('" + sub->getName() +
                                "') is neither a 1-dimensional RealVectorStateSpace nor an SO2StateSpace");
      }
    }
  } else {
    throw InvalidInputError(who + ": not a RealVectorStateSpace or a CompoundStateSpace of joints");
  }
  if (!joints.empty()) {
    if (joints.size() != coordinates.size()) {
      throw InvalidInputError(who + ": " + std::to_string(joints.size()) + " joint names for " +
                              std::to_string(coordinates.size()) + " coordinates");
    }
    for (std::size_t i = 0; i < joints.size(); ++i) coordinates[i].first = joints[i];
  }
  ArmSpacePtr out(new ArmSpace());
  for (std::size_t i = 0; i < coordinates.size(); ++i) {
    const auto& [name, so2] = coordinates[i];
    const std::string at = who + ", coordinate " + std::to_string(i);
    const int j = model->findJoint(name);
    if (j < 0) throw InvalidInputError(at + ": '" + name + "' is not a joint of robot '" + model->name() + "'");
    const scene::Joint& joint = model->joint(j);
    if (!joint.moves() || joint.mimic) {
      throw InvalidInputError(at + ": joint '" + name + "' is " + (joint.mimic ? "a mimic joint" : "fixed"));
    }
    if (so2 && joint.type != scene::JointType::kContinuous) {
      throw InvalidInputError(at + ": an SO2 coordinate for joint '" + name + "', which is not continuous");
    }
    out->variables_.push_back(joint.variable);
    out->circular_.push_back(so2);
  }
  requireVariables(*model, out->variables_);
  out->fixed_ = checkedFixed(*model, std::move(fixed));
  out->space_ = std::move(space);
  out->model_ = std::move(model);
  return out;
}

void ArmSpace::configuration(const ob::State* state, double* q) const {
  std::copy(fixed_.begin(), fixed_.end(), q);
  auto* s = const_cast<ob::State*>(state);  // OMPL's value access takes a non-const state
  for (std::size_t i = 0; i < variables_.size(); ++i) {
    q[variables_[i]] = *space_->getValueAddressAtIndex(s, static_cast<unsigned int>(i));
  }
}

std::vector<double> ArmSpace::configuration(const ob::State* state) const {
  std::vector<double> q(fixed_.size());
  configuration(state, q.data());
  return q;
}

void ArmSpace::setState(ob::State* state, const double* q) const {
  for (std::size_t i = 0; i < variables_.size(); ++i) {
    *space_->getValueAddressAtIndex(state, static_cast<unsigned int>(i)) = q[variables_[i]];
  }
}

void ArmSpace::edge(const ob::State* s1, const ob::State* s2, double* q0, double* q1) const {
  configuration(s1, q0);
  configuration(s2, q1);
  for (std::size_t i = 0; i < variables_.size(); ++i) {
    if (!circular_[i]) continue;
    // SO2StateSpace::interpolate: the direct way when |diff| <= pi, else
    // the other way round.
    const int v = variables_[i];
    double diff = q1[v] - q0[v];
    if (std::abs(diff) > kPi) diff = diff > 0.0 ? diff - 2.0 * kPi : diff + 2.0 * kPi;
    q1[v] = q0[v] + diff;
  }
}

std::vector<std::vector<double>> ArmSpace::pathConfigurations(const std::vector<const ob::State*>& states) const {
  std::vector<std::vector<double>> out;
  if (states.empty()) return out;
  out.push_back(configuration(states.front()));
  const std::size_t n = out.front().size();
  std::vector<double> q0(n), q1(n);
  for (std::size_t i = 1; i < states.size(); ++i) {
    edge(states[i - 1], states[i], q0.data(), q1.data());
    std::vector<double> next = out.back();
    for (std::size_t k = 0; k < n; ++k) next[k] += q1[k] - q0[k];
    out.push_back(std::move(next));
  }
  return out;
}

}  // namespace mddual::planning
