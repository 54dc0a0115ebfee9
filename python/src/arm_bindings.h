// What robot.cpp (RobotModel, Srdf, AllowedCollisions), arms.cpp (ArmScene,
// arm problems) and hull_cast.cpp (the Bullet peer on an ArmScene) share.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Geometry>
#include <memory>
#include <tuple>
#include <vector>

#include "convert.h"
#include "mddual/planning/arm_scene.h"
#include "mddual/scene/robot_model.h"
#include "mddual/scene/srdf.h"
#include "planning_convert.h"
#include "typed.h"

namespace mddual::python {

/// mddual.AllowedCollisions: the filter with the model that names its links.
struct AllowedLinks {
  std::shared_ptr<scene::RobotModel> model;
  scene::AllowedCollisions filter;
};

/// The index of a link given by name (SceneError when unknown) or by index
/// (IndexError when out of range); `name` is the argument's.
int linkIndexFrom(const scene::RobotModel& model, const py::handle& link, const char* name);

/// Link indices from None (every link) or a list of names or indices.
std::vector<int> linkSelection(const scene::RobotModel& model, const py::object& links);

/// The poses X_WB X_BL of `links` for each configuration of `q`: (L, 4, 4)
/// for one, (K, L, 4, 4) for a batch. Runs without the GIL.
py::object linkPosesArray(const scene::RobotModel& model, const StateBatch& q, const std::vector<int>& links,
                          const Eigen::Isometry3d& X_WB);

/// mddual.ArmScene: the C++ scene with the model Python knows. The batches
/// run without the GIL on `threads` workers (see parallelFor).
struct ArmSceneHandle {
  std::shared_ptr<scene::RobotModel> model;
  std::shared_ptr<const planning::ArmScene> scene;

  static ArmSceneHandle make(const std::shared_ptr<scene::RobotModel>& model, const PolytopesArg& world,
                             const AllowedArg& allowed, const ArrayLikeOrNoneArg& X_WB, double contact_distance,
                             int max_depth);
  BoolOrArray collides(const ArrayLikeArg& q, int threads) const;
  FloatOrArray clearance(const ArrayLikeArg& q, int threads) const;
  /// The pair that makes one configuration collide, or None.
  ArmContactResult contact(const ArrayLikeArg& q) const;
  EdgeResults checkEdges(const ArrayLikeArg& q0, const ArrayLikeArg& q1, bool first_contact, double fraction_tolerance,
                         int threads) const;

 private:
  /// collides(Q) or clearance(Q): f(q) per configuration, a scalar for one.
  template <class T, class F>
  py::object perConfiguration(const ArrayLikeArg& q, int threads, const F& f) const;
};

/// The edges from the configurations of Q0 to those of Q1 (an edge per row;
/// one of them may be a single configuration), each checked by edge(q0, q1)
/// -> (collides, fraction) on `threads` workers without the GIL: a
/// tuple (bool, float) when neither is a batch, else of two arrays.
template <class F>
EdgeResults edgeBatch(const ArrayLikeArg& q0, const ArrayLikeArg& q1, const scene::RobotModel& model, int threads,
                      const F& edge) {
  const StateBatch a = configBatchFrom(q0, "Q0", model);
  const StateBatch b = configBatchFrom(q1, "Q1", model);
  const std::size_t n = batchSizeOf(a, "Q0", b, "Q1");
  py::array_t<bool> collides(static_cast<py::ssize_t>(n));
  py::array_t<double> fraction(static_cast<py::ssize_t>(n));
  {
    bool* c = collides.mutable_data();
    double* f = fraction.mutable_data();
    py::gil_scoped_release release;
    const int nv = model.numVariables();
    parallelFor(n, workerCount(threads, n),
                [&](std::size_t k) { std::tie(c[k], f[k]) = edge(a.row(k, nv), b.row(k, nv)); });
  }
  if (!a.batched && !b.batched) return py::make_tuple(py::bool_(collides.at(0)), py::float_(fraction.at(0)));
  return py::make_tuple(collides, fraction);
}

/// ArmScene.contact's dict for a contact `c` of `scene`: link, other_link (a
/// self-collision) or world_piece and world_piece_origin (the others None).
py::dict armContactDict(const scene::RobotModel& model, const planning::ArmScene& scene, const planning::ArmContact& c);

}  // namespace mddual::python
