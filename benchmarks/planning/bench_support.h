// Shared by the planning-layer benchmarks: their clock (wall-clock time, or
// the calling thread's CPU time, steadier on a shared, loaded machine), their
// time format, and MDD's one-time set-up done before timing.
#pragma once

#include <chrono>
#include <cstdio>
#include <ctime>
#include <string>

#include "mddual/planning/mdd_scene.h"

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

/// Seconds as microseconds, 3 significant digits or so ("9.34", "27.1", "807").
inline std::string micros(double seconds) {
  char buf[32];
  const double v = seconds * 1e6;
  std::snprintf(buf, sizeof buf, v < 10 ? "%.2f" : (v < 100 ? "%.1f" : "%.0f"), v);
  return buf;
}

/// Builds all of the scene's enlarged robot pieces (every level), which a
/// planning run builds on first use, so that no timed pass pays for them.
inline void buildEnlargedPieces(const mddual::planning::MddScene& scene) {
  const int pieces = static_cast<int>(scene.robot().pieces().size());
  for (int level = 0; level <= scene.refinementLevels(); ++level) {
    for (int i = 0; i < pieces; ++i) scene.enlargedPiece(level, i);
  }
}

}  // namespace mddual::bench
