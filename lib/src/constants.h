// Constants shared by the core's sources (not part of the installed API).
// One definition here rather than one per file: the library is built as one
// translation unit (UNITY_BUILD), where two files' definitions would clash.
#pragma once

#include <limits>

#include "mddual/constants.h"  // kPi

namespace mddual::detail {

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace mddual::detail
