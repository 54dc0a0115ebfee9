// One-pair queries: mdd, toi, intersect, penetration_depth, width, distance. The
// arguments are converted under the GIL; the query itself runs without it.
#include "mddual/brute_force.h"
#include "mddual/distance.h"
#include "mddual/error.h"
#include "mddual/penetration.h"
#include "mddual/query.h"

#include <limits>

#include "bindings.h"
#include "convert.h"
#include "typed.h"

namespace mddual::python {

QueryMethod queryMethodFrom(const std::string& text, const char* name) {
  if (text == "mddual") return QueryMethod::kMddual;
  if (text == "brute") return QueryMethod::kBrute;
  throw py::value_error(std::string(name) + ": expected 'mddual' or 'brute', got '" + mddual::clipForMessage(text) +
                        "'");
}

PenetrationMethod penetrationMethodFrom(const std::string& text, const char* name) {
  for (PenetrationMethod method : {PenetrationMethod::kExact, PenetrationMethod::kShallow, PenetrationMethod::kApprox,
                                   PenetrationMethod::kBruteForce}) {
    if (text == toString(method)) return method;
  }
  throw py::value_error(std::string(name) + ": expected 'exact', 'shallow', 'approx' or 'brute', got '" +
                        mddual::clipForMessage(text) + "'");
}

namespace {

DirectionalInput directionalInput(const ConvexPolytope& a, const ArrayLikeOrNoneArg& X_WA, const ConvexPolytope& b,
                                  const ArrayLikeOrNoneArg& X_WB, const ArrayLikeArg& direction) {
  DirectionalInput in;
  in.a = &a;
  in.X_WA = poseFrom(X_WA, "X_WA");
  in.b = &b;
  in.X_WB = poseFrom(X_WB, "X_WB");
  in.s_W = vectorFrom(direction, "direction");
  return in;
}

MddResult mddCall(const ConvexPolytope& a, const ArrayLikeOrNoneArg& X_WA, const ConvexPolytope& b,
                  const ArrayLikeOrNoneArg& X_WB, const ArrayLikeArg& direction, const std::string& method) {
  const QueryMethod m = queryMethodFrom(method, "method");
  const DirectionalInput in = directionalInput(a, X_WA, b, X_WB, direction);
  py::gil_scoped_release release;
  return m == QueryMethod::kBrute ? bruteForceMdd(in) : mdd(in);
}

ToiResult toiCall(const ConvexPolytope& a, const ArrayLikeOrNoneArg& X_WA, const ConvexPolytope& b,
                  const ArrayLikeOrNoneArg& X_WB, const ArrayLikeArg& direction, double max_distance, bool exact,
                  const std::string& method) {
  const QueryMethod m = queryMethodFrom(method, "method");
  DirectionalInput in = directionalInput(a, X_WA, b, X_WB, direction);
  in.max_distance = max_distance;
  in.exact_toi = exact;
  py::gil_scoped_release release;
  return m == QueryMethod::kBrute ? bruteForceToi(in) : toi(in);
}

IntersectResult intersectCall(const ConvexPolytope& a, const ArrayLikeOrNoneArg& X_WA, const ConvexPolytope& b,
                              const ArrayLikeOrNoneArg& X_WB, const std::string& method) {
  const QueryMethod m = queryMethodFrom(method, "method");
  IntersectInput in;
  in.a = &a;
  in.X_WA = poseFrom(X_WA, "X_WA");
  in.b = &b;
  in.X_WB = poseFrom(X_WB, "X_WB");
  py::gil_scoped_release release;
  return m == QueryMethod::kBrute ? bruteForceIntersect(in) : intersect(in);
}

PenetrationResult penetrationCall(const ConvexPolytope& a, const ArrayLikeOrNoneArg& X_WA, const ConvexPolytope& b,
                                  const ArrayLikeOrNoneArg& X_WB, const std::string& method, double delta) {
  PenetrationInput in;
  in.method = penetrationMethodFrom(method, "method");
  in.a = &a;
  in.X_WA = poseFrom(X_WA, "X_WA");
  in.b = &b;
  in.X_WB = poseFrom(X_WB, "X_WB");
  in.delta = delta;
  py::gil_scoped_release release;
  return penetrationDepth(in);
}

WidthResult widthCall(const ConvexPolytope& a, const ArrayLikeOrNoneArg& X_WA, const std::string& method,
                      double delta) {
  WidthInput in;
  in.method = penetrationMethodFrom(method, "method");
  in.a = &a;
  in.X_WA = poseFrom(X_WA, "X_WA");
  in.delta = delta;
  py::gil_scoped_release release;
  return width(in);
}

DistanceResult distanceCall(const ConvexPolytope& a, const ArrayLikeOrNoneArg& X_WA, const ConvexPolytope& b,
                            const ArrayLikeOrNoneArg& X_WB) {
  DistanceInput in;
  in.a = &a;
  in.X_WA = poseFrom(X_WA, "X_WA");
  in.b = &b;
  in.X_WB = poseFrom(X_WB, "X_WB");
  py::gil_scoped_release release;
  return distance(in);
}

}  // namespace

void bindQueries(py::module_& m) {
  const double inf = std::numeric_limits<double>::infinity();
  m.def("mdd", &mddCall, py::arg("a"), py::arg("X_WA"), py::arg("b"), py::arg("X_WB"), py::arg("direction"),
        py::kw_only(), py::arg("method") = "mddual",
        "Signed minimum directional distance of A (fixed) and B (moving along `direction`, any nonzero length). "
        "method='brute' builds A - B explicitly (the slow reference).");
  m.def("toi", &toiCall, py::arg("a"), py::arg("X_WA"), py::arg("b"), py::arg("X_WB"), py::arg("direction"),
        py::kw_only(), py::arg("max_distance") = inf, py::arg("exact") = true, py::arg("method") = "mddual",
        "How far B can translate along `direction` before it touches A ('never' beyond max_distance). With "
        "exact=False a hit may be reported before the first contact is computed (toi_exact False, toi an upper "
        "bound).");
  m.def("intersect", &intersectCall, py::arg("a"), py::arg("X_WA"), py::arg("b"), py::arg("X_WB"), py::kw_only(),
        py::arg("method") = "mddual", "Intersection test of A and B.");
  m.def("penetration_depth", &penetrationCall, py::arg("a"), py::arg("X_WA"), py::arg("b"), py::arg("X_WB"),
        py::kw_only(), py::arg("method") = "exact", py::arg("delta") = 0.0,
        "Penetration depth of A and B (0 unless the interiors overlap). method: 'exact', 'shallow', 'approx' "
        "(within a factor 1 + delta) or 'brute'; delta = 0 selects the method's default.");
  m.def("width", &widthCall, py::arg("a"), py::arg("X_WA") = py::none(), py::kw_only(), py::arg("method") = "exact",
        py::arg("delta") = 0.0, "Width of A: the smallest distance between two parallel planes enclosing it.");
  m.def("distance", &distanceCall, py::arg("a"), py::arg("X_WA"), py::arg("b"), py::arg("X_WB"),
        "Euclidean separation distance of A and B with a witness point on each (0 when touching, minus the "
        "exact penetration depth when the interiors overlap).");
}

}  // namespace mddual::python
