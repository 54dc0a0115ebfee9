// mddual.ArmScene and the arm problems: planning::ArmScene's exact state
// checks, clearance and certified motion checks on arrays of joint
// configurations, and MotionBenchMaker problems (planning::loadArmProblem).
// The batch loops run without the GIL, on `threads` workers (ArmScene's const
// methods are thread-safe). See docs/arms.md#from-python.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "arm_bindings.h"
#include "bindings.h"
#include "convert.h"
#include "mddual/planning/arm_problem.h"
#include "mddual/planning/arm_scene.h"
#include "planning_convert.h"
#include "typed.h"

namespace mddual::python {
namespace {

namespace mp = mddual::planning;

}  // namespace

py::dict armContactDict(const scene::RobotModel& model, const mp::ArmScene& scene, const mp::ArmContact& c) {
  const auto& pieces = scene.world().pieces();
  py::dict out;
  out["link"] = model.link(c.link).name;
  out["other_link"] = c.other_link >= 0 ? py::object(py::str(model.link(c.other_link).name)) : py::none();
  out["world_piece"] = c.world_piece >= 0 ? py::object(py::int_(c.world_piece)) : py::none();
  out["world_piece_origin"] =
      c.world_piece >= 0 ? py::object(py::str(pieces[static_cast<std::size_t>(c.world_piece)].origin)) : py::none();
  return out;
}

ArmSceneHandle ArmSceneHandle::make(const std::shared_ptr<scene::RobotModel>& model, const PolytopesArg& world,
                                    const AllowedArg& allowed, const ArrayLikeOrNoneArg& X_WB, double contact_distance,
                                    int max_depth) {
  if (!model) throw py::type_error("model: expected a RobotModel, got None");
  std::vector<scene::Piece> pieces;
  if (!world.is_none()) {
    for (const py::handle& p : world) {
      const std::string origin = "world " + std::to_string(pieces.size());
      pieces.push_back(scene::Piece::make(p.cast<ConvexPolytope>(), scene::PieceKind::kConvex, origin));
    }
  }
  scene::AllowedCollisions filter(*model);
  if (py::isinstance<AllowedLinks>(allowed)) {
    const auto& a = allowed.cast<const AllowedLinks&>();
    if (a.model != model) throw py::value_error("allowed: an AllowedCollisions of another RobotModel");
    filter = a.filter;
  } else if (py::isinstance<scene::Srdf>(allowed)) {
    filter = scene::AllowedCollisions(*model, allowed.cast<const scene::Srdf&>());
  } else if (!allowed.is_none()) {
    throw py::type_error("allowed: expected an AllowedCollisions, an Srdf or None");
  }
  mp::ArmSceneOptions options;
  options.contact_distance = contact_distance;
  options.max_depth = max_depth;
  auto w = std::make_shared<const scene::World>(std::move(pieces), "world");
  return {model, std::make_shared<const mp::ArmScene>(model, w, std::move(filter), poseFrom(X_WB, "X_WB"), options)};
}

template <class T, class F>
py::object ArmSceneHandle::perConfiguration(const ArrayLikeArg& q, int threads, const F& f) const {
  const StateBatch b = configBatchFrom(q, "Q", *model);
  py::array_t<T> out(static_cast<py::ssize_t>(b.count));
  T* o = out.mutable_data();
  {
    py::gil_scoped_release release;
    const int n = model->numVariables();
    parallelFor(b.count, workerCount(threads, b.count), [&](std::size_t k) { o[k] = f(b.row(k, n)); });
  }
  if (!b.batched) return py::cast(o[0]);
  return std::move(out);
}

BoolOrArray ArmSceneHandle::collides(const ArrayLikeArg& q, int threads) const {
  return perConfiguration<bool>(q, threads, [this](const double* x) { return scene->collides(x); });
}

FloatOrArray ArmSceneHandle::clearance(const ArrayLikeArg& q, int threads) const {
  return perConfiguration<double>(q, threads, [this](const double* x) { return scene->clearance(x); });
}

ArmContactResult ArmSceneHandle::contact(const ArrayLikeArg& q) const {
  const StateBatch b = configBatchFrom(q, "q", *model);
  if (b.batched) throw py::value_error("q: expected one configuration, got a batch");
  mp::ArmContact c;
  bool hit = false;
  {
    py::gil_scoped_release release;
    hit = scene->collides(b.row(0, model->numVariables()), &c);
  }
  if (!hit) return py::none();
  return armContactDict(*model, *scene, c);
}

EdgeResults ArmSceneHandle::checkEdges(const ArrayLikeArg& q0, const ArrayLikeArg& q1, bool first_contact,
                                       double fraction_tolerance, int threads) const {
  if (!(fraction_tolerance >= 0.0 && fraction_tolerance <= 1.0)) {
    throw py::value_error("fraction_tolerance: expected a number in [0, 1], got " +
                          py::repr(py::float_(fraction_tolerance)).cast<std::string>());
  }
  if (fraction_tolerance > 0.0 && !first_contact) {
    throw py::value_error(
        "fraction_tolerance: only with first_contact=True (without, a colliding edge has no fraction)");
  }
  // A tolerance asks for the motion validator's lastValid query: decided as
  // kValidity, then a lower bound at most the tolerance below the first contact.
  const mp::EdgeQuery query = !first_contact             ? mp::EdgeQuery::kValidity
                              : fraction_tolerance > 0.0 ? mp::EdgeQuery::kLastValid
                                                         : mp::EdgeQuery::kFirstContact;
  return edgeBatch(q0, q1, *model, threads, [&](const double* a, const double* b) {
    const mp::ArmEdgeResult r = scene->checkEdge(a, b, query, fraction_tolerance);
    // kValidity stops at any contact: its fraction bounds nothing.
    return std::make_pair(r.collides,
                          r.collides && !first_contact ? std::numeric_limits<double>::quiet_NaN() : r.fraction);
  });
}

namespace {

/// mddual.ArmProblem.
struct ArmProblemHandle {
  mp::ArmProblem problem;
  ArmSceneHandle scene;
};

std::shared_ptr<scene::RobotModel> mutableModel(const std::shared_ptr<const scene::RobotModel>& m) {
  return std::const_pointer_cast<scene::RobotModel>(m);
}

/// A problem's files: an ArmProblemFiles or a (scene, request) pair.
scene::MbmProblemFiles problemFilesFrom(const py::object& problem) {
  if (py::isinstance<scene::MbmProblemFiles>(problem)) return problem.cast<scene::MbmProblemFiles>();
  scene::MbmProblemFiles files;
  try {
    std::tie(files.scene, files.request) = problem.cast<std::pair<std::filesystem::path, std::filesystem::path>>();
  } catch (const py::cast_error&) {
    throw py::type_error(
        "problem: expected an ArmProblemFiles (list_arm_problems) or a (scene, request) pair of paths");
  }
  return files;
}

ArmProblemHandle loadProblem(const RobotOrPathArg& robot, const SrdfOrPathArg& srdf, const ProblemFilesArg& problem,
                             const std::optional<std::string>& group,
                             const std::vector<std::filesystem::path>& package_path, double contact_distance,
                             int max_depth) {
  mp::ArmRobot arm;
  scene::RobotLoadOptions load;
  load.package_path = package_path;
  const bool model_given = py::isinstance<scene::RobotModel>(robot);
  const bool srdf_given = py::isinstance<scene::Srdf>(srdf);
  if (!model_given && !srdf_given) {
    arm = mp::loadArmRobot(robot.cast<std::filesystem::path>(), srdf.cast<std::filesystem::path>(), load);
  } else {
    arm.model =
        model_given
            ? robot.cast<std::shared_ptr<scene::RobotModel>>()
            : std::make_shared<scene::RobotModel>(scene::loadRobotModel(robot.cast<std::filesystem::path>(), load));
    arm.srdf = srdf_given ? srdf.cast<scene::Srdf>() : scene::loadSrdf(srdf.cast<std::filesystem::path>());
  }
  mp::ArmProblemOptions options;
  options.group = group.value_or("");
  options.scene.contact_distance = contact_distance;
  options.scene.max_depth = max_depth;
  ArmProblemHandle out;
  out.problem = mp::loadArmProblem(arm, problemFilesFrom(problem), options);
  out.scene = {mutableModel(arm.model), out.problem.scene};
  return out;
}

py::array_t<double> vectorArray(const std::vector<double>& q) {
  return py::array_t<double>(static_cast<py::ssize_t>(q.size()), q.data());
}

/// A trajectory file of the problem as full configurations, (K, n).
FloatArray trajectoryArray(const ArmProblemHandle& p, const std::optional<std::filesystem::path>& path) {
  const std::filesystem::path file = path ? *path : p.problem.files.trajectory;
  if (file.empty()) {
    throw scene::SceneError(p.problem.name + ": no trajectoryNNNN.yaml beside the problem; give the file's path");
  }
  const std::vector<std::vector<double>> states =
      mp::armTrajectoryStates(p.problem, scene::loadMbmTrajectory(file), file.string());
  const auto n = static_cast<py::ssize_t>(p.problem.start.size());
  py::array_t<double> out({static_cast<py::ssize_t>(states.size()), n});
  auto view = out.mutable_unchecked<2>();
  for (py::ssize_t k = 0; k < view.shape(0); ++k) {
    for (py::ssize_t i = 0; i < n; ++i) view(k, i) = states[static_cast<std::size_t>(k)][static_cast<std::size_t>(i)];
  }
  return FloatArray(std::move(out));
}

}  // namespace

void bindArms(py::module_& m) {
  const mp::ArmSceneOptions defaults;
  py::class_<ArmSceneHandle>(
      m, "ArmScene",
      "An articulated robot (RobotModel) in a static world of convex pieces, with the exact state check, the "
      "clearance and the certified motion check of joint-space edges (touching counts as collision). "
      "Configurations are full: (n,) or (K, n), n = model.num_variables.")
      .def(py::init(&ArmSceneHandle::make), py::arg("model"), py::arg("world") = py::none(),
           py::arg("allowed") = py::none(), py::arg("X_WB") = py::none(), py::kw_only(),
           py::arg("contact_distance") = defaults.contact_distance, py::arg("max_depth") = defaults.max_depth,
           "world: ConvexPolytope pieces in the world frame (None: empty); allowed: an AllowedCollisions, an Srdf "
           "(its collision matrix) or None (every link pair checked, adjacent links included); X_WB: the root "
           "link's 4x4 pose in the world (None: identity); contact_distance: the clearance every state of an edge "
           "called free keeps; max_depth: halvings before an unresolved interval counts as a contact.")
      .def_property_readonly("model", [](const ArmSceneHandle& s) { return s.model; })
      .def_property_readonly("num_variables", [](const ArmSceneHandle& s) { return s.model->numVariables(); })
      .def_property_readonly("world_pieces",
                             [](const ArmSceneHandle& s) { return polytopes(s.scene->world().pieces()); })
      .def_property_readonly("world_piece_origins",
                             [](const ArmSceneHandle& s) { return origins(s.scene->world().pieces()); })
      .def_property_readonly("X_WB", [](const ArmSceneHandle& s) { return s.scene->baseInWorld().matrix().eval(); })
      .def_property_readonly("contact_distance",
                             [](const ArmSceneHandle& s) { return s.scene->options().contact_distance; })
      .def_property_readonly("max_depth", [](const ArmSceneHandle& s) { return s.scene->options().max_depth; })
      .def_property_readonly(
          "self_pairs",
          [](const ArmSceneHandle& s) {
            std::vector<std::pair<std::string, std::string>> out;
            for (const auto& [k, l] : s.scene->selfPairs())
              out.emplace_back(s.model->link(k).name, s.model->link(l).name);
            return out;
          },
          "the link pairs the self check tests, by name")
      .def_property_readonly(
          "num_pairs", [](const ArmSceneHandle& s) { return s.scene->numPairs(); },
          "pairs checked: links against the world, then self pairs")
      .def("collides", &ArmSceneHandle::collides, py::arg("Q"), py::kw_only(), py::arg("threads") = 1,
           "Whether each configuration collides (a link touches the world or another checked link): bool for "
           "(n,), bool array for (K, n). threads: workers (0: one per core).")
      .def("clearance", &ArmSceneHandle::clearance, py::arg("Q"), py::kw_only(), py::arg("threads") = 1,
           "Smallest signed distance over the checked pairs (negative: the deepest penetration found; inf when "
           "nothing is checked): > 0 exactly when the configuration does not collide.")
      .def("contact", &ArmSceneHandle::contact, py::arg("q"),
           "For one configuration, the pair that collides: None when free, else a dict of link, other_link (a "
           "self-collision) or world_piece and world_piece_origin (a world contact; the other keys None).")
      .def("check_edges", &ArmSceneHandle::checkEdges, py::arg("Q0"), py::arg("Q1"), py::kw_only(),
           py::arg("first_contact") = false, py::arg("fraction_tolerance") = 0.0, py::arg("threads") = 1,
           "The certified motion check of each edge Q0[k] -> Q1[k] (straight lines in joint space; one of them "
           "may be a single configuration): returns (collides, fraction). collides is never False when some "
           "state of the edge collides. fraction: inf for a free edge; with first_contact, a lower bound of the "
           "first contact (every state before it keeps contact_distance); without, NaN for a colliding edge. "
           "fraction_tolerance (in [0, 1], with first_contact only): the fraction may lie up to this much below "
           "the first contact, for less work on a colliding edge (OMPL's lastValid: the motion validator passes "
           "one discrete step).")
      .def(
          "forward_kinematics",
          [](const ArmSceneHandle& s, const ArrayLikeArg& q, const LinksArg& links) -> FloatArray {
            return linkPosesArray(*s.model, configBatchFrom(q, "q", *s.model), linkSelection(*s.model, links),
                                  s.scene->baseInWorld());
          },
          py::arg("q"), py::arg("links") = py::none(),
          "RobotModel.forward_kinematics in the world frame: X_WL = X_WB X_BL.")
      .def("__repr__", [](const ArmSceneHandle& s) {
        return "ArmScene(robot='" + s.model->name() +
               "', world_pieces=" + std::to_string(s.scene->world().pieces().size()) +
               ", pairs=" + std::to_string(s.scene->numPairs()) + ")";
      });

  py::class_<scene::MbmProblemFiles>(m, "ArmProblemFiles",
                                     "One MotionBenchMaker problem: its number, sceneNNNN.yaml and requestNNNN.yaml.")
      .def(py::init([](std::filesystem::path scene, std::filesystem::path request, int number) {
             return scene::MbmProblemFiles{number, std::move(scene), std::move(request), {}};
           }),
           py::arg("scene"), py::arg("request"), py::arg("number") = 0)
      .def_readonly("number", &scene::MbmProblemFiles::number)
      .def_readonly("scene", &scene::MbmProblemFiles::scene)
      .def_readonly("request", &scene::MbmProblemFiles::request)
      .def_property_readonly(
          "trajectory",
          [](const scene::MbmProblemFiles& f) -> std::optional<std::filesystem::path> {
            if (f.trajectory.empty()) return std::nullopt;
            return f.trajectory;
          },
          "trajectoryNNNN.yaml beside the problem (a witness path), or None")
      .def("__repr__", [](const scene::MbmProblemFiles& f) {
        return "ArmProblemFiles(number=" + std::to_string(f.number) + ", scene='" + f.scene.string() + "')";
      });
  m.def("list_arm_problems", &scene::listMbmProblems, py::arg("directory"),
        "The problems of a MotionBenchMaker directory (sceneNNNN.yaml with requestNNNN.yaml), by number.");

  py::class_<ArmProblemHandle>(m, "ArmProblem",
                               "A MotionBenchMaker problem ready for planning: the scene, the start and goal "
                               "(full configurations, checked free and within limits) and the group's variables.")
      .def_property_readonly("name", [](const ArmProblemHandle& p) { return p.problem.name; })
      .def_property_readonly("files", [](const ArmProblemHandle& p) { return p.problem.files; })
      .def_property_readonly("group", [](const ArmProblemHandle& p) { return p.problem.group; })
      .def_property_readonly("planner_id", [](const ArmProblemHandle& p) { return p.problem.request.planner_id; })
      .def_property_readonly("allowed_planning_time",
                             [](const ArmProblemHandle& p) { return p.problem.request.allowed_planning_time; })
      .def_property_readonly("scene", [](const ArmProblemHandle& p) { return p.scene; })
      .def_property_readonly("model", [](const ArmProblemHandle& p) { return p.scene.model; })
      .def_property_readonly("start", [](const ArmProblemHandle& p) { return vectorArray(p.problem.start); })
      .def_property_readonly("goal", [](const ArmProblemHandle& p) { return vectorArray(p.problem.goal); })
      .def_property_readonly(
          "group_variables", [](const ArmProblemHandle& p) { return p.problem.space->variables(); },
          "the variables the group moves (indices into a configuration); the others stay at start's values")
      .def_property_readonly("group_variable_names",
                             [](const ArmProblemHandle& p) {
                               std::vector<std::string> out;
                               for (int v : p.problem.space->variables()) out.push_back(p.scene.model->variableName(v));
                               return out;
                             })
      .def_property_readonly("warnings", [](const ArmProblemHandle& p) { return p.problem.warnings; })
      .def("load_trajectory", &trajectoryArray, py::arg("path") = py::none(),
           "A MoveIt trajectory (joint_trajectory.joint_names and points[].positions; by default the problem's "
           "trajectoryNNNN.yaml) as full configurations, one row per point: the start's values with the "
           "trajectory's group joints set. SceneError naming the file for a joint outside the group, a group "
           "joint missing, a value outside its limits or a malformed field.")
      .def("__repr__", [](const ArmProblemHandle& p) {
        return "ArmProblem(name='" + p.problem.name + "', group='" + p.problem.group + "')";
      });
  m.def("load_arm_problem", &loadProblem, py::arg("robot"), py::arg("srdf"), py::arg("problem"), py::kw_only(),
        py::arg("group") = py::none(), py::arg("package_path") = std::vector<std::filesystem::path>(),
        py::arg("contact_distance") = defaults.contact_distance, py::arg("max_depth") = defaults.max_depth,
        "Loads a MotionBenchMaker problem for a robot: robot a RobotModel or a URDF path (package_path for its "
        "meshes), srdf an Srdf or a path, problem an ArmProblemFiles or a (scene, request) pair of paths; group "
        "overrides the request's. SceneError naming the file and the field or joint for anything wrong, including "
        "a start or goal in collision or outside its limits.");
}

}  // namespace mddual::python
