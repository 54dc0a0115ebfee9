// The clock of the planning-layer benchmarks: wall-clock time, or the calling
// thread's CPU time (steadier on a shared, loaded machine).
#pragma once

#include <chrono>
#include <ctime>

namespace mddual::bench {

/// Seconds since an arbitrary origin: the thread's CPU clock when `cpu`, else
/// the steady wall clock. Only differences of two readings of the same kind
/// are meaningful.
inline double nowSeconds(bool cpu) {
  if (cpu) {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace mddual::bench
