// mddual.HullCastScene and mddual.ArmHullCastScene: the benchmarks' Bullet
// peer checker "hull-cast" (mddual/planning/hull_cast_checkers.h: MoveIt's and
// Tesseract's cast of each piece's convex hull at two poses) on the pieces of
// a Scene or an ArmScene, to run the same edges through it and through the
// exact checks. Exact on translations; on a rotating edge it misses contacts
// inside a piece's arc and outside the hull of its end poses.
//
// check_edges runs the C++ motion validators as the benchmarks install them
// (checker_registry.h's "hull-cast"): FCL's state check on each segment's end
// state and the cast between the segment's ends, segments "resolution"
// (OMPL's default resolution of the space, Tesseract's validator) or
// "whole_edge" (one cast between the edge's ends, MoveIt's cast between two
// states). Each binding has a SpaceInformation of its own, set up once; the
// validators' const methods are thread-safe. Built when the mddual_hull_cast
// library is (Bullet found: MDDUAL_PYTHON_HAS_HULL_CAST).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "arm_bindings.h"
#include "bindings.h"
#include "convert.h"
#include "mddual/error.h"
#include "mddual/planning/arm_checkers.h"
#include "mddual/planning/fcl_checkers.h"
#include "mddual/planning/hull_cast_checkers.h"
#include "planning_convert.h"
#include "scene_binding.h"
#include "typed.h"

namespace mddual::python {
namespace {

namespace mp = mddual::planning;
namespace ob = ompl::base;

/// "resolution" or "whole_edge"; TypeError for another type, ValueError for another str.
mp::CastSegments castSegmentsFrom(const CastSegmentsArg& segments) {
  if (!py::isinstance<py::str>(segments)) {
    throw py::type_error("segments: expected 'resolution' or 'whole_edge', got a " +
                         std::string(py::str(py::type::of(segments).attr("__name__"))));
  }
  const std::string text = segments.cast<std::string>();
  if (text == "resolution") return mp::CastSegments::kResolution;
  if (text == "whole_edge") return mp::CastSegments::kWholeEdge;
  throw py::value_error("segments: expected 'resolution' or 'whole_edge', got '" + mddual::clipForMessage(text) + "'");
}

/// The validator's answer on one edge: (collides, fraction), the fraction of
/// the first failing segment's start (OMPL's lastValid), inf when free.
template <class Validator>
std::pair<bool, double> checkOne(const Validator& v, const ob::State* s1, const ob::State* s2, ob::State* last) {
  std::pair<ob::State*, double> last_valid(last, 0.0);
  if (v.checkMotion(s1, s2, last_valid)) return {false, std::numeric_limits<double>::infinity()};
  return {true, last_valid.second};
}

/// mddual.HullCastScene.
class HullCast {
 public:
  explicit HullCast(const Scene& scene)
      : space_(scene.makeSpace()),
        dim_(scene.dimension()),
        cast_(std::make_shared<const mp::HullCastScene>(scene.problem().robot(), scene.problem().world())),
        si_(std::make_shared<ob::SpaceInformation>(space_->stateSpace())) {
    auto fcl = std::make_shared<const mp::FclScene>(scene.problem().robot(), scene.problem().world());
    si_->setStateValidityChecker(std::make_shared<mp::FclStateValidityChecker>(si_, space_, fcl));
    resolution_ = std::make_shared<mp::HullCastMotionValidator>(si_, space_, cast_, mp::CastSegments::kResolution);
    whole_edge_ = std::make_shared<mp::HullCastMotionValidator>(si_, space_, cast_, mp::CastSegments::kWholeEdge);
    si_->setMotionValidator(resolution_);
    si_->setup();
  }

  BoolOrArray castCollides(const ArrayLikeArg& poses_a, const ArrayLikeArg& poses_b) const {
    const PoseBatch a = poseBatchFrom(poses_a, "X_a");
    const PoseBatch b = poseBatchFrom(poses_b, "X_b");
    BatchSize size;
    size.add(a.poses.size(), a.batched, "X_a");
    size.add(b.poses.size(), b.batched, "X_b");
    const std::size_t n = size.size();
    py::array_t<bool> out(static_cast<py::ssize_t>(n));
    bool* o = out.mutable_data();
    {
      py::gil_scoped_release release;
      for (std::size_t k = 0; k < n; ++k) o[k] = cast_->castCollides(a[k], b[k]);
    }
    if (!a.batched && !b.batched) return py::bool_(o[0]);
    return std::move(out);
  }

  ArrayDict checkEdges(const ArrayLikeArg& starts, const ArrayLikeArg& ends, const CastSegmentsArg& segments) const {
    const mp::HullCastMotionValidator& v = validator(segments);
    const StateBatch s1 = stateBatchFrom(starts, "starts", dim_, "state");
    const StateBatch s2 = stateBatchFrom(ends, "ends", dim_, "state");
    const std::size_t n = batchSizeOf(s1, "starts", s2, "ends");
    py::array_t<bool> collides(static_cast<py::ssize_t>(n));
    py::array_t<double> fraction(static_cast<py::ssize_t>(n));
    {
      bool* c = collides.mutable_data();
      double* f = fraction.mutable_data();
      py::gil_scoped_release release;
      StateHolder last(space_->stateSpace());
      forEachEdge(space_->stateSpace(), dim_, s1, s2, n, [&](std::size_t k, const ob::State* a, const ob::State* b) {
        std::tie(c[k], f[k]) = checkOne(v, a, b, last.get());
      });
    }
    py::dict out;
    out["collides"] = collides;
    out["fraction"] = fraction;
    return out;
  }

