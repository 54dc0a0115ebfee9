// A tiny benchmark config for the front end's and `mddual bench`'s tests:
// a 10 m cube, a 2 cm wall across it at x = 5 with one door (y in [6.5,
// 8.5]), a 0.5 m cube robot going from (2, 5, 5) to (8, 5, 5), translation
// only. The wall is far thinner than OMPL's default motion-check resolution
// (0.17 m here), so FCL's discrete checking can step through it. Planners:
// rrtconnect and mdd_rrtconnect; 2 runs of 0.2 s. Header-only (std only).
#pragma once

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace mddual::testing {

/// The [problem] section's extra lines, the [benchmark] and [planner] sections.
struct TinyConfigText {
  std::string problem_extra;
  std::string benchmark = "time_limit = 0.2\nmem_limit = 2000\nrun_count = 2\n";
  std::string planners = "rrtconnect =\nmdd_rrtconnect =\n";
};

inline void writeTextFile(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

/// Writes dir/tiny.cfg, dir/robot.urdf, dir/world.urdf; returns the cfg's path.
inline std::filesystem::path writeTinyConfig(const std::filesystem::path& dir,
                                             const TinyConfigText& text = TinyConfigText()) {
  writeTextFile(dir / "robot.urdf", R"(<?xml version="1.0"?>
<robot name="cube">
  <link name="cube_link">
    <collision><geometry><box size="0.5 0.5 0.5"/></geometry></collision>
  </link>
</robot>
)");
  writeTextFile(dir / "world.urdf", R"(<?xml version="1.0"?>
<robot name="wall">
  <link name="wall_link">
    <collision><origin xyz="5 3.25 5"/><geometry><box size="0.02 6.5 10"/></geometry></collision>
    <collision><origin xyz="5 9.25 5"/><geometry><box size="0.02 1.5 10"/></geometry></collision>
  </link>
</robot>
)");
  const std::filesystem::path cfg = dir / "tiny.cfg";
  writeTextFile(cfg,
                "[problem]\nname = tiny\nrobot = robot.urdf\nworld = world.urdf\n"
                "start.x = 2\nstart.y = 5\nstart.z = 5\nstart.axis.x = 0\nstart.axis.y = 0\nstart.axis.z = 1\n"
                "start.theta = 0\ngoal.x = 8\ngoal.y = 5\ngoal.z = 5\ngoal.axis.x = 0\ngoal.axis.y = 0\n"
                "goal.axis.z = 1\ngoal.theta = 0\nvolume.min.x = 0\nvolume.min.y = 0\nvolume.min.z = 0\n"
                "volume.max.x = 10\nvolume.max.y = 10\nvolume.max.z = 10\ntranslation_only = true\n" +
                    text.problem_extra + "\n[benchmark]\n" + text.benchmark + "\n[planner]\n" + text.planners);
  return cfg;
}

}  // namespace mddual::testing
