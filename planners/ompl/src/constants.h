// Constants shared by the planning layer's sources (not part of the installed
// API). One definition here rather than one per file: the library is built
// as one translation unit per batch of files (UNITY_BUILD), where two files'
// definitions would clash.
#pragma once

#include <limits>

#include "mddual/constants.h"  // kPi

namespace mddual::planning::detail {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace mddual::planning::detail
