// How the benchmark runners write run properties in OMPL's logs (shared by
// bench_runner.cpp and arm_bench.cpp, which are built in one unity batch).
#pragma once

#include <cstdio>
#include <string>

namespace mddual::planning::detail {

/// A BOOLEAN property.
inline std::string flag(bool b) {
  return b ? "1" : "0";
}

/// A REAL property, 9 significant digits.
inline std::string real(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  return buf;
}

}  // namespace mddual::planning::detail
