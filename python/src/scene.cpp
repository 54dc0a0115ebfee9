// mddual.Scene: a benchmark config's robot and world (mddual::planning's
// loadProblem) with the exact checks of the planning layer (MddScene) on
// arrays of poses, states and edges. States use OMPL's layout for the
// config's space ("se2": x, y, yaw; "se3": x, y, z, qx, qy, qz, qw; "r2": x, y;
// "r3": x, y, z); edges follow OMPL's interpolation (PlanningSpace::motion).
// The loops run without the GIL; MddScene's const methods are thread-safe.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <sstream>

#include "bindings.h"
#include "convert.h"
#include "mddual/planning/clearance.h"
#include "mddual/planning/mdd_scene.h"
#include "mddual/planning/problem_setup.h"
#include "mddual/planning/state_space.h"
#include "planning_convert.h"
#include "scene_binding.h"
#include "typed.h"

namespace mddual::python {
namespace {

namespace mp = mddual::planning;
namespace ob = ompl::base;

/// Numbers per state of each space kind (OMPL's copyToReals order).
int stateDimension(mp::SpaceKind kind) {
  switch (kind) {
    case mp::SpaceKind::kSE2: return 3;
    case mp::SpaceKind::kSE3: return 7;
    case mp::SpaceKind::kR2: return 2;
    case mp::SpaceKind::kR3: return 3;
  }
  return 0;
}

/// SE(3)'s quaternion (components 3 to 6) made unit: scaled by its largest
/// component first (its norm overflows at 1e200); InvalidInputError when
/// its norm is below mp::kMinQuaternionNorm, the planning layer's "no
/// rotation" (a zero one aborted in OMPL's SO(3) code from check_edges and
/// was the identity in pose()).
void normaliseQuaternion(std::vector<double>* reals, const std::string& what) {
  Eigen::Map<Eigen::Vector4d> q(reals->data() + 3);
  const double largest = q.cwiseAbs().maxCoeff();
  const double norm = largest > 0.0 ? largest * (q / largest).norm() : 0.0;
  if (!(norm >= mp::kMinQuaternionNorm)) {
    std::ostringstream msg;
    msg << what << ": the quaternion (components 3 to 6) has norm " << norm << ", below " << mp::kMinQuaternionNorm
        << ": not a rotation";
    throw InvalidInputError(msg.str());
  }
  q /= largest;
  q.normalize();
}

scene::SpaceKind spaceKindFrom(const std::string& text) {
  for (scene::SpaceKind kind :
       {scene::SpaceKind::kSE2, scene::SpaceKind::kSE3, scene::SpaceKind::kR2, scene::SpaceKind::kR3}) {
    if (text == mp::toString(mp::toPlanningKind(kind))) return kind;
  }
  throw py::value_error("space: expected 'SE2', 'SE3', 'R2' or 'R3', got '" + mddual::clipForMessage(text) + "'");
}

}  // namespace

void StateHolder::set(const double* values, int d, const std::string& what) {
  for (int i = 0; i < d; ++i) {
    if (!std::isfinite(values[i])) {
      throw InvalidInputError(what + ": component " + std::to_string(i) + " is not finite");
    }
  }
  std::vector<double> reals(values, values + d);
  if (space_->getType() == ob::STATE_SPACE_SE3) normaliseQuaternion(&reals, what);
  space_->copyFromReals(state_, reals);
}

Scene::Scene(mp::Problem problem) : problem_(std::move(problem)) {
  space_ = makeSpace();
  scene_ = std::make_shared<mp::MddScene>(problem_.robot(), problem_.world());
  dim_ = stateDimension(space_->kind());
}

mp::PlanningSpacePtr Scene::makeSpace() const {
  const scene::ProblemScene& sc = *problem_.scene;
  mp::PlanningSpacePtr space = mp::PlanningSpace::make(
      mp::toPlanningKind(sc.space), sc.bounds, sc.start.translation().z(), Eigen::Quaterniond(sc.start.linear()));
  // setup() fills the value locations that copyToReals / copyFromReals use.
  space->stateSpace()->setup();
  return space;
}

Scene Scene::load(const std::filesystem::path& cfg) {
  return Scene(mp::loadProblem(cfg));
}

Scene Scene::fromPolytopes(const std::vector<ConvexPolytope>& robot, const std::vector<ConvexPolytope>& world,
                           const std::string& space, const ArrayLikeArg& bounds, const ArrayLikeOrNoneArg& start,
                           const ArrayLikeOrNoneArg& goal, const std::string& name) {
  scene::ProblemScene sc;
  sc.space = spaceKindFrom(space);
  const DoubleArray b = toDoubleArray(bounds, "bounds", "a (2, 3) array: min and max corner");
  if (b.ndim() != 2 || b.shape(0) != 2 || b.shape(1) != 3) {
    throw py::value_error("bounds: expected a (2, 3) array: min and max corner, got shape " + shapeText(b));
  }
  sc.bounds = Eigen::AlignedBox3d(Eigen::Vector3d(b.at(0, 0), b.at(0, 1), b.at(0, 2)),
                                  Eigen::Vector3d(b.at(1, 0), b.at(1, 1), b.at(1, 2)));
  sc.start = poseFrom(start, "start");
  sc.goal = poseFrom(goal, "goal");
  std::vector<scene::Piece> robot_pieces;
  for (std::size_t i = 0; i < robot.size(); ++i) {
    robot_pieces.push_back(scene::Piece::make(robot[i], scene::PieceKind::kConvex, "robot " + std::to_string(i)));
  }
  std::vector<scene::Piece> world_pieces;
  for (std::size_t i = 0; i < world.size(); ++i) {
    world_pieces.push_back(scene::Piece::make(world[i], scene::PieceKind::kConvex, "world " + std::to_string(i)));
  }
  sc.robot = scene::RigidBody(std::move(robot_pieces), "robot");
  sc.world = scene::World(std::move(world_pieces), "world");
  scene::ProblemConfig config;
  config.name = name;
  config.space = sc.space;
  Scene out(mp::makeProblem(std::move(config), std::move(sc)));
  // The start and goal must be states of the space (e.g. planar for SE2).
  out.stateOf(out.problem().scene->start);
  out.stateOf(out.problem().scene->goal);
  return out;
}

py::array_t<double> Scene::stateOf(const Eigen::Isometry3d& X_WR) const {
  StateHolder s(space_->stateSpace());
  space_->setPose(X_WR, s.get());
  std::vector<double> reals;
  space_->stateSpace()->copyToReals(reals, s.get());
  return py::array_t<double>(static_cast<py::ssize_t>(reals.size()), reals.data());
}

Eigen::Matrix4d Scene::poseOf(const ArrayLikeArg& state) const {
  const StateBatch b = stateBatchFrom(state, "state", dim_, "state");
  if (b.batched) throw py::value_error("state: expected one state, got a batch");
  StateHolder s(space_->stateSpace());
  s.set(b.values.data(), dim_, "state");
  return space_->pose(s.get()).matrix();
}

BoolOrArray Scene::collides(const ArrayLikeArg& poses) const {
  const PoseBatch X = poseBatchFrom(poses, "X_WR");
  const std::size_t n = X.poses.size();
  py::array_t<bool> out(static_cast<py::ssize_t>(n));
  bool* o = out.mutable_data();
  {
    py::gil_scoped_release release;
    for (std::size_t k = 0; k < n; ++k) o[k] = scene_->collides(X.poses[k]);
  }
  if (!X.batched) return py::bool_(o[0]);
  return std::move(out);
}

BoolOrArray Scene::isValid(const ArrayLikeArg& states) const {
  const StateBatch b = stateBatchFrom(states, "states", dim_, "state");
  py::array_t<bool> out(static_cast<py::ssize_t>(b.count));
  bool* o = out.mutable_data();
  {
    py::gil_scoped_release release;
    StateHolder s(space_->stateSpace());
    for (std::size_t k = 0; k < b.count; ++k) {
      s.set(b.row(k, dim_), dim_, itemName("states", k, b.batched));
      const Eigen::Isometry3d X_WR = space_->pose(s.get());
      o[k] = space_->positionInBounds(X_WR.translation()) && !scene_->collides(X_WR);
    }
  }
  if (!b.batched) return py::bool_(o[0]);
  return std::move(out);
}

ArrayDict Scene::checkEdges(const ArrayLikeArg& starts, const ArrayLikeArg& ends) const {
  const StateBatch s1 = stateBatchFrom(starts, "starts", dim_, "state");
  const StateBatch s2 = stateBatchFrom(ends, "ends", dim_, "state");
  const std::size_t n = batchSizeOf(s1, "starts", s2, "ends");
  py::array_t<bool> collides(static_cast<py::ssize_t>(n));
  py::array_t<bool> start_collides(static_cast<py::ssize_t>(n));
  py::array_t<double> fraction(static_cast<py::ssize_t>(n));
  py::array_t<bool> exact(static_cast<py::ssize_t>(n));
  {
    bool* c = collides.mutable_data();
    bool* sc = start_collides.mutable_data();
    double* f = fraction.mutable_data();
    bool* e = exact.mutable_data();
    py::gil_scoped_release release;
    forEachEdge(space_->stateSpace(), dim_, s1, s2, n, [&](std::size_t k, const ob::State* a, const ob::State* b) {
      const mp::EdgeContact r = mp::edgeContact(*scene_, *space_, a, b);
      c[k] = r.collides;
      sc[k] = r.start_collides;
      f[k] = r.fraction;
      e[k] = r.exact;
    });
  }
  py::dict out;
  out["collides"] = collides;
  out["start_collides"] = start_collides;
  out["fraction"] = fraction;
  out["exact"] = exact;
  return out;
}

ArrayDict Scene::directedClearance(const ArrayLikeArg& poses, const ArrayLikeArg& directions,
                                   const ArrayLikeArg& max_distance) const {
  const PoseBatch X = poseBatchFrom(poses, "X_WR");
  const VectorBatch u = vectorBatchFrom(directions, "directions");
  const ScalarBatch limit = scalarBatchFrom(max_distance, "max_distance");
  BatchSize size;
  size.add(X.poses.size(), X.batched, "X_WR");
  size.add(u.vectors.size(), u.batched, "directions");
  size.add(limit.values.size(), limit.batched, "max_distance");
  const std::size_t n = size.size();
  py::array_t<double> distance(static_cast<py::ssize_t>(n));
  py::array_t<bool> start_collides(static_cast<py::ssize_t>(n));
  py::array_t<std::int32_t> robot_piece(static_cast<py::ssize_t>(n));
  py::array_t<std::int32_t> world_piece(static_cast<py::ssize_t>(n));
  py::array_t<double> point({static_cast<py::ssize_t>(n), py::ssize_t{3}});
  py::array_t<double> normal({static_cast<py::ssize_t>(n), py::ssize_t{3}});
  {
    double* dist = distance.mutable_data();
    bool* sc = start_collides.mutable_data();
    std::int32_t* rp = robot_piece.mutable_data();
    std::int32_t* wp = world_piece.mutable_data();
    double* p = point.mutable_data();
    double* nn = normal.mutable_data();
    py::gil_scoped_release release;
    for (std::size_t k = 0; k < n; ++k) {
      mp::DirectedClearance r;
      try {
        r = mp::directedClearance(*scene_, X[k], u[k], limit[k]);
      } catch (const InvalidInputError& e) {
        throw InvalidInputError("directed_clearance: query " + std::to_string(k) + ": " + e.what());
      }
      dist[k] = r.distance;
      sc[k] = r.start_collides;
      rp[k] = r.contact.robot_piece;
      wp[k] = r.contact.world_piece;
      for (std::size_t j = 0; j < 3; ++j) {
        p[3 * k + j] = r.contact.p_WC(static_cast<Eigen::Index>(j));
        nn[3 * k + j] = r.contact.n_W(static_cast<Eigen::Index>(j));
      }
    }
  }
  py::dict out;
  out["distance"] = distance;
  out["start_collides"] = start_collides;
  out["robot_piece"] = robot_piece;
  out["world_piece"] = world_piece;
  out["point"] = point;
  out["normal"] = normal;
  return out;
}

void bindScene(py::module_& m) {
  // scene::SceneError: a subclass of InvalidInputError (as in C++); this
  // translator is registered after bindErrors' and so is tried first.
  static PyObject* scene_error = [&m] {
    const py::object base = m.attr("InvalidInputError");
    PyObject* cls = PyErr_NewExceptionWithDoc("mddual.SceneError",
                                              "Bad scene input: an unreadable or malformed config, URDF or mesh "
                                              "file; the message names the file and the line or element.",
                                              base.ptr(), nullptr);
    if (cls == nullptr) throw py::error_already_set();
    m.add_object("SceneError", py::reinterpret_borrow<py::object>(cls));
    return cls;
  }();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const scene::SceneError& e) {
      PyErr_SetString(scene_error, e.what());
    }
  });

  const double inf = std::numeric_limits<double>::infinity();
  py::class_<Scene>(m, "Scene",
                    "A benchmark config's robot and world (Scene.load(cfg)) with the planning layer's exact checks. "
                    "States use OMPL's layout for the space: 'se2' (x, y, yaw), 'se3' (x, y, z, qx, qy, qz, qw), "
                    "'r2' (x, y), 'r3' (x, y, z).")
      .def_static("load", &Scene::load, py::arg("cfg"),
                  "Reads an OMPL.app-style .cfg and loads its robot and world (SceneError naming the file and "
                  "line for anything wrong).")
      .def_static("from_polytopes", &Scene::fromPolytopes, py::arg("robot"), py::arg("world"), py::kw_only(),
                  py::arg("space") = "SE3", py::arg("bounds"), py::arg("start") = py::none(),
                  py::arg("goal") = py::none(), py::arg("name") = "in_memory",
                  "A scene from polytopes in memory: robot pieces (frame R) and world pieces (world frame), "
                  "the space kind, the position bounds ((2, 3): min and max corner) and the start and goal poses "
                  "(None: identity; the translation-only spaces keep the start's orientation).")
      .def_property_readonly("name", [](const Scene& s) { return s.problem().name; })
      .def_property_readonly("space", [](const Scene& s) { return mp::toString(s.space().kind()); })
      .def_property_readonly("state_dimension", &Scene::dimension)
      .def_property_readonly(
          "bounds",
          [](const Scene& s) {
            Eigen::Matrix<double, 2, 3, Eigen::RowMajor> b;
            b.row(0) = s.space().bounds().min().transpose();
            b.row(1) = s.space().bounds().max().transpose();
            return b;
          },
          "(2, 3): the position bounds' min and max (planar spaces: x and y bound the state)")
      .def_property_readonly(
          "start", [](const Scene& s) { return s.problem().scene->start.matrix().eval(); },
          "4x4 pose X_WR of the start")
      .def_property_readonly("goal", [](const Scene& s) { return s.problem().scene->goal.matrix().eval(); })
      .def_property_readonly("start_state", [](const Scene& s) { return s.stateOf(s.problem().scene->start); })
      .def_property_readonly("goal_state", [](const Scene& s) { return s.stateOf(s.problem().scene->goal); })
      .def_property_readonly(
          "robot_pieces", [](const Scene& s) { return polytopes(s.mddScene().robot().pieces()); },
          "the robot's convex pieces (ConvexPolytope, robot frame R)")
      .def_property_readonly(
          "world_pieces", [](const Scene& s) { return polytopes(s.mddScene().world().pieces()); },
          "the world's convex pieces (ConvexPolytope, world frame)")
      .def_property_readonly("robot_piece_origins",
                             [](const Scene& s) { return origins(s.mddScene().robot().pieces()); })
      .def_property_readonly("world_piece_origins",
                             [](const Scene& s) { return origins(s.mddScene().world().pieces()); })
      .def_property_readonly("warnings", [](const Scene& s) { return s.problem().scene->warnings; })
      .def(
          "state", [](const Scene& s, const ArrayLikeArg& X_WR) { return s.stateOf(poseFrom(X_WR, "X_WR")); },
          py::arg("X_WR"), "The state of this space whose pose is X_WR (InvalidInputError if there is none).")
      .def("pose", &Scene::poseOf, py::arg("state"), "The robot's 4x4 pose X_WR in `state`.")
      .def("collides", &Scene::collides, py::arg("X_WR"),
           "Whether the robot at pose X_WR (4x4, or (K, 4, 4) for a bool array) touches or overlaps the world.")
      .def("is_valid", &Scene::isValid, py::arg("states"),
           "Whether each state (one, or (K, d)) is within the position bounds and free of the world.")
      .def("check_edges", &Scene::checkEdges, py::arg("starts"), py::arg("ends"),
           "The first contact on each edge starts[k] -> ends[k] under OMPL's interpolation (geometry only: the "
           "bounds are not checked). Returns a dict: collides, start_collides, exact (bool, K), fraction (K,: "
           "first contact in [0, 1], exact for translation edges and a lower bound for rotating ones; inf when "
           "free).")
      .def("directed_clearance", &Scene::directedClearance, py::arg("X_WR"), py::arg("directions"), py::kw_only(),
           py::arg("max_distance") = inf,
           "How far the robot at X_WR can translate along each direction before it touches the world (inf when "
           "never within max_distance; when it already touches, minus the deepest pair's way out, see "
           "clearance.h). Returns a dict: distance, start_collides, robot_piece, world_piece (K,), point, "
           "normal (K, 3).")
      .def("__repr__", [](const Scene& s) {
        return "Scene(name='" + s.problem().name + "', space='" + mp::toString(s.space().kind()) +
               "', robot_pieces=" + std::to_string(s.mddScene().robot().pieces().size()) +
               ", world_pieces=" + std::to_string(s.mddScene().world().pieces().size()) + ")";
      });
}

}  // namespace mddual::python
