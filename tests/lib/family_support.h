// Small helpers shared by the randomized test families (seeded draws, poses,
// and the MDDUAL_SWEEP_* environment knobs of the long sweeps).
#pragma once

#include <Eigen/Geometry>
#include <cstdlib>
#include <random>

#include "mddual/generators.h"
#include "test_shapes.h"

namespace mddual::testing {

inline double uniform(generators::Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}
/// A vector of coordinates uniform in [lo, hi], drawn x, y, z in that order
/// (generators::drawVector draws z first).
inline Eigen::Vector3d uniformVector(generators::Rng& rng, double lo, double hi) {
  Eigen::Vector3d v;
  for (int k = 0; k < 3; ++k) v[k] = uniform(rng, lo, hi);
  return v;
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

/// A random direction times a length uniform in [0, max_length], the length
/// drawn first: the order GCC evaluated the operands of the
/// `randomUnitVector(rng) * uniform(rng, 0.0, max_length)` this replaces (C++
/// leaves the operands of an overloaded `*` unsequenced; Clang goes left to
/// right), kept so the seeded offsets stay as they were.
inline Eigen::Vector3d randomOffset(generators::Rng& rng, double max_length) {
  const double length = uniform(rng, 0.0, max_length);
  return generators::randomUnitVector(rng) * length;
}

/// A triangle of three random unit vectors times `scale`, the last vertex drawn
/// first: the order GCC evaluated the arguments of the `triangle(
/// randomUnitVector(rng) * scale, ...)` calls this replaces (C++ leaves it
/// unspecified), kept so the seeded triangles stay as they were.
inline generators::Points randomTriangle(generators::Rng& rng, double scale) {
  const Eigen::Vector3d v2 = generators::randomUnitVector(rng) * scale;
  const Eigen::Vector3d v1 = generators::randomUnitVector(rng) * scale;
  const Eigen::Vector3d v0 = generators::randomUnitVector(rng) * scale;
  return generators::triangle(v0, v1, v2);
}

/// A lattice of 1 to 3 unit steps along each axis, drawn z, y, x (the order GCC
/// evaluated the `lattice()` arguments this replaces).
inline generators::Points randomLattice(generators::Rng& rng) {
  const int nz = uniformInt(rng, 1, 3);
  const int ny = uniformInt(rng, 1, 3);
  const int nx = uniformInt(rng, 1, 3);
  return lattice(nx, ny, nz, 1.0);
}

/// Prisms over a regular k-gon (B's: k or 2k sides at random) of circumradius
/// in [0.3, 1.5] and height in [0.3, 2]. Each height is drawn before its
/// radius and B's side count last: the order GCC evaluated the arguments of
/// the `prism()` calls this replaces, kept so the seeded prisms stay.
inline void randomPrisms(generators::Rng& rng, int k, generators::Points* a, generators::Points* b) {
  const double h_a = uniform(rng, 0.3, 2.0);
  const double r_a = uniform(rng, 0.3, 1.5);
  *a = generators::prism(k, r_a, h_a);
  const double h_b = uniform(rng, 0.3, 2.0);
  const double r_b = uniform(rng, 0.3, 1.5);
  *b = generators::prism(uniformInt(rng, 0, 1) ? k : 2 * k, r_b, h_b);
}

/// An integer from the environment (MDDUAL_SWEEP_SCALE, MDDUAL_SWEEP_SEED), or
/// `fallback` when unset.
inline long envLong(const char* name, long fallback) {
  const char* v = std::getenv(name);
  return v != nullptr ? std::strtol(v, nullptr, 10) : fallback;
}

}  // namespace mddual::testing
