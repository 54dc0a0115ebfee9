// What robot.cpp (RobotModel, Srdf, AllowedCollisions) and arms.cpp
// (ArmScene, arm problems) share.
#pragma once

#include <pybind11/pybind11.h>

#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "convert.h"
#include "mddual/scene/robot_model.h"
#include "mddual/scene/srdf.h"

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

}  // namespace mddual::python