  int segmentCount(const ArrayLikeArg& start, const ArrayLikeArg& end) const {
    const StateBatch s1 = stateBatchFrom(start, "start", dim_, "state");
    const StateBatch s2 = stateBatchFrom(end, "end", dim_, "state");
    if (s1.batched || s2.batched) throw py::value_error("segment_count: expected one state each, got a batch");
    StateHolder a(space_->stateSpace()), b(space_->stateSpace());
    a.set(s1.row(0, dim_), dim_, "start");
    b.set(s2.row(0, dim_), dim_, "end");
    return static_cast<int>(std::max(1U, space_->stateSpace()->validSegmentCount(a.get(), b.get())));
  }

 private:
  const mp::HullCastMotionValidator& validator(const CastSegmentsArg& segments) const {
    return castSegmentsFrom(segments) == mp::CastSegments::kWholeEdge ? *whole_edge_ : *resolution_;
  }

  mp::PlanningSpacePtr space_;
  int dim_;
  std::shared_ptr<const mp::HullCastScene> cast_;
  ob::SpaceInformationPtr si_;
  std::shared_ptr<mp::HullCastMotionValidator> resolution_, whole_edge_;
};

/// Every variable of `model`, in order: the arm cast's space.
std::vector<int> allVariables(const scene::RobotModel& model) {
  std::vector<int> out(static_cast<std::size_t>(model.numVariables()));
  std::iota(out.begin(), out.end(), 0);
  return out;
}

/// mddual.ArmHullCastScene.
class ArmHullCast {
 public:
  explicit ArmHullCast(const ArmSceneHandle& arm)
      : model_(arm.model),
        cast_(std::make_shared<const mp::ArmHullCastScene>(arm.scene)),
        space_(mp::ArmSpace::make(arm.model, allVariables(*arm.model))),
        si_(std::make_shared<ob::SpaceInformation>(space_->stateSpace())) {
    auto fcl = std::make_shared<const mp::FclArmScene>(arm.scene);
    si_->setStateValidityChecker(std::make_shared<mp::FclArmStateValidityChecker>(si_, space_, fcl));
    resolution_ = std::make_shared<mp::ArmHullCastMotionValidator>(si_, space_, cast_, mp::CastSegments::kResolution);
    whole_edge_ = std::make_shared<mp::ArmHullCastMotionValidator>(si_, space_, cast_, mp::CastSegments::kWholeEdge);
    si_->setMotionValidator(resolution_);
    si_->setup();
  }

  BoolOrArray castCollides(const ArrayLikeArg& q0, const ArrayLikeArg& q1, int threads) const {
    const StateBatch a = configBatchFrom(q0, "Q0", *model_);
    const StateBatch b = configBatchFrom(q1, "Q1", *model_);
    const std::size_t n = batchSizeOf(a, "Q0", b, "Q1");
    py::array_t<bool> out(static_cast<py::ssize_t>(n));
    bool* o = out.mutable_data();
    {
      py::gil_scoped_release release;
      const int nv = model_->numVariables();
      parallelFor(n, workerCount(threads, n),
                  [&](std::size_t k) { o[k] = cast_->castCollides(a.row(k, nv), b.row(k, nv)); });
    }
    if (!a.batched && !b.batched) return py::bool_(o[0]);
    return std::move(out);
  }

  ArmContactResult castContact(const ArrayLikeArg& q0, const ArrayLikeArg& q1) const {
    const StateBatch a = configBatchFrom(q0, "q0", *model_);
    const StateBatch b = configBatchFrom(q1, "q1", *model_);
    if (a.batched || b.batched) throw py::value_error("cast_contact: expected one configuration each, got a batch");
    mp::ArmContact c;
    bool hit = false;
    {
      py::gil_scoped_release release;
      hit = cast_->castCollides(a.row(0, model_->numVariables()), b.row(0, model_->numVariables()), &c);
    }
    if (!hit) return py::none();
    return armContactDict(*model_, cast_->scene(), c);
  }

  EdgeResults checkEdges(const ArrayLikeArg& q0, const ArrayLikeArg& q1, const CastSegmentsArg& segments,
                         int threads) const {
    const mp::ArmHullCastMotionValidator& v =
        castSegmentsFrom(segments) == mp::CastSegments::kWholeEdge ? *whole_edge_ : *resolution_;
    return edgeBatch(q0, q1, *model_, threads, [&](const double* a, const double* b) {
      StateHolder s1(space_->stateSpace()), s2(space_->stateSpace()), last(space_->stateSpace());
      space_->setState(s1.get(), a);
      space_->setState(s2.get(), b);
      return checkOne(v, s1.get(), s2.get(), last.get());
    });
  }

