// mddual.Scene's C++ class, shared by scene.cpp (its bindings) and
// hull_cast.cpp (the Bullet peer's, which checks a Scene's edges): a loaded
// problem with its planning space and exact checks (MddScene), and OMPL
// states made from rows of numbers (StateHolder, forEachEdge).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "convert.h"
#include "mddual/planning/mdd_scene.h"
#include "mddual/planning/problem_setup.h"
#include "mddual/planning/state_space.h"
#include "mddual/polytope.h"
#include "typed.h"

namespace mddual::python {

/// An OMPL state of `space`, freed with it.
class StateHolder {
 public:
  explicit StateHolder(const ompl::base::StateSpacePtr& space) : space_(space), state_(space->allocState()) {}
  ~StateHolder() { space_->freeState(state_); }
  StateHolder(const StateHolder&) = delete;
  StateHolder& operator=(const StateHolder&) = delete;
  ompl::base::State* get() const { return state_; }
  /// Sets the state from `d` numbers (an SE(3) state's quaternion made unit);
  /// InvalidInputError naming `what` for a non-finite one or a quaternion of
  /// no rotation.
  void set(const double* values, int d, const std::string& what);

 private:
  ompl::base::StateSpacePtr space_;
  ompl::base::State* state_;
};

/// Calls f(k, s1, s2) for the n edges of two batches of states (one side may
/// be a single state that every edge shares), each state set from its row
/// (StateHolder::set's errors name `starts[k]` or `ends[k]`). Runs where it
/// is called (the callers release the GIL around it).
template <class F>
void forEachEdge(const ompl::base::StateSpacePtr& space, int dim, const StateBatch& starts, const StateBatch& ends,
                 std::size_t n, const F& f) {
  StateHolder a(space), b(space);
  for (std::size_t k = 0; k < n; ++k) {
    a.set(starts.row(k, dim), dim, itemName("starts", k, starts.batched));
    b.set(ends.row(k, dim), dim, itemName("ends", k, ends.batched));
    f(k, a.get(), b.get());
  }
}

/// mddual.Scene: a problem (robot, world, space, start and goal) with its
/// planning space and the exact checks. Its const methods are thread-safe.
class Scene {
 public:
  explicit Scene(planning::Problem problem);

  static Scene load(const std::filesystem::path& cfg);
  /// A scene from polytopes in memory: the robot's pieces in its frame R, the
  /// world's in the world frame, kConvex pieces as the loaders make them.
  static Scene fromPolytopes(const std::vector<ConvexPolytope>& robot, const std::vector<ConvexPolytope>& world,
                             const std::string& space, const ArrayLikeArg& bounds, const ArrayLikeOrNoneArg& start,
                             const ArrayLikeOrNoneArg& goal, const std::string& name);

  const planning::Problem& problem() const { return problem_; }
  const planning::PlanningSpace& space() const { return *space_; }
  const planning::MddScene& mddScene() const { return *scene_; }
  /// Numbers per state.
  int dimension() const { return dim_; }
  /// A new space of the same kind, bounds and fixed coordinates as space(),
  /// set up: for checkers that set up a SpaceInformation of their own.
  planning::PlanningSpacePtr makeSpace() const;

  py::array_t<double> stateOf(const Eigen::Isometry3d& X_WR) const;
  Eigen::Matrix4d poseOf(const ArrayLikeArg& state) const;
  BoolOrArray collides(const ArrayLikeArg& poses) const;
  BoolOrArray isValid(const ArrayLikeArg& states) const;
  ArrayDict checkEdges(const ArrayLikeArg& starts, const ArrayLikeArg& ends) const;
  ArrayDict directedClearance(const ArrayLikeArg& poses, const ArrayLikeArg& directions,
                              const ArrayLikeArg& max_distance) const;

 private:
  planning::Problem problem_;
  planning::PlanningSpacePtr space_;
  std::shared_ptr<planning::MddScene> scene_;
  int dim_ = 0;
};

}  // namespace mddual::python
