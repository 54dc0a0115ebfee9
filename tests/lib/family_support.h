// Small helpers shared by the randomized test families (seeded draws, poses,
// and the MDDUAL_SWEEP_* environment knobs of the long sweeps).
#pragma once

#include <Eigen/Geometry>
#include <cstdlib>
#include <random>

#include "mddual/generators.h"

namespace mddual::testing {

inline double uniform(generators::Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}
inline int uniformInt(generators::Rng& rng, int lo, int hi) {
  return std::uniform_int_distribution<int>(lo, hi)(rng);
}

inline Eigen::Isometry3d pose(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}

/// An integer from the environment (MDDUAL_SWEEP_SCALE, MDDUAL_SWEEP_SEED), or
/// `fallback` when unset.
inline long envLong(const char* name, long fallback) {
  const char* v = std::getenv(name);
  return v != nullptr ? std::strtol(v, nullptr, 10) : fallback;
}

}  // namespace mddual::testing
