// What robot.cpp (RobotModel, Srdf, AllowedCollisions), arms.cpp (ArmScene,
// arm problems) and hull_cast.cpp (the Bullet peer on an ArmScene) share.
#pragma once

#include <pybind11/pybind11.h>

#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "convert.h"
#include "mddual/planning/arm_scene.h"
#include "mddual/scene/robot_model.h"
#include "mddual/scene/srdf.h"
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
  EdgeResults checkEdges(const ArrayLikeArg& q0, const ArrayLikeArg& q1, bool first_contact, int threads) const;

 private:
  /// collides(Q) or clearance(Q): f(q) per configuration, a scalar for one.
  template <class T, class F>
  py::object perConfiguration(const ArrayLikeArg& q, int threads, const F& f) const;
};

/// ArmScene.contact's dict for a contact `c` of `scene`: link, other_link (a
/// self-collision) or world_piece and world_piece_origin (the others None).
py::dict armContactDict(const scene::RobotModel& model, const planning::ArmScene& scene, const planning::ArmContact& c);

}  // namespace mddual::python
