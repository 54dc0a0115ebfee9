// Primitive builders: boxes exact, cylinders and spheres circumscribed within
// the tolerance (true surface inside, vertices within tolerance of it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "mddual/constants.h"
#include "mddual/generators.h"
#include "mddual/scene/loaders.h"
#include "scene_test_util.h"

namespace mddual::scene {
namespace {

using testing::expectSceneError;

/// Largest signed distance of p outside the polytope's face planes (<= 0 inside).
double outside(const ConvexPolytope& P, const Eigen::Vector3d& p) {
  double worst = -std::numeric_limits<double>::infinity();
  for (int f = 0; f < P.numFaces(); ++f) worst = std::max(worst, P.faceNormal(f).dot(p) - P.faceOffset(f));
  return worst;
}

Eigen::Isometry3d somePose() {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  X.translation() = Eigen::Vector3d(3.0, -2.0, 5.0);
  return X;
}

TEST(Primitives, BoxIsExact) {
  const Eigen::Isometry3d X = somePose();
  const Piece p = boxPiece(Eigen::Vector3d(1, 2, 4), X, "box");
  EXPECT_EQ(p.polytope.numVertices(), 8);
  EXPECT_EQ(p.polytope.numFaces(), 6);
  EXPECT_EQ(p.kind, PieceKind::kConvex);
  EXPECT_EQ(p.origin, "box");
  for (const Eigen::Vector3d& v : p.polytope.vertices()) {
    const Eigen::Vector3d local = X.inverse() * v;
    EXPECT_NEAR(std::abs(local.x()), 0.5, 1e-12);
    EXPECT_NEAR(std::abs(local.y()), 1.0, 1e-12);
    EXPECT_NEAR(std::abs(local.z()), 2.0, 1e-12);
  }
}

TEST(Primitives, CylinderContainsTheTrueSurfaceWithinTolerance) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Eigen::Isometry3d X = somePose();
  for (const double r : {0.05, 1.0, 30.0}) {
    for (const double tol : {1e-2, 1e-3}) {
      const double length = 2.5;
      const Piece p = cylinderPiece(r, length, X, tol, "cyl");
      const int k = cylinderSides(r, tol);
      EXPECT_EQ(p.polytope.numVertices(), 2 * k);
      EXPECT_LE(r / std::cos(kPi / k) - r, tol);
      if (k > 8) {
        EXPECT_GT(r / std::cos(kPi / (k - 1)) - r, tol) << "k is not the smallest";
      }
      // Points on the true surface (side and caps) are inside.
      for (int i = 0; i < 500; ++i) {
        const double a = 2.0 * kPi * u(rng);
        const double z = (u(rng) - 0.5) * length;
        const double rho = r * std::sqrt(u(rng));
        const Eigen::Vector3d side(r * std::cos(a), r * std::sin(a), z);
        const Eigen::Vector3d cap(rho * std::cos(a), rho * std::sin(a), (i % 2 ? 0.5 : -0.5) * length);
        EXPECT_LE(outside(p.polytope, X * side), 1e-12 * (1.0 + r));
        EXPECT_LE(outside(p.polytope, X * cap), 1e-12 * (1.0 + r));
      }
      // Vertices are within the tolerance of the surface.
      for (const Eigen::Vector3d& v : p.polytope.vertices()) {
        const Eigen::Vector3d local = X.inverse() * v;
        const double radial = std::hypot(local.x(), local.y());
        EXPECT_GE(radial, r - 1e-12);
        EXPECT_LE(radial, r + tol + 1e-12);
        EXPECT_NEAR(std::abs(local.z()), 0.5 * length, 1e-12);
      }
    }
  }
}

TEST(Primitives, SphereContainsTheTrueSurfaceWithinTolerance) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  const Eigen::Isometry3d X = somePose();
  for (const double r : {0.1, 2.0}) {
    for (const double tol : {2e-2, 2e-3}) {
      const Piece p = spherePiece(r, X, tol, "sphere");
      for (int i = 0; i < 2000; ++i) {
        const Eigen::Vector3d dir = generators::drawVector(g, rng).normalized();
        EXPECT_LE(outside(p.polytope, X * (r * dir)), 1e-11 * r) << "surface point outside, r " << r;
      }
      for (const Eigen::Vector3d& v : p.polytope.vertices()) {
        const double d = (v - X.translation()).norm();
        EXPECT_GE(d, r - 1e-12);
        EXPECT_LE(d, r + tol + 1e-12);
      }
      // Every face plane is at distance >= r from the centre.
      for (int f = 0; f < p.polytope.numFaces(); ++f) {
        EXPECT_GE(p.polytope.faceOffset(f) - p.polytope.faceNormal(f).dot(X.translation()), r * (1 - 1e-12));
      }
    }
  }
}

TEST(Primitives, TighterToleranceGivesMoreVertices) {
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  int last_cyl = 0;
  int last_sphere = 0;
  for (const double tol : {1e-1, 1e-2, 1e-3}) {
    const int cyl = cylinderPiece(1.0, 1.0, I, tol, "c").polytope.numVertices();
    const int sphere = spherePiece(1.0, I, tol, "s").polytope.numVertices();
    EXPECT_GT(cyl, last_cyl) << "tol " << tol;
    EXPECT_GT(sphere, last_sphere) << "tol " << tol;
    last_cyl = cyl;
    last_sphere = sphere;
  }
  // A coarse sphere is the icosahedron scaled out (12 vertices).
  EXPECT_EQ(spherePiece(1.0, I, 1.0, "s").polytope.numVertices(), 12);
}

TEST(Primitives, BadSizesAreErrors) {
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  expectSceneError([&] { boxPiece(Eigen::Vector3d(1, 0, 1), I, "wall"); }, {"wall", "box sizes"});
  expectSceneError([&] { boxPiece(Eigen::Vector3d(1, -1, 1), I, "wall"); }, {"wall", "box sizes"});
  expectSceneError([&] { cylinderPiece(0.0, 1.0, I, 1e-3, "pole"); }, {"pole", "radius"});
  expectSceneError([&] { cylinderPiece(1.0, -2.0, I, 1e-3, "pole"); }, {"pole", "length"});
  expectSceneError([&] { spherePiece(std::nan(""), I, 1e-3, "ball"); }, {"ball", "radius"});
  expectSceneError([&] { spherePiece(1.0, I, 0.0, "ball"); }, {"ball", "tolerance"});
  expectSceneError([&] { spherePiece(1.0, I, 1e-9, "ball"); }, {"ball", "larger primitive tolerance"});
  expectSceneError([&] { cylinderPiece(1.0, 1.0, I, 1e-12, "pole"); }, {"pole", "larger primitive tolerance"});
}

}  // namespace
}  // namespace mddual::scene
