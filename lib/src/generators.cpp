#include "mddual/generators.h"

#include <cmath>
#include <stdexcept>

#include "constants.h"
#include "mddual/error.h"

namespace mddual::generators {
namespace {

/// Ring of k points on the ellipse (a cos t, b sin t) at height z.
void ellipseRing(int k, double a, double b, double z, double phase, Points* out) {
  for (int i = 0; i < k; ++i) {
    const double t = 2.0 * kPi * (i + phase) / k;
    out->emplace_back(a * std::cos(t), b * std::sin(t), z);
  }
}

double uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

}  // namespace

Points truncatedEllipticCone(int vertices) {
  // Base semi-axes a = 1.1, b = 2.2, height 4.4 (1:2:4), top half the size:
  // inside radius 5 once centred at mid-height.
  const int k = vertices / 2;
  Points p;
  ellipseRing(k, 1.1, 2.2, -2.2, 0.0, &p);
  ellipseRing(k, 0.55, 1.1, 2.2, 0.0, &p);
  return p;
}

Points truncatedEllipticCylinder(int vertices) {
  const int k = vertices / 2;
  Points p;
  ellipseRing(k, 1.1, 2.2, -2.2, 0.0, &p);
  ellipseRing(k, 1.1, 2.2, 2.2, 0.0, &p);
  return p;
}

Points ellipsoid(int vertices) {
  // Semi-axes 2:2:5 scaled so that the longest is 5.
  const Eigen::Vector3d axes(2.0, 2.0, 5.0);
  Points p;
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < vertices; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / vertices;
    const double r = std::sqrt(1.0 - z * z);
    const double t = golden * i;
    p.emplace_back(axes.x() * r * std::cos(t), axes.y() * r * std::sin(t), axes.z() * z);
  }
  return p;
}

Points roundedCubeRandom(int vertices, Rng& rng) {
  // Random directions pushed onto |x|^6 + |y|^6 + |z|^6 = s^6: strictly
  // convex, so every point is a vertex, and cube-like.
  constexpr double kHalfWidth = 2.8;
  Points p;
  for (int i = 0; i < vertices; ++i) {
    const Eigen::Vector3d d = randomUnitVector(rng);
    const double norm6 =
        std::pow(std::pow(std::abs(d.x()), 6) + std::pow(std::abs(d.y()), 6) + std::pow(std::abs(d.z()), 6), 1.0 / 6.0);
    p.push_back(kHalfWidth * d / norm6);
  }
  return p;
}

Points solidOfRevolution(int vertices) {
  // Profile r(z) concave in z (a convex solid), slightly egg-shaped.
  const int rings = 9;
  const int per_ring = (vertices - 2) / rings;
  Points p;
  for (int j = 0; j < rings; ++j) {
    const double z = -4.5 + 9.0 * (j + 0.5) / rings;
    const double r = 2.5 * std::sqrt(1.0 - (z / 4.5) * (z / 4.5)) * (1.0 - 0.15 * z / 4.5);
    ellipseRing(per_ring, r, r, z, 0.5 * (j % 2), &p);
  }
  p.emplace_back(0.0, 0.0, -4.5);
  p.emplace_back(0.0, 0.0, 4.5);
  return p;
}

Points paperPolytope(const std::string& name) {
  if (name == "P1") return truncatedEllipticCone(20);
  if (name == "P2") return truncatedEllipticCylinder(50);
  if (name == "P3") return ellipsoid(200);
  if (name == "P4") return ellipsoid(500);
  if (name == "P5") {
    Rng rng(5);
    return roundedCubeRandom(100, rng);
  }
  if (name == "P6") return solidOfRevolution(200);
  throw InvalidInputError("paperPolytope: unknown name '" + name + "' (use P1..P6)");
}

Points blob(int n, const Eigen::Vector3d& semi_axes, Rng& rng) {
  Points p;
  for (int i = 0; i < n; ++i) p.push_back(semi_axes.cwiseProduct(randomUnitVector(rng)));
  return p;
}

Points box(const Eigen::Vector3d& h) {
  Points p;
  for (int i = 0; i < 8; ++i) {
    p.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
  }
  return p;
}

Points prism(int k, double r, double h) {
  Points p;
  ellipseRing(k, r, r, -0.5 * h, 0.0, &p);
  ellipseRing(k, r, r, 0.5 * h, 0.0, &p);
  return p;
}

Points triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r) {
  return {p, q, r};
}

Eigen::Matrix3d randomRotation(Rng& rng) {
  // Uniform unit quaternion (Shoemake).
  const double u1 = uniform(rng, 0.0, 1.0);
  const double u2 = uniform(rng, 0.0, 2.0 * kPi);
  const double u3 = uniform(rng, 0.0, 2.0 * kPi);
  const double a = std::sqrt(1.0 - u1);
  const double b = std::sqrt(u1);
  const Eigen::Quaterniond q(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3));
  return q.normalized().toRotationMatrix();
}

Eigen::Vector3d randomUnitVector(Rng& rng) {
  for (;;) {
    const Eigen::Vector3d v = drawVector(std::uniform_real_distribution<double>(-1.0, 1.0), rng);
    const double n = v.norm();
    if (n > 1e-3 && n <= 1.0) return v / n;
  }
}

}  // namespace mddual::generators
