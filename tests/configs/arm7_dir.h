// Where configs/arm7 and configs/panda are, for the tests of their problem
// sets.
#pragma once

#include <filesystem>

namespace mddual::planning::testing {

inline const std::filesystem::path kArm7Dir = std::filesystem::path(MDDUAL_CONFIGS_DIR) / "arm7";
inline const std::filesystem::path kPandaDir = std::filesystem::path(MDDUAL_CONFIGS_DIR) / "panda";

}  // namespace mddual::planning::testing
