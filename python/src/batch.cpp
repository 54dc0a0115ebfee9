// Batch forms: one pair of polytopes, K queries (poses (K, 4, 4) and
// directions (K, 3), or one of each shared by every query). The inputs are
// converted and the output arrays allocated under the GIL; the loop runs
// without it. Statuses come back as small integers: the index of the status
// name in mddual.CONTACT_STATUSES / TOI_STATUSES / INTERSECT_STATUSES (the
// C++ enum's value).
#include <pybind11/numpy.h>

#include <cstdint>
#include <limits>

#include "bindings.h"
#include "convert.h"
#include "mddual/error.h"
#include "mddual/query.h"
#include "typed.h"

namespace mddual::python {
namespace {

/// Re-throws the exception being handled with "<prefix>" before its message,
/// keeping its type (call inside a catch block).
[[noreturn]] void rethrowWithPrefix(const std::string& prefix) {
  try {
    throw;
  } catch (const DegenerateGeometryError& e) {
    throw DegenerateGeometryError(prefix + e.what());
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(prefix + e.what());
  } catch (const HullError& e) {
    throw HullError(prefix + e.what());
  } catch (const NumericalError& e) {
    throw NumericalError(prefix + e.what());
  } catch (const Error& e) {
    throw Error(prefix + e.what());
  }
}

std::string queryPrefix(const char* function, std::size_t k) {
  return std::string(function) + ": query " + std::to_string(k) + ": ";
}

py::array_t<double> vectors(std::size_t n) {
  return py::array_t<double>({static_cast<py::ssize_t>(n), py::ssize_t{3}});
}
py::array_t<double> scalars(std::size_t n) {
  return py::array_t<double>(static_cast<py::ssize_t>(n));
}
py::array_t<std::int8_t> codes(std::size_t n) {
  return py::array_t<std::int8_t>(static_cast<py::ssize_t>(n));
}

void store(double* out, std::size_t k, const Eigen::Vector3d& v) {
  for (int j = 0; j < 3; ++j) out[3 * k + static_cast<std::size_t>(j)] = v(j);
}

/// The arguments every batch shares, converted under the GIL.
struct PairBatch {
  PoseBatch X_WA;
  PoseBatch X_WB;
  BatchSize size;
};

PairBatch pairBatch(const py::object& X_WA, const py::object& X_WB) {
  PairBatch p{poseBatchFrom(X_WA, "X_WA"), poseBatchFrom(X_WB, "X_WB"), {}};
  p.size.add(p.X_WA.poses.size(), p.X_WA.batched, "X_WA");
  p.size.add(p.X_WB.poses.size(), p.X_WB.batched, "X_WB");
  return p;
}

/// Runs query(k, warm) for k = 0 .. n - 1 without the GIL, with one warm
/// start carried from query to query (nullptr without warm_start); an error
/// of query k is re-thrown with "<function>: query k: " before its message.
/// The output arrays' pointers must be taken before (under the GIL).
template <typename Query>
void runQueries(const char* function, std::size_t n, bool warm_start, const Query& query) {
  py::gil_scoped_release release;
  WarmStart warm;
  for (std::size_t k = 0; k < n; ++k) {
    try {
      query(k, warm_start ? &warm : nullptr);
    } catch (const Error&) {
      rethrowWithPrefix(queryPrefix(function, k));
    }
  }
}

/// Query k's input: the pair at its poses, direction s_W.
DirectionalInput directionalInput(const ConvexPolytope& a, const ConvexPolytope& b, const PairBatch& p, std::size_t k,
                                  const Eigen::Vector3d& s_W) {
  DirectionalInput in;
  in.a = &a;
  in.X_WA = p.X_WA[k];
  in.b = &b;
  in.X_WB = p.X_WB[k];
  in.s_W = s_W;
  return in;
}

ArrayDict mddBatch(const ConvexPolytope& a, const ArrayLikeOrNoneArg& X_WA, const ConvexPolytope& b,
                   const ArrayLikeOrNoneArg& X_WB, const ArrayLikeArg& directions, bool warm_start) {
  PairBatch p = pairBatch(X_WA, X_WB);
  const VectorBatch s = vectorBatchFrom(directions, "directions");
  p.size.add(s.vectors.size(), s.batched, "directions");
  const std::size_t n = p.size.size();
  auto status = codes(n);
  auto distance = scalars(n);
  auto t_lo = scalars(n);
  auto t_hi = scalars(n);
  auto normal = vectors(n);
  auto point = vectors(n);
  std::int8_t* status_out = status.mutable_data();
  double* distance_out = distance.mutable_data();
  double* t_lo_out = t_lo.mutable_data();
  double* t_hi_out = t_hi.mutable_data();
  double* normal_out = normal.mutable_data();
  double* point_out = point.mutable_data();
  runQueries("mdd_batch", n, warm_start, [&](std::size_t k, WarmStart* warm) {
    const MddResult r = mdd(directionalInput(a, b, p, k, s[k]), warm);
    status_out[k] = static_cast<std::int8_t>(r.status);
    distance_out[k] = r.distance;
    t_lo_out[k] = r.t_lo;
    t_hi_out[k] = r.t_hi;
    store(normal_out, k, r.contact.normal_W);
    store(point_out, k, r.contact.point_W);
  });
  py::dict out;
  out["status"] = status;
  out["distance"] = distance;
  out["t_lo"] = t_lo;
  out["t_hi"] = t_hi;
  out["normal"] = normal;
  out["point"] = point;
  return out;
}

ArrayDict toiBatch(const ConvexPolytope& a, const ArrayLikeOrNoneArg& X_WA, const ConvexPolytope& b,
                   const ArrayLikeOrNoneArg& X_WB, const ArrayLikeArg& directions, const ArrayLikeArg& max_distance,
                   bool exact, bool warm_start) {
  PairBatch p = pairBatch(X_WA, X_WB);
  const VectorBatch s = vectorBatchFrom(directions, "directions");
  p.size.add(s.vectors.size(), s.batched, "directions");
  const ScalarBatch limit = scalarBatchFrom(max_distance, "max_distance");
  p.size.add(limit.values.size(), limit.batched, "max_distance");
  const std::size_t n = p.size.size();
  auto status = codes(n);
  auto toi_values = scalars(n);
  auto toi_exact = py::array_t<bool>(static_cast<py::ssize_t>(n));
  auto normal = vectors(n);
  auto point = vectors(n);
  std::int8_t* status_out = status.mutable_data();
  double* toi_out = toi_values.mutable_data();
  bool* exact_out = toi_exact.mutable_data();
  double* normal_out = normal.mutable_data();
  double* point_out = point.mutable_data();
  runQueries("toi_batch", n, warm_start, [&](std::size_t k, WarmStart* warm) {
    DirectionalInput in = directionalInput(a, b, p, k, s[k]);
    in.max_distance = limit[k];
    in.exact_toi = exact;
    const ToiResult r = toi(in, warm);
    status_out[k] = static_cast<std::int8_t>(r.status);
    toi_out[k] = r.toi;
    exact_out[k] = r.toi_exact;
    store(normal_out, k, r.contact.normal_W);
    store(point_out, k, r.contact.point_W);
  });
  py::dict out;
  out["status"] = status;
  out["toi"] = toi_values;
  out["toi_exact"] = toi_exact;
  out["normal"] = normal;
  out["point"] = point;
  return out;
}

ArrayDict intersectBatch(const ConvexPolytope& a, const ArrayLikeOrNoneArg& X_WA, const ConvexPolytope& b,
                         const ArrayLikeOrNoneArg& X_WB, bool warm_start) {
  const PairBatch p = pairBatch(X_WA, X_WB);
  const std::size_t n = p.size.size();
  auto status = codes(n);
  auto intersecting = py::array_t<bool>(static_cast<py::ssize_t>(n));
  auto separating_normal = vectors(n);
  std::int8_t* status_out = status.mutable_data();
  bool* intersecting_out = intersecting.mutable_data();
  double* normal_out = separating_normal.mutable_data();
  runQueries("intersect_batch", n, warm_start, [&](std::size_t k, WarmStart* warm) {
    IntersectInput in;
    in.a = &a;
    in.X_WA = p.X_WA[k];
    in.b = &b;
    in.X_WB = p.X_WB[k];
    const IntersectResult r = intersect(in, warm);
    status_out[k] = static_cast<std::int8_t>(r.status);
    intersecting_out[k] = r.intersecting;
    store(normal_out, k, r.separating_normal_W);
  });
  py::dict out;
  out["status"] = status;
  out["intersecting"] = intersecting;
  out["separating_normal"] = separating_normal;
  return out;
}

}  // namespace

void bindBatch(py::module_& m) {
  m.attr("CONTACT_STATUSES") =
      py::make_tuple(toString(ContactStatus::kSeparated), toString(ContactStatus::kTouching),
                     toString(ContactStatus::kPenetrating), toString(ContactStatus::kNoContact));
  m.attr("TOI_STATUSES") =
      py::make_tuple(toString(ToiStatus::kHit), toString(ToiStatus::kInContact), toString(ToiStatus::kNever));
  m.attr("INTERSECT_STATUSES") =
      py::make_tuple(toString(IntersectStatus::kSeparated), toString(IntersectStatus::kTouching),
                     toString(IntersectStatus::kPenetrating));

  const double inf = std::numeric_limits<double>::infinity();
  m.def("mdd_batch", &mddBatch, py::arg("a"), py::arg("X_WA"), py::arg("b"), py::arg("X_WB"), py::arg("directions"),
        py::kw_only(), py::arg("warm_start") = true,
        "mdd() for K queries on one pair: X_WA, X_WB are (K, 4, 4) or one pose (None: identity), directions (K, 3) "
        "or (3,). Returns a dict of arrays: status (int8, index into CONTACT_STATUSES), distance, t_lo, t_hi (K,), "
        "normal, point (K, 3). warm_start reuses the previous query's result (frame coherence); the answers are the "
        "same up to round-off. Runs without the GIL.");
  m.def("toi_batch", &toiBatch, py::arg("a"), py::arg("X_WA"), py::arg("b"), py::arg("X_WB"), py::arg("directions"),
        py::kw_only(), py::arg("max_distance") = inf, py::arg("exact") = true, py::arg("warm_start") = true,
        "toi() for K queries on one pair (shapes as in mdd_batch; max_distance a number or (K,)). Returns a dict: "
        "status (int8, index into TOI_STATUSES), toi, toi_exact (K,), normal, point (K, 3). Runs without the GIL.");
  m.def("intersect_batch", &intersectBatch, py::arg("a"), py::arg("X_WA"), py::arg("b"), py::arg("X_WB"), py::kw_only(),
        py::arg("warm_start") = true,
        "intersect() for K poses of one pair. Returns a dict: status (int8, index into INTERSECT_STATUSES), "
        "intersecting (bool, K), separating_normal (K, 3). Runs without the GIL.");
}

}  // namespace mddual::python
