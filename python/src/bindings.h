// Pieces of the Python module shared by its source files.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "mddual/penetration.h"

namespace mddual::python {

namespace py = pybind11;

/// How a directional query or intersection test is answered.
enum class QueryMethod { kMddual, kBrute };

/// "mddual" or "brute"; ValueError naming `name` otherwise.
QueryMethod queryMethodFrom(const std::string& text, const char* name);
/// "exact", "shallow", "approx" or "brute"; ValueError naming `name` otherwise.
PenetrationMethod penetrationMethodFrom(const std::string& text, const char* name);

/// Registers the exception types (mddual.Error and its subclasses) and the
/// translator from the library's C++ exceptions.
void bindErrors(py::module_& m);
/// ConvexPolytope and the result types.
void bindTypes(py::module_& m);
/// mdd, toi, intersect, penetration_depth, width.
void bindQueries(py::module_& m);
/// mdd_batch, toi_batch, intersect_batch and the status tables.
void bindBatch(py::module_& m);
/// mddual.Scene and mddual.SceneError (only when the planning layer is built:
/// MDDUAL_PYTHON_HAS_PLANNING).
void bindScene(py::module_& m);
/// mddual.RobotModel, Srdf and AllowedCollisions (with the planning layer).
void bindRobot(py::module_& m);
/// mddual.ArmScene, ArmProblem, list_arm_problems and load_arm_problem (with
/// the planning layer; after bindRobot).
void bindArms(py::module_& m);
/// mddual.HullCastScene and ArmHullCastScene, the Bullet peer checker (when
/// the mddual_hull_cast library is built: MDDUAL_PYTHON_HAS_HULL_CAST; after
/// bindScene and bindArms).
void bindHullCast(py::module_& m);

}  // namespace mddual::python
