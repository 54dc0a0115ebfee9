// ArmSpace: a planning group's joints as an OMPL state space, and the map
// between its states and the robot's full configuration (RobotModel
// variables; the joints outside the group keep fixed values).
//
// Spaces: ArmSpace::make builds a RealVectorStateSpace over the group's
// variables (bounds: the URDF limits; dimension names: the joint names) when
// no joint of the group is continuous, and otherwise a CompoundStateSpace
// with one component per variable, named by its joint: a RealVectorStateSpace
// of dimension 1, or an SO2StateSpace for a continuous joint (OMPL then
// interpolates it the short way round, and the edge below does the same).
// ArmSpace::wrap accepts a space the user made in either layout, joints
// matched by name (RealVector dimension names or compound component names),
// or in the order given.
//
// Edges: OMPL interpolates every coordinate linearly (an SO2 angle along
// the shorter turn), which is the straight segment q0 + t (q1 - q0) in
// variable space once q1's continuous joints are unwrapped next to q0's:
// what ArmScene::checkEdge takes.
//
// Thread safety: immutable; any number of threads may use it at once.
#pragma once

#include <ompl/base/StateSpace.h>
#include <ompl/util/ClassForward.h>

#include <memory>
#include <string>
#include <vector>

#include "mddual/scene/robot_model.h"

namespace mddual::planning {

OMPL_CLASS_FORWARD(ArmSpace);

/// See the file comment.
class ArmSpace {
 public:
  /// The group's space. `group` lists RobotModel variables (each once);
  /// `fixed` is a full configuration giving the other joints' values (empty:
  /// RobotModel::defaultConfiguration()). Throws InvalidInputError for an
  /// empty group, a variable out of range or repeated, a `fixed` of the
  /// wrong size or with a non-finite value.
  static ArmSpacePtr make(std::shared_ptr<const scene::RobotModel> model, const std::vector<int>& group,
                          std::vector<double> fixed = {});
  /// A space the user made: a RealVectorStateSpace, or a CompoundStateSpace
  /// of one-dimensional RealVectorStateSpace and SO2StateSpace components.
  /// `joints` names the joint of each coordinate in the state's order; empty:
  /// the RealVector dimension names or the compound's component names. Throws
  /// InvalidInputError naming the space and the coordinate for another
  /// layout, an unknown or unnamed joint, a fixed or mimic joint, or an SO2
  /// component on a joint that is not continuous.
  static ArmSpacePtr wrap(ompl::base::StateSpacePtr space, std::shared_ptr<const scene::RobotModel> model,
                          std::vector<std::string> joints = {}, std::vector<double> fixed = {});

  const ompl::base::StateSpacePtr& stateSpace() const { return space_; }
  const scene::RobotModel& model() const { return *model_; }
  const std::shared_ptr<const scene::RobotModel>& modelPtr() const { return model_; }
  /// The group's variables, in the state's order.
  const std::vector<int>& variables() const { return variables_; }
  int dimension() const { return static_cast<int>(variables_.size()); }
  /// The full configuration of `state` (model().numVariables() values).
  void configuration(const ompl::base::State* state, double* q) const;
  std::vector<double> configuration(const ompl::base::State* state) const;
  /// Sets the group's coordinates of `state` from a full configuration.
  void setState(ompl::base::State* state, const double* q) const;
  /// The edge from s1 to s2 under OMPL's interpolation: q0 and q1 (full
  /// configurations) with q(t) = q0 + t (q1 - q0).
  void edge(const ompl::base::State* s1, const ompl::base::State* s2, double* q0, double* q1) const;
  /// The full configurations of a path's states, continuous joints unwrapped
  /// along it: the first state's configuration, then each the previous one
  /// plus edge()'s step, so straight lines between them are OMPL's edges.
  std::vector<std::vector<double>> pathConfigurations(const std::vector<const ompl::base::State*>& states) const;
  /// The full configuration the joints outside the group keep.
  const std::vector<double>& fixedConfiguration() const { return fixed_; }

 private:
  ArmSpace() = default;
  static std::vector<double> checkedFixed(const scene::RobotModel& model, std::vector<double> fixed);
  ompl::base::StateSpacePtr space_;
  std::shared_ptr<const scene::RobotModel> model_;
  std::vector<int> variables_;
  std::vector<bool> circular_;  ///< per coordinate: an SO2 angle
  std::vector<double> fixed_;
};

}  // namespace mddual::planning
