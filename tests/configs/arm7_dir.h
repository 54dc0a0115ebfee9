// Where configs/arm7 is, for the tests of its problem sets.
#pragma once

#include <filesystem>

namespace mddual::planning::testing {

inline const std::filesystem::path kArm7Dir = std::filesystem::path(MDDUAL_CONFIGS_DIR) / "arm7";

}  // namespace mddual::planning::testing
