// mddual.RobotModel, mddual.Srdf and mddual.AllowedCollisions: an
// articulated robot read from a URDF (scene::loadRobotModel) with its forward
// kinematics on arrays of configurations, its SRDF (groups, group states,
// collision matrix) and the link pairs the arm checks skip. See
// docs/arms.md#from-python.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "arm_bindings.h"
#include "bindings.h"
#include "convert.h"
#include "mddual/scene/srdf.h"
#include "planning_convert.h"
#include "typed.h"

namespace mddual::python {

int linkIndexFrom(const scene::RobotModel& model, const py::handle& link, const char* name) {
  if (py::isinstance<py::str>(link)) return model.linkIndex(link.cast<std::string>());
  // Any integer (NumPy's too, through __index__); bool is refused.
  if (!PyIndex_Check(link.ptr()) || py::isinstance<py::bool_>(link)) {
    throw py::type_error(std::string(name) + ": expected a link name or index, got a " +
                         std::string(py::str(py::type::of(link).attr("__name__"))));
  }
  const Py_ssize_t k = PyNumber_AsSsize_t(link.ptr(), PyExc_IndexError);
  if (k == -1 && PyErr_Occurred()) throw py::error_already_set();
  if (k < 0 || k >= model.numLinks()) {
    throw py::index_error(std::string(name) + ": link index " + std::to_string(k) + " is out of range (robot '" +
                          model.name() + "' has " + std::to_string(model.numLinks()) + " links)");
  }
  return static_cast<int>(k);
}

py::object linkPosesArray(const scene::RobotModel& model, const StateBatch& q, const std::vector<int>& links,
                          const Eigen::Isometry3d& X_WB) {
  const auto count = static_cast<py::ssize_t>(q.count);
  const auto nl = static_cast<py::ssize_t>(links.size());
  py::array_t<double> out({count, nl, py::ssize_t{4}, py::ssize_t{4}});
  double* o = out.mutable_data();
  {
    py::gil_scoped_release release;
    std::vector<Eigen::Isometry3d> X_BL;
    for (std::size_t k = 0; k < q.count; ++k) {
      model.linkPoses(q.row(k, model.numVariables()), &X_BL);
      for (std::size_t i = 0; i < links.size(); ++i) {
        const Eigen::Matrix4d X = (X_WB * X_BL[static_cast<std::size_t>(links[i])]).matrix();
        double* m = o + 16 * (k * links.size() + i);
        for (int r = 0; r < 4; ++r) {
          for (int c = 0; c < 4; ++c) m[4 * r + c] = X(r, c);
        }
      }
    }
  }
  if (q.batched) return std::move(out);
  return out[py::int_(0)];
}

std::vector<int> linkSelection(const scene::RobotModel& model, const py::object& links) {
  std::vector<int> out;
  if (links.is_none()) {
    for (int k = 0; k < model.numLinks(); ++k) out.push_back(k);
    return out;
  }
  if (py::isinstance<py::str>(links)) throw py::type_error("links: expected a list of link names or None, got a str");
  for (const py::handle& l : links) out.push_back(linkIndexFrom(model, l, "links"));
  return out;
}

namespace {

using RobotPtr = std::shared_ptr<scene::RobotModel>;

std::shared_ptr<scene::RobotModel> fromUrdf(const std::filesystem::path& urdf,
                                            const std::vector<std::filesystem::path>& package_path,
                                            bool use_environment) {
  scene::RobotLoadOptions options;
  options.package_path = package_path;
  options.use_environment = use_environment;
  return std::make_shared<scene::RobotModel>(scene::loadRobotModel(urdf, options));
}

py::dict jointDict(const scene::RobotModel& m, const scene::Joint& j) {
  py::dict d;
  d["name"] = j.name;
  d["type"] = scene::toString(j.type);
  d["parent"] = m.link(j.parent_link).name;
  d["child"] = m.link(j.child_link).name;
  d["origin"] = py::cast(j.X_PJ.matrix().eval());
  d["axis"] = py::cast(j.axis_J);
  d["lower"] = j.lower;
  d["upper"] = j.upper;
  d["variable"] = j.variable;
  d["mimic"] = j.mimic;
  d["multiplier"] = j.multiplier;
  d["offset"] = j.offset;
  return d;
}

py::array_t<double> configurationArray(const std::vector<double>& q) {
  return py::array_t<double>(static_cast<py::ssize_t>(q.size()), q.data());
}

std::vector<std::pair<std::string, double>> namedValues(const py::dict& values) {
  std::vector<std::pair<std::string, double>> out;
  for (const auto& [name, value] : values) out.emplace_back(py::str(name), value.cast<double>());
  return out;
}

std::vector<double> baseConfiguration(const scene::RobotModel& m, const ArrayLikeOrNoneArg& base) {
  if (base.is_none()) return m.defaultConfiguration();
  const StateBatch b = configBatchFrom(base, "base", m);
  if (b.batched) throw py::value_error("base: expected one configuration, got a batch");
  return b.values;
}

std::vector<std::pair<std::string, std::string>> linkPairNames(const scene::RobotModel& m,
                                                               const scene::AllowedCollisions& a) {
  std::vector<std::pair<std::string, std::string>> out;
  for (int k = 0; k < m.numLinks(); ++k) {
    for (int l = k + 1; l < m.numLinks(); ++l) {
      if (a.allowed(k, l)) out.emplace_back(m.link(k).name, m.link(l).name);
    }
  }
  return out;
}

}  // namespace

void bindRobot(py::module_& m) {
  py::class_<scene::RobotModel, RobotPtr>(
      m, "RobotModel",
      "An articulated robot read from a URDF: links, joints (fixed, revolute, continuous, prismatic, mimic), "
      "collision pieces per link and forward kinematics. Configurations are arrays of num_variables values, one "
      "per moving non-mimic joint, in variable_names order.")
      .def_static("from_urdf", &fromUrdf, py::arg("urdf"), py::kw_only(),
                  py::arg("package_path") = std::vector<std::filesystem::path>(), py::arg("use_environment") = true,
                  "Reads a URDF. package:// and relative mesh paths are looked up in the URDF's folder and its "
                  "parents, then in each package_path folder, then (use_environment) in MDDUAL_PACKAGE_PATH. "
                  "SceneError naming the file, the element and every place searched otherwise.")
      .def_property_readonly("name", &scene::RobotModel::name)
      .def_property_readonly("num_variables", &scene::RobotModel::numVariables)
      .def_property_readonly("num_links", &scene::RobotModel::numLinks)
      .def_property_readonly(
          "variable_names",
          [](const scene::RobotModel& r) {
            std::vector<std::string> out;
            for (int v = 0; v < r.numVariables(); ++v) out.push_back(r.variableName(v));
            return out;
          },
          "the joints that own the variables, in configuration order")
      .def_property_readonly(
          "link_names",
          [](const scene::RobotModel& r) {
            std::vector<std::string> out;
            for (const scene::Link& l : r.links()) out.push_back(l.name);
            return out;
          },
          "every link, in tree order (the root first): the order of forward_kinematics")
      .def_property_readonly(
          "joints",
          [](const scene::RobotModel& r) {
            py::list out;
            for (const scene::Joint& j : r.joints()) out.append(jointDict(r, j));
            return out;
          },
          "one dict per joint: name, type, parent, child (link names), origin (4x4 X_PJ), axis, lower, upper, "
          "variable (-1 when fixed), mimic, multiplier, offset")
      .def_property_readonly(
          "limits",
          [](const scene::RobotModel& r) {
            py::array_t<double> out({static_cast<py::ssize_t>(r.numVariables()), py::ssize_t{2}});
            for (int v = 0; v < r.numVariables(); ++v) {
              out.mutable_at(v, 0) = r.joint(r.variableJoint(v)).lower;
              out.mutable_at(v, 1) = r.joint(r.variableJoint(v)).upper;
            }
            return out;
          },
          "(num_variables, 2): each variable's lower and upper limit (continuous joints: -inf, inf)")
      .def("variable_index", &scene::RobotModel::variableIndex, py::arg("joint"),
           "The variable of a joint (SceneError for an unknown, fixed or mimic joint).")
      .def("link_index", &scene::RobotModel::linkIndex, py::arg("link"))
      .def(
          "default_configuration",
          [](const scene::RobotModel& r) { return configurationArray(r.defaultConfiguration()); },
          "Every variable at 0, or at the middle of its limits when 0 is outside.")
      .def(
          "configuration",
          [](const scene::RobotModel& r, const py::dict& values, const ArrayLikeOrNoneArg& base) {
            return configurationArray(
                scene::applyJointValues(r, baseConfiguration(r, base), namedValues(values), "configuration"));
          },
          py::arg("values"), py::arg("base") = py::none(),
          "A configuration from {joint name: value} over `base` (default_configuration() when None); mimic "
          "joints are skipped (their leader decides). SceneError for an unknown or fixed joint.")
      .def(
          "link_pieces",
          [](const scene::RobotModel& r, const LinkArg& link) {
            return polytopes(r.link(linkIndexFrom(r, link, "link")).pieces);
          },
          py::arg("link"), "The collision pieces (ConvexPolytope) of a link (name or index), in the link's frame.")
      .def(
          "forward_kinematics",
          [](const scene::RobotModel& r, const ArrayLikeArg& q, const LinksArg& links) -> FloatArray {
            return linkPosesArray(r, configBatchFrom(q, "q", r), linkSelection(r, links),
                                  Eigen::Isometry3d::Identity());
          },
          py::arg("q"), py::arg("links") = py::none(),
          "The poses X_BL of the links (all, in link_names order, or the `links` named) in the root link's "
          "frame: (L, 4, 4) for one configuration (n,), (K, L, 4, 4) for (K, n). The loop runs without the GIL.")
      .def("__repr__", [](const scene::RobotModel& r) {
        return "RobotModel(name='" + r.name() + "', links=" + std::to_string(r.numLinks()) +
               ", variables=" + std::to_string(r.numVariables()) + ")";
      });

  py::class_<scene::Srdf>(m, "Srdf",
                          "A robot's SRDF: planning groups, group states, virtual joints and the collision matrix. "
                          "Names are checked when resolved against a RobotModel.")
      .def_static("load", &scene::loadSrdf, py::arg("path"), "Reads an SRDF file (SceneError naming file and line).")
      .def_static("parse", &scene::parseSrdf, py::arg("text"), py::arg("label") = "<string>",
                  "Reads SRDF text; `label` names it in messages.")
      .def_readonly("source", &scene::Srdf::source)
      .def_readonly("robot_name", &scene::Srdf::robot_name)
      .def_property_readonly("group_names",
                             [](const scene::Srdf& s) {
                               std::vector<std::string> out;
                               for (const scene::SrdfGroup& g : s.groups) out.push_back(g.name);
                               return out;
                             })
      .def_property_readonly(
          "group_states",
          [](const scene::Srdf& s) {
            std::vector<std::pair<std::string, std::string>> out;
            for (const scene::SrdfGroupState& g : s.group_states) out.emplace_back(g.group, g.name);
            return out;
          },
          "(group, state) pairs")
      .def_readonly("disabled_pairs", &scene::Srdf::disabled_pairs)
      .def_readonly("disabled_links", &scene::Srdf::disabled_links)
      .def_readonly("enabled_pairs", &scene::Srdf::enabled_pairs)
      .def(
          "group_variables",
          [](const scene::Srdf& s, const scene::RobotModel& r, const std::string& group) {
            return scene::groupVariables(s, r, group);
          },
          py::arg("model"), py::arg("group"),
          "The variables (indices into a configuration, ascending) that a group moves (SceneError for an unknown "
          "group, joint or link).")
      .def(
          "group_state",
          [](const scene::Srdf& s, const scene::RobotModel& r, const std::string& group, const std::string& state) {
            py::dict out;
            for (const auto& [v, value] : scene::groupStateValues(s, r, group, state)) {
              out[py::str(r.variableName(v))] = value;
            }
            return out;
          },
          py::arg("model"), py::arg("group"), py::arg("state"),
          "A group state's values as {joint name: value} (for RobotModel.configuration).")
      .def("__repr__", [](const scene::Srdf& s) {
        return "Srdf(robot_name='" + s.robot_name + "', groups=" + std::to_string(s.groups.size()) + ")";
      });

  py::class_<AllowedLinks>(m, "AllowedCollisions",
                           "The contacts the arm checks skip (MoveIt's allowed collision matrix): link pairs of the "
                           "self check and links allowed to touch the world. Links by name or index.")
      .def(py::init([](RobotPtr model, const std::optional<scene::Srdf>& srdf) {
             if (!model) throw py::type_error("model: expected a RobotModel, got None");
             AllowedLinks a{model, srdf ? scene::AllowedCollisions(*model, *srdf) : scene::AllowedCollisions(*model)};
             return a;
           }),
           py::arg("model"), py::arg("srdf") = py::none(),
           "Every pair checked, or the SRDF's matrix (SceneError for a link the model does not have).")
      .def(
          "allow",
          [](AllowedLinks& a, const LinkArg& k, const LinkArg& l, bool allowed) {
            a.filter.allow(linkIndexFrom(*a.model, k, "link1"), linkIndexFrom(*a.model, l, "link2"), allowed);
          },
          py::arg("link1"), py::arg("link2"), py::arg("allowed") = true, "Skip (or check again) a link pair.")
      .def(
          "allowed",
          [](const AllowedLinks& a, const LinkArg& k, const LinkArg& l) {
            return a.filter.allowed(linkIndexFrom(*a.model, k, "link1"), linkIndexFrom(*a.model, l, "link2"));
          },
          py::arg("link1"), py::arg("link2"))
      .def(
          "allow_with_world",
          [](AllowedLinks& a, const LinkArg& k, bool allowed) {
            a.filter.allowWithWorld(linkIndexFrom(*a.model, k, "link"), allowed);
          },
          py::arg("link"), py::arg("allowed") = true, "Skip (or check again) a link against the world.")
      .def(
          "allowed_with_world",
          [](const AllowedLinks& a, const LinkArg& k) {
            return a.filter.allowedWithWorld(linkIndexFrom(*a.model, k, "link"));
          },
          py::arg("link"))
      .def_property_readonly(
          "allowed_pairs", [](const AllowedLinks& a) { return linkPairNames(*a.model, a.filter); },
          "the skipped link pairs, by name")
      .def_property_readonly("model", [](const AllowedLinks& a) { return a.model; });
}

}  // namespace mddual::python
