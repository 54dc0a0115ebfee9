// Point sets for tests, benchmarks and the CLI demo: the six polytopes of the
// MDD-DUAL paper's benchmark (docs/algorithms.md section 5) and the families the
// randomized tests sweep. Everything random takes an explicit generator, so
// callers decide the seed.
#pragma once

#include <Eigen/Geometry>
#include <random>
#include <string>
#include <vector>

namespace mddual::generators {

using Rng = std::mt19937_64;
using Points = std::vector<Eigen::Vector3d>;

// ---- The paper's six polytopes (all inside a sphere of radius 5) -------------

/// P1: truncated elliptic cone, base semi-axes a:b and height h in 1:2:4, the
/// top ellipse half the size of the base; 2 * (vertices / 2) vertices.
Points truncatedEllipticCone(int vertices = 20);
/// P2: truncated elliptic cylinder (base semi-axes : height = 1:2:4).
Points truncatedEllipticCylinder(int vertices = 50);
/// P3, P4: ellipsoid with semi-axes 2:2:5 scaled into radius 5, `vertices`
/// points spread by a Fibonacci lattice (all of them hull vertices).
Points ellipsoid(int vertices);
/// P5: `vertices` random points on a rounded cube (superellipsoid with
/// exponent 6 and half-width 2.8), all of them hull vertices.
Points roundedCubeRandom(int vertices, Rng& rng);
/// P6: solid of revolution of the convex profile r(z) = 2.5 * sqrt(1 - (z/4.5)^2)
/// * (1 - 0.15 z / 4.5): nine rings of (vertices - 2) / 9 points and the two
/// poles (200 vertices for the default).
Points solidOfRevolution(int vertices = 200);

/// The paper's polytopes by name "P1".."P6" (P5 uses a fixed seed).
Points paperPolytope(const std::string& name);

// ---- Test families -----------------------------------------------------------

/// n random points on an ellipsoid with the given semi-axes (a round blob).
Points blob(int n, const Eigen::Vector3d& semi_axes, Rng& rng);
/// Axis-aligned box with the given half extents, centred at the origin.
Points box(const Eigen::Vector3d& half_extents);
/// Right prism over a regular k-gon of circumradius r, height h, axis z.
Points prism(int k, double r, double h);
/// A triangle (flat polygon).
Points triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r);

/// Uniformly random rotation.
Eigen::Matrix3d randomRotation(Rng& rng);
/// Uniformly random unit vector.
Eigen::Vector3d randomUnitVector(Rng& rng);

/// Three draws `dist(gen)` as a vector, drawn z first, then y, then x: the
/// order GCC evaluates the arguments of `Eigen::Vector3d(dist(gen), dist(gen),
/// dist(gen))` (C++ leaves it unspecified; Clang goes left to right), kept so
/// seeded samples stay what GCC made them and are the same under any compiler.
/// `dist` is any callable taking the generator (a distribution or a lambda).
template <class Distribution, class Generator>
Eigen::Vector3d drawVector(Distribution&& dist, Generator& gen) {
  const double z = static_cast<double>(dist(gen));
  const double y = static_cast<double>(dist(gen));
  const double x = static_cast<double>(dist(gen));
  return Eigen::Vector3d(x, y, z);
}

}  // namespace mddual::generators
