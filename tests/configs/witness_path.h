// The witness path scripts/make_configs.py writes beside each mesh config
// (configs/NAME/witness_path.txt), read as poses of the robot frame: used by
// test_mesh_configs.cpp (the path is collision-free) and by
// test_mesh_soundness.cpp (edges are sampled near it).
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "mddual/scene/problem_config.h"

namespace mddual::scene::testing {

/// The states of `file` (one per line, '#' comments; SE(2): x y theta,
/// otherwise x y z axis.x axis.y axis.z theta) as poses X_WR. A line that
/// does not parse fails the test.
inline std::vector<Eigen::Isometry3d> witnessPath(const std::filesystem::path& file, SpaceKind space) {
  std::ifstream in(file);
  EXPECT_TRUE(in.good()) << file;
  std::vector<Eigen::Isometry3d> states;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    PoseSpec pose;
    if (isPlanar(space)) {
      fields >> pose.position.x() >> pose.position.y() >> pose.theta;
    } else {
      fields >> pose.position.x() >> pose.position.y() >> pose.position.z() >> pose.axis.x() >> pose.axis.y() >>
          pose.axis.z() >> pose.theta;
    }
    EXPECT_FALSE(fields.fail()) << file << ": " << line;
    states.push_back(toIsometry(pose, space));
  }
  return states;
}

}  // namespace mddual::scene::testing
