// Mathematical constants, one definition for the library, the planning layer,
// the tools and the tests (std::numbers is C++20; M_PI is POSIX, not C++).
#pragma once

namespace mddual {

/// pi to double precision.
inline constexpr double kPi = 3.14159265358979323846;

}  // namespace mddual
