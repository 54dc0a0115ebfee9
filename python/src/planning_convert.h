// Helpers of the planning layer's bindings (scene.cpp, robot.cpp, arms.cpp):
// pieces as Python lists, joint configurations from NumPy arrays and the
// worker loop of the arm batches.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <string>
#include <thread>
#include <vector>

#include "convert.h"
#include "mddual/error.h"
#include "mddual/scene/robot_model.h"
#include "mddual/scene/scene.h"

namespace mddual::python {

/// The pieces' polytopes (copies), in the pieces' frame.
inline std::vector<ConvexPolytope> polytopes(const std::vector<scene::Piece>& pieces) {
  std::vector<ConvexPolytope> out;
  out.reserve(pieces.size());
  for (const scene::Piece& p : pieces) out.push_back(p.polytope);
  return out;
}

/// The pieces' origins ("scene0001.yaml: object 'Can1', primitive 0").
inline std::vector<std::string> origins(const std::vector<scene::Piece>& pieces) {
  std::vector<std::string> out;
  for (const scene::Piece& p : pieces) out.push_back(p.origin);
  return out;
}

/// Joint configurations of `model` for a batch: (n,) or (K, n), n =
/// model.numVariables(). ValueError for another shape; InvalidInputError
/// naming the row and the variable for a value that is not finite.
inline StateBatch configBatchFrom(const py::handle& obj, const char* name, const scene::RobotModel& model) {
  const int n = model.numVariables();
  StateBatch batch = stateBatchFrom(obj, name, n, "configuration");
  for (std::size_t k = 0; k < batch.count; ++k) {
    const double* q = batch.row(k, n);
    for (int v = 0; v < n; ++v) {
      if (!std::isfinite(q[v])) {
        throw InvalidInputError(itemName(name, k, batch.batched) + ": variable '" + model.variableName(v) + "' (" +
                                std::to_string(v) + ") is not finite");
      }
    }
  }
  return batch;
}

/// The number of worker threads for `threads` (0: one per hardware thread)
/// and `count` items; ValueError for a negative count.
inline unsigned workerCount(int threads, std::size_t count) {
  if (threads < 0)
    throw py::value_error("threads: expected 0 (all cores) or a positive count, got " + std::to_string(threads));
  const unsigned wanted =
      threads == 0 ? std::max(1U, std::thread::hardware_concurrency()) : static_cast<unsigned>(threads);
  return static_cast<unsigned>(std::min<std::size_t>(wanted, std::max<std::size_t>(count, 1)));
}

/// Runs f(k) for k in [0, count) on `workers` threads (the caller's thread
/// alone for one), items handed out one at a time. The first exception a
/// worker throws stops the others after their current item and is rethrown.
template <class F>
void parallelFor(std::size_t count, unsigned workers, const F& f) {
  if (workers <= 1) {
    for (std::size_t k = 0; k < count; ++k) f(k);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::vector<std::exception_ptr> errors(workers);
  std::vector<std::thread> pool;
  pool.reserve(workers);
  for (unsigned w = 0; w < workers; ++w) {
    pool.emplace_back([&, w] {
      try {
        for (std::size_t k = next++; k < count; k = next++) f(k);
      } catch (...) {
        errors[w] = std::current_exception();
        next = count;
      }
    });
  }
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace mddual::python
