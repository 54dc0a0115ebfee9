// Helpers for the scene tests: a temporary folder per test, file writing, and
// assertions on SceneError messages.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mddual/scene/scene.h"

namespace mddual::scene::testing {

/// A fresh folder named after the running test, removed at the end.
class TempDir {
 public:
  TempDir() {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::string name = info != nullptr ? std::string(info->test_suite_name()) + "_" + info->name() : "scene";
    path_ = std::filesystem::temp_directory_path() /
            ("mddual_scene_" + name + "_" + std::to_string(static_cast<long>(::getpid())));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  /// Writes `text` to path()/name (creating folders) and returns the path.
  std::filesystem::path write(const std::string& name, const std::string& text) const {
    const std::filesystem::path p = path_ / name;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream out(p, std::ios::binary);
    out << text;
    return p;
  }

 private:
  std::filesystem::path path_;
};

/// Runs `f` and checks that it throws SceneError whose message contains
/// every one of `parts`.
inline void expectSceneError(const std::function<void()>& f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "no SceneError thrown (expected one mentioning '" << (parts.empty() ? "" : parts.front()) << "')";
  } catch (const SceneError& e) {
    const std::string message = e.what();
    for (const std::string& part : parts) {
      EXPECT_NE(message.find(part), std::string::npos) << "message '" << message << "' lacks '" << part << "'";
    }
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
  }
}

/// An ASCII STL of the triangles (three corners each).
inline std::string asciiStl(const std::vector<Eigen::Vector3d>& corners) {
  std::string s = "solid test\n";
  for (std::size_t t = 0; t + 2 < corners.size(); t += 3) {
    const Eigen::Vector3d n = (corners[t + 1] - corners[t]).cross(corners[t + 2] - corners[t]).normalized();
    s += "facet normal " + std::to_string(n.x()) + " " + std::to_string(n.y()) + " " + std::to_string(n.z()) +
         "\n outer loop\n";
    for (std::size_t c = 0; c < 3; ++c) {
      const Eigen::Vector3d& v = corners[t + c];
      s += "  vertex " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " " + std::to_string(v.z()) + "\n";
    }
    s += " endloop\nendfacet\n";
  }
  return s + "endsolid test\n";
}

/// The 12 triangles of the axis-aligned box [lo, hi], outward winding.
inline std::vector<Eigen::Vector3d> boxTriangles(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const auto corner = [&](int i) {
    return Eigen::Vector3d((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
  };
  // Each face as a quad of corner indices, counter-clockwise seen from outside.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<Eigen::Vector3d> out;
  for (const auto& q : quads) {
    out.insert(out.end(), {corner(q[0]), corner(q[1]), corner(q[2]), corner(q[0]), corner(q[2]), corner(q[3])});
  }
  return out;
}

}  // namespace mddual::scene::testing
