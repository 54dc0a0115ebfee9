// The arm scenes of the OMPL layer's tests: configs/arm7 in a world of a
// table, a 2 mm wall, a bar and a post; seeded configurations; the dense
// reference of an edge (evenly spaced states, each checked exactly).
#pragma once

#include <cmath>
#include <filesystem>
#include <memory>
#include <vector>

#include "mddual/constants.h"
#include "mddual/planning/arm_scene.h"
#include "mddual/planning/dense_contact.h"
#include "mddual/scene/loaders.h"
#include "test_support.h"

namespace mddual::planning::testing {

inline const std::filesystem::path kArm7Dir = std::filesystem::path(MDDUAL_CONFIGS_DIR) / "arm7";

/// A table top, a thin wall (2 mm, far thinner than a motion-check step at
/// OMPL's default resolution for this arm), a bar across the workspace and
/// a post.
inline std::shared_ptr<const scene::World> armWorld() {
  auto at = [](double x, double y, double z) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = Eigen::Vector3d(x, y, z);
    return X;
  };
  std::vector<scene::Piece> pieces;
  pieces.push_back(scene::boxPiece(Eigen::Vector3d(0.5, 0.8, 0.03), at(0.65, 0.0, 0.35), "table"));
  pieces.push_back(scene::boxPiece(Eigen::Vector3d(0.6, 0.002, 0.6), at(0.2, 0.45, 0.5), "thin wall"));
  Eigen::Isometry3d bar = at(-0.3, 0.0, 0.9);
  bar.rotate(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()));
  pieces.push_back(
      scene::cylinderPiece(0.02, 1.2, bar * Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitX()), 1e-3, "bar"));
  pieces.push_back(scene::boxPiece(Eigen::Vector3d(0.05, 0.05, 1.0), at(-0.35, -0.4, 0.5), "post"));
  return std::make_shared<const scene::World>(std::move(pieces), "arm world");
}

struct ArmFixture {
  std::shared_ptr<const scene::RobotModel> model;
  std::shared_ptr<ArmScene> scene;
};

inline ArmFixture makeArm() {
  ArmFixture f;
  f.model = std::make_shared<const scene::RobotModel>(scene::loadRobotModel(kArm7Dir / "arm7.urdf"));
  const scene::Srdf srdf = scene::loadSrdf(kArm7Dir / "arm7.srdf");
  f.scene = std::make_shared<ArmScene>(f.model, armWorld(), scene::AllowedCollisions(*f.model, srdf));
  return f;
}

inline std::vector<double> randomConfiguration(const scene::RobotModel& model, Rng& rng) {
  std::vector<double> q(static_cast<std::size_t>(model.numVariables()));
  for (int v = 0; v < model.numVariables(); ++v) {
    const scene::Joint& j = model.joint(model.variableJoint(v));
    q[static_cast<std::size_t>(v)] = std::uniform_real_distribution<double>(j.lower, j.upper)(rng);
  }
  return q;
}

/// The dense reference: the first of `steps` + 1 evenly spaced states that
/// collides (its fraction), or +infinity (planning/dense_contact.h).
using planning::denseFirstContact;

}  // namespace mddual::planning::testing
