// Where configs/arm7 and configs/panda are, and their problem sets, for the
// tests of those sets.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace mddual::planning::testing {

inline const std::filesystem::path kArm7Dir = std::filesystem::path(MDDUAL_CONFIGS_DIR) / "arm7";
inline const std::filesystem::path kPandaDir = std::filesystem::path(MDDUAL_CONFIGS_DIR) / "panda";

/// Both robots' sets (scripts/arm_problems.py).
inline const std::vector<std::string> kArmSets = {"bookshelf_thin",   "cage",      "box", "table_pick",
                                                  "table_under_pick", "table_bars"};
/// The Panda's sets in MotionBenchMaker's own scenes (scripts/mbm_panda.py).
inline const std::vector<std::string> kPandaMbmSets = {"mbm_bookshelf_thin", "mbm_box", "mbm_table_pick",
                                                       "mbm_table_under_pick"};

}  // namespace mddual::planning::testing