  int segmentCount(const ArrayLikeArg& q0, const ArrayLikeArg& q1) const {
    const StateBatch a = configBatchFrom(q0, "q0", *model_);
    const StateBatch b = configBatchFrom(q1, "q1", *model_);
    if (a.batched || b.batched) throw py::value_error("segment_count: expected one configuration each, got a batch");
    StateHolder s1(space_->stateSpace()), s2(space_->stateSpace());
    space_->setState(s1.get(), a.row(0, model_->numVariables()));
    space_->setState(s2.get(), b.row(0, model_->numVariables()));
    return static_cast<int>(std::max(1U, space_->stateSpace()->validSegmentCount(s1.get(), s2.get())));
  }

 private:
  std::shared_ptr<scene::RobotModel> model_;
  std::shared_ptr<const mp::ArmHullCastScene> cast_;
  mp::ArmSpacePtr space_;
  ob::SpaceInformationPtr si_;
  std::shared_ptr<mp::ArmHullCastMotionValidator> resolution_, whole_edge_;
};

}  // namespace

void bindHullCast(py::module_& m) {
  py::class_<HullCast>(
      m, "HullCastScene",
      "The benchmarks' peer checker 'hull-cast' on a Scene's pieces: Bullet's cast of each robot piece's convex hull "
      "at two poses against the world (MoveIt's and Tesseract's continuous check). Exact on translations; a "
      "rotating piece's contacts inside its arc and outside that hull are MISSED (not sound on rotating edges), "
      "where Scene.check_edges is certified.")
      .def(py::init<const Scene&>(), py::arg("scene"))
      .def("cast_collides", &HullCast::castCollides, py::arg("X_a"), py::arg("X_b"),
           "Whether the hull of some robot piece at pose X_a and at X_b (4x4, or (K, 4, 4) for a bool array) "
           "overlaps a world piece: one cast, no state check, no bounds.")
      .def("check_edges", &HullCast::checkEdges, py::arg("starts"), py::arg("ends"), py::kw_only(),
           py::arg("segments") = "resolution",
           "The hull-cast motion check of each edge starts[k] -> ends[k] (states as in Scene.check_edges), as "
           "the benchmarks run it: segments='resolution' cuts the edge at OMPL's resolution (segment_count), "
           "checks each segment's end state with FCL and casts between its ends (Tesseract's validator); "
           "'whole_edge' casts once between the edge's ends (MoveIt's cast between two states). An end outside "
           "the position bounds fails the edge at 0. Returns a dict: collides (bool, K), fraction (K,: the "
           "start of the first failing segment, no bound on the first contact; inf when free).")
      .def("segment_count", &HullCast::segmentCount, py::arg("start"), py::arg("end"),
           "The segments segments='resolution' cuts the edge start -> end into (OMPL's validSegmentCount).")
      .def("__repr__", [](const HullCast&) { return std::string("HullCastScene()"); });

  py::class_<ArmHullCast>(
      m, "ArmHullCastScene",
      "The benchmarks' peer checker 'hull-cast' on an ArmScene: Bullet's cast of each checked link piece's convex "
      "hull at two configurations against the world and, for the self pairs the ArmScene checks, against the "
      "other link's swept hulls. Misses contacts of turning links outside those hulls (not sound), where "
      "ArmScene.check_edges is certified. Configurations are full: (n,) or (K, n).")
      .def(py::init<const ArmSceneHandle&>(), py::arg("scene"))
      .def("cast_collides", &ArmHullCast::castCollides, py::arg("Q0"), py::arg("Q1"), py::kw_only(),
           py::arg("threads") = 1,
           "Whether the hulls of some checked pair overlap for the edge Q0[k] -> Q1[k]: one cast between the two "
           "configurations, no state check, no limits. threads: workers (0: one per core).")
      .def("cast_contact", &ArmHullCast::castContact, py::arg("q0"), py::arg("q1"),
           "For one edge, the pair cast_collides finds: None, else a dict as ArmScene.contact's.")
      .def("check_edges", &ArmHullCast::checkEdges, py::arg("Q0"), py::arg("Q1"), py::kw_only(),
           py::arg("segments") = "resolution", py::arg("threads") = 1,
           "The hull-cast motion check of each edge Q0[k] -> Q1[k], as the arm benchmark runs it, in an OMPL "
           "space of all the model's variables (a continuous joint turns the short way): segments='resolution' "
           "cuts the edge at OMPL's resolution (segment_count), checks each segment's end state with FCL and "
           "casts between its ends; 'whole_edge' casts once between the ends. An end outside the joint limits "
           "(a continuous joint's outside [-pi, pi]) fails the edge at 0. Returns (collides, fraction) as "
           "ArmScene.check_edges; fraction: the start of the first failing segment (no bound on the first "
           "contact), inf when free.")
      .def("segment_count", &ArmHullCast::segmentCount, py::arg("q0"), py::arg("q1"),
           "The segments segments='resolution' cuts the edge q0 -> q1 into (OMPL's validSegmentCount).")
      .def("__repr__", [](const ArmHullCast&) { return std::string("ArmHullCastScene()"); });
}

}  // namespace mddual::python
