#include "mddual/planning/example_scenes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "constants.h"
#include "mddual/error.h"
#include "mddual/generators.h"
#include "mddual/scene/loaders.h"

namespace mddual::planning::examples {
namespace {

using generators::Rng;

double uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

scene::Piece trianglePiece(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                           const std::string& origin) {
  return scene::Piece::make(ConvexPolytope::fromPoints({a, b, c}), scene::PieceKind::kTriangle, origin);
}

/// Two triangles of the rectangle corner + s u + t v, s, t in [0, 1].
void addRectangle(const Eigen::Vector3d& corner, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                  const std::string& origin, std::vector<scene::Piece>* out) {
  out->push_back(trianglePiece(corner, corner + u, corner + u + v, origin));
  out->push_back(trianglePiece(corner, corner + u + v, corner + v, origin));
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Ear clipping of a simple counter-clockwise polygon: index triples.
std::vector<std::array<int, 3>> triangulate(const std::vector<Eigen::Vector2d>& poly) {
  std::vector<int> idx(poly.size());
  for (std::size_t i = 0; i < poly.size(); ++i) idx[i] = static_cast<int>(i);
  std::vector<std::array<int, 3>> out;
  while (idx.size() > 3) {
    bool clipped = false;
    for (std::size_t k = 0; k < idx.size() && !clipped; ++k) {
      const int a = idx[(k + idx.size() - 1) % idx.size()], b = idx[k], c = idx[(k + 1) % idx.size()];
      const Eigen::Vector2d &pa = poly[a], &pb = poly[b], &pc = poly[c];
      if (cross2(pb - pa, pc - pb) <= 0.0) continue;  // reflex
      bool empty = true;
      for (int q : idx) {
        if (q == a || q == b || q == c) continue;
        const Eigen::Vector2d& p = poly[q];
        if (cross2(pb - pa, p - pa) >= 0.0 && cross2(pc - pb, p - pb) >= 0.0 && cross2(pa - pc, p - pc) >= 0.0) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      out.push_back({a, b, c});
      idx.erase(idx.begin() + static_cast<std::ptrdiff_t>(k));
      clipped = true;
    }
    if (!clipped) throw InvalidInputError("prismTriangles: the polygon is not simple and counter-clockwise");
  }
  out.push_back({idx[0], idx[1], idx[2]});
  return out;
}

/// A random convex polygon: hull of random points on a circle of radius r.
std::vector<Eigen::Vector2d> randomConvexPolygon(Rng& rng, double r) {
  const int n = std::uniform_int_distribution<int>(4, 8)(rng);
  std::vector<double> angles;
  for (int i = 0; i < n; ++i) angles.push_back(uniform(rng, 0.0, 2.0 * kPi));
  std::sort(angles.begin(), angles.end());
  std::vector<Eigen::Vector2d> out;
  for (double a : angles) out.emplace_back(r * std::cos(a), r * std::sin(a));
  return out;
}

std::vector<Eigen::Vector3d> extrude(const std::vector<Eigen::Vector2d>& polygon, double z0, double z1) {
  std::vector<Eigen::Vector3d> out;
  for (const Eigen::Vector2d& p : polygon) {
    out.emplace_back(p.x(), p.y(), z0);
    out.emplace_back(p.x(), p.y(), z1);
  }
  return out;
}

std::vector<Eigen::Vector3d> transformed(const std::vector<Eigen::Vector3d>& points, const Eigen::Isometry3d& X) {
  std::vector<Eigen::Vector3d> out;
  for (const Eigen::Vector3d& p : points) out.push_back(X * p);
  return out;
}

Eigen::Isometry3d translation(const Eigen::Vector3d& p) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = p;
  return X;
}

ExampleScene make(std::string name, std::vector<scene::Piece> robot, std::vector<scene::Piece> world,
                  const Eigen::AlignedBox3d& bounds, SpaceKind kind) {
  ExampleScene s;
  s.robot = std::make_shared<scene::RigidBody>(std::move(robot), name + " robot");
  s.world = std::make_shared<scene::World>(std::move(world), name + " world");
  s.name = std::move(name);
  s.bounds = bounds;
  s.kind = kind;
  return s;
}

}  // namespace

scene::Piece convexPiece(const std::vector<Eigen::Vector3d>& points, const std::string& origin) {
  return scene::Piece::make(ConvexPolytope::fromPoints(points), scene::PieceKind::kConvex, origin);
}

std::vector<scene::Piece> boxTriangles(const Eigen::Vector3d& h, const Eigen::Isometry3d& X,
                                       const std::string& origin) {
  std::vector<scene::Piece> out;
  const Eigen::Matrix3d R = X.linear();
  for (int axis = 0; axis < 3; ++axis) {
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    for (double side : {-1.0, 1.0}) {
      const Eigen::Vector3d n = side * h[axis] * R.col(axis);
      const Eigen::Vector3d u = 2.0 * h[a] * R.col(a), v = 2.0 * h[b] * R.col(b);
      addRectangle(X.translation() + n - 0.5 * u - 0.5 * v, u, v, origin, &out);
    }
  }
  return out;
}

std::vector<scene::Piece> prismTriangles(const std::vector<Eigen::Vector2d>& polygon, double z0, double z1,
                                         const std::string& origin) {
  std::vector<scene::Piece> out;
  const auto at = [&](int i, double z) { return Eigen::Vector3d(polygon[i].x(), polygon[i].y(), z); };
  for (const auto& t : triangulate(polygon)) {
    out.push_back(trianglePiece(at(t[0], z0), at(t[2], z0), at(t[1], z0), origin + " bottom"));
    out.push_back(trianglePiece(at(t[0], z1), at(t[1], z1), at(t[2], z1), origin + " top"));
  }
  const int n = static_cast<int>(polygon.size());
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d a = at(i, z0), b = at((i + 1) % n, z0);
    addRectangle(a, b - a, Eigen::Vector3d(0, 0, z1 - z0), origin + " side", &out);
  }
  return out;
}

ExampleScene primitivesScene(std::uint64_t seed, int obstacles) {
  Rng rng(seed);
  std::vector<scene::Piece> world;
  world.push_back(
      convexPiece(transformed(generators::box({20.0, 20.0, 0.5}), translation({0, 0, -0.5})), "floor (box)"));
  const double circumscribe = 1.0 / std::cos(kPi / 16.0);  // 16-gon around the circle
  for (int i = 0; i < obstacles; ++i) {
    // Coordinates drawn last first: the order GCC gave the constructors'
    // arguments (C++ leaves it unspecified), kept so the seeded scenes stay.
    const double at_y = uniform(rng, -18, 18);
    const double at_x = uniform(rng, -18, 18);
    const Eigen::Vector3d at(at_x, at_y, 0.0);
    if (i % 2 == 0) {
      const double h_z = uniform(rng, 0.3, 3.0);
      const double h_y = uniform(rng, 0.3, 2.0);
      const double h_x = uniform(rng, 0.3, 2.0);
      const Eigen::Vector3d h(h_x, h_y, h_z);
      Eigen::Isometry3d X = translation(at + Eigen::Vector3d(0, 0, uniform(rng, 0.0, 5.0)));
      X.linear() = generators::randomRotation(rng);
      world.push_back(convexPiece(transformed(generators::box(h), X), "box " + std::to_string(i)));
    } else {
      const double r = uniform(rng, 0.2, 1.0), height = uniform(rng, 1.0, 8.0);
      const Eigen::Isometry3d X = translation(at + Eigen::Vector3d(0, 0, 0.5 * height));
      world.push_back(convexPiece(transformed(generators::prism(16, r * circumscribe, height), X),
                                  "cylinder " + std::to_string(i)));
    }
  }
  std::vector<scene::Piece> robot;
  robot.push_back(convexPiece(generators::box({0.5, 0.3, 0.2}), "base (box)"));
  robot.push_back(convexPiece(transformed(generators::prism(16, 0.2 * circumscribe, 0.6), translation({0.2, 0, 0.5})),
                              "mast (cylinder)"));
  return make("primitives", std::move(robot), std::move(world),
              Eigen::AlignedBox3d(Eigen::Vector3d(-20, -20, 0.1), Eigen::Vector3d(20, 20, 8)), SpaceKind::kR3);
}

ExampleScene meshScene(std::uint64_t seed, int obstacles) {
  Rng rng(seed);
  std::vector<scene::Piece> world;
  const double L = 10.0, H = 6.0;
  addRectangle({-L, -L, 0}, {2 * L, 0, 0}, {0, 2 * L, 0}, "floor", &world);
  addRectangle({-L, -L, H}, {2 * L, 0, 0}, {0, 2 * L, 0}, "ceiling", &world);
  addRectangle({-L, -L, 0}, {2 * L, 0, 0}, {0, 0, H}, "wall -y", &world);
  addRectangle({-L, L, 0}, {2 * L, 0, 0}, {0, 0, H}, "wall +y", &world);
  addRectangle({-L, -L, 0}, {0, 2 * L, 0}, {0, 0, H}, "wall -x", &world);
  addRectangle({L, -L, 0}, {0, 2 * L, 0}, {0, 0, H}, "wall +x", &world);
  for (double x : {-3.0, 4.0}) {  // partition walls, door 2.4 wide and 3 high at y = d
    const double d = uniform(rng, -6.0, 6.0);
    addRectangle({x, -L, 0}, {0, d - 1.2 + L, 0}, {0, 0, H}, "partition", &world);
    addRectangle({x, d + 1.2, 0}, {0, L - d - 1.2, 0}, {0, 0, H}, "partition", &world);
    addRectangle({x, d - 1.2, 3.0}, {0, 2.4, 0}, {0, 0, H - 3.0}, "partition lintel", &world);
  }
  for (int i = 0; i < obstacles; ++i) {
    const Eigen::Vector3d h = generators::drawVector(std::uniform_real_distribution<double>(0.3, 1.5), rng);
    Eigen::Isometry3d X = translation({uniform(rng, -9, 9), uniform(rng, -9, 9), uniform(rng, 0.5, 5.5)});
    X.linear() = generators::randomRotation(rng);
    for (scene::Piece& p : boxTriangles(h, X, "mesh box " + std::to_string(i))) world.push_back(std::move(p));
  }
  // An L of arms 2 and width 0.6, centred near its vertex mean, 0.6 thick.
  std::vector<Eigen::Vector2d> ell = {{0, 0}, {2, 0}, {2, 0.6}, {0.6, 0.6}, {0.6, 2}, {0, 2}};
  for (Eigen::Vector2d& p : ell) p -= Eigen::Vector2d(0.8, 0.8);
  return make("mesh", prismTriangles(ell, -0.3, 0.3, "L robot"), std::move(world),
              Eigen::AlignedBox3d(Eigen::Vector3d(-9.5, -9.5, 0.5), Eigen::Vector3d(9.5, 9.5, 5.5)), SpaceKind::kSE3);
}

ExampleScene planarScene(std::uint64_t seed, int obstacles) {
  Rng rng(seed);
  std::vector<scene::Piece> world;
  for (int i = 0; i < obstacles; ++i) {
    std::vector<Eigen::Vector2d> poly = randomConvexPolygon(rng, uniform(rng, 0.5, 2.5));
    // y drawn first: the order GCC gave the constructor's arguments (C++ leaves
    // it unspecified), kept so the seeded scene stays as it was.
    const double at_y = uniform(rng, -19, 19);
    const double at_x = uniform(rng, -19, 19);
    const Eigen::Vector2d at(at_x, at_y);
    for (Eigen::Vector2d& p : poly) p += at;
    world.push_back(convexPiece(extrude(poly, -0.5, 0.5), "polygon " + std::to_string(i)));
  }
  std::vector<scene::Piece> robot;
  robot.push_back(convexPiece(generators::box({1.0, 0.15, 0.25}), "T bar"));
  robot.push_back(convexPiece(transformed(generators::box({0.15, 0.5, 0.25}), translation({0, -0.6, 0})), "T stem"));
  return make("planar", std::move(robot), std::move(world),
              Eigen::AlignedBox3d(Eigen::Vector3d(-20, -20, -1), Eigen::Vector3d(20, 20, 1)), SpaceKind::kSE2);
}

ExampleScene blobScene(std::uint64_t seed, int obstacles) {
  Rng rng(seed);
  std::vector<scene::Piece> world;
  for (int i = 0; i < obstacles; ++i) {
    const Eigen::Vector3d axes = generators::drawVector(std::uniform_real_distribution<double>(0.5, 2.5), rng);
    const int n = std::uniform_int_distribution<int>(20, 40)(rng);
    Eigen::Isometry3d X = translation({uniform(rng, -14, 14), uniform(rng, -14, 14), uniform(rng, -14, 14)});
    X.linear() = generators::randomRotation(rng);
    world.push_back(convexPiece(transformed(generators::blob(n, axes, rng), X), "blob " + std::to_string(i)));
  }
  std::vector<scene::Piece> robot;
  robot.push_back(convexPiece(generators::blob(30, {0.8, 0.5, 0.4}, rng), "robot blob"));
  robot.push_back(
      convexPiece(transformed(generators::prism(6, 0.25, 1.2), translation({0.6, 0.0, 0.3})), "robot prism"));
  return make("blobs", std::move(robot), std::move(world),
              Eigen::AlignedBox3d(Eigen::Vector3d(-15, -15, -15), Eigen::Vector3d(15, 15, 15)), SpaceKind::kSE3);
}

ExampleScene trapScene(int grid) {
  if (grid < 6 || grid % 2 != 0) throw InvalidInputError("trapScene: the grid must be even and at least 6");
  std::vector<scene::Piece> world;
  const double outer = 5.0, inner = 4.6;
  // The opening: the central hole_cells x hole_cells squares of both surfaces
  // of the +x wall.
  const int hole_cells = std::max(2, grid / 4) / 2 * 2;
  const int h0 = (grid - hole_cells) / 2, h1 = h0 + hole_cells;
  const auto hole = [&](double half) { return -half + 2.0 * half * h0 / grid; };
  // Both surfaces of every wall: the six faces of the cubes of half side
  // `outer` and `inner`.
  for (const double half : {outer, inner}) {
    for (int axis = 0; axis < 3; ++axis) {
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      for (const double side : {-1.0, 1.0}) {
        Eigen::Vector3d corner = Eigen::Vector3d::Constant(-half);
        corner[axis] = side * half;
        const bool opening = axis == 0 && side > 0.0;
        // The outside of the closed walls: large triangles (2 x 2 squares).
        const int n = opening || half == inner ? grid : 2;
        const Eigen::Vector3d u = 2.0 * half / n * Eigen::Vector3d::Unit(a);
        const Eigen::Vector3d v = 2.0 * half / n * Eigen::Vector3d::Unit(b);
        for (int i = 0; i < n; ++i) {
          for (int j = 0; j < n; ++j) {
            if (opening && i >= h0 && i < h1 && j >= h0 && j < h1) continue;
            addRectangle(corner + i * u + j * v, u, v, "trap wall", &world);
          }
        }
      }
    }
  }
  // The opening's four sides between the surfaces, then a tube inward.
  const double ho = -hole(outer), hi = -hole(inner), tube_end = 2.0;
  const int tube_cells = 4;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d c[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    const Eigen::Vector2d p = c[k], q = c[(k + 1) % 4];
    const Eigen::Vector3d po(outer, ho * p.x(), ho * p.y()), qo(outer, ho * q.x(), ho * q.y());
    const Eigen::Vector3d pi(inner, hi * p.x(), hi * p.y()), qi(inner, hi * q.x(), hi * q.y());
    world.push_back(trianglePiece(po, qo, qi, "trap opening"));
    world.push_back(trianglePiece(po, qi, pi, "trap opening"));
    const Eigen::Vector3d u = (qi - pi) / tube_cells;
    const Eigen::Vector3d v = Eigen::Vector3d(tube_end - inner, 0, 0) / tube_cells;
    for (int i = 0; i < tube_cells; ++i) {
      for (int j = 0; j < tube_cells; ++j) addRectangle(pi + i * u + j * v, u, v, "trap tube", &world);
    }
  }
  // Tilted, so that no wall is parallel to the frame's planes (as in a
  // general mesh: the walls' triangles have thick axis-aligned boxes).
  Eigen::Isometry3d tilt = Eigen::Isometry3d::Identity();
  tilt.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (scene::Piece& p : world) {
    p = scene::Piece::make(ConvexPolytope::fromPoints(transformed(p.polytope.vertices(), tilt)), p.kind, p.origin);
  }
  // The capsule: rings along x (pole, two cap rings, five body rings, two cap
  // rings, pole) of 14 vertices each.
  const double r = 0.35, body = 1.2;
  const int m = 14;
  std::vector<std::pair<double, double>> rings;  // (x, radius)
  for (const double phi : {kPi / 6, kPi / 3}) rings.emplace_back(-body - r * std::cos(phi), r * std::sin(phi));
  for (int k = 0; k <= 4; ++k) rings.emplace_back(-body + 0.5 * body * k, r);
  for (const double phi : {kPi / 3, kPi / 6}) rings.emplace_back(body + r * std::cos(phi), r * std::sin(phi));
  const auto at = [&](std::size_t ring, int k) {
    const double t = 2.0 * kPi * k / m;
    return Eigen::Vector3d(rings[ring].first, rings[ring].second * std::cos(t), rings[ring].second * std::sin(t));
  };
  std::vector<scene::Piece> robot;
  const Eigen::Vector3d pole0(-body - r, 0, 0), pole1(body + r, 0, 0);
  for (int k = 0; k < m; ++k) {
    robot.push_back(trianglePiece(pole0, at(0, (k + 1) % m), at(0, k), "capsule cap"));
    robot.push_back(trianglePiece(pole1, at(rings.size() - 1, k), at(rings.size() - 1, (k + 1) % m), "capsule cap"));
    for (std::size_t ring = 0; ring + 1 < rings.size(); ++ring) {
      robot.push_back(trianglePiece(at(ring, k), at(ring, (k + 1) % m), at(ring + 1, (k + 1) % m), "capsule"));
      robot.push_back(trianglePiece(at(ring, k), at(ring + 1, (k + 1) % m), at(ring + 1, k), "capsule"));
    }
  }
  return make("trap", std::move(robot), std::move(world),
              Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-7.0), Eigen::Vector3d::Constant(7.0)), SpaceKind::kSE3);
}

ExampleScene thinWallScene(double thickness) {
  if (!(thickness > 0.0)) throw InvalidInputError("thinWallScene: the thickness must be positive");
  std::vector<scene::Piece> world;
  const double x0 = 50.0;
  world.push_back(
      convexPiece(transformed(generators::box({0.5 * thickness, 10.0, 1.0}), translation({x0 + 0.5 * thickness, 0, 0})),
                  "thin wall"));
  std::vector<scene::Piece> robot;
  robot.push_back(convexPiece(generators::box({0.1, 0.1, 0.1}), "cube"));
  return make("thin wall", std::move(robot), std::move(world),
              Eigen::AlignedBox3d(Eigen::Vector3d(0, -5, -1), Eigen::Vector3d(100, 5, 1)), SpaceKind::kR2);
}

PlanningSpacePtr makeSpace(const ExampleScene& scene, SpaceKind kind) {
  return PlanningSpace::make(kind, scene.bounds);
}

PlanarArm planarArm(const std::vector<double>& lengths, double half_width, double half_height) {
  if (lengths.empty()) throw InvalidInputError("planarArm: no link");
  if (!(half_width > 0.0) || !(half_height > 0.0)) throw InvalidInputError("planarArm: sizes must be positive");
  std::vector<scene::Link> links(lengths.size() + 1);
  std::vector<scene::Joint> joints(lengths.size());
  links[0].name = "base";
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    const double length = lengths[i];
    if (!(length > 0.0)) throw InvalidInputError("planarArm: link lengths must be positive");
    scene::Joint& j = joints[i];
    j.name = "joint" + std::to_string(i + 1);
    j.type = scene::JointType::kRevolute;
    j.parent_link = static_cast<int>(i);
    j.child_link = static_cast<int>(i + 1);
    j.X_PJ.translation() = Eigen::Vector3d(i == 0 ? 0.0 : lengths[i - 1], 0.0, 0.0);
    j.axis_J = Eigen::Vector3d::UnitZ();
    j.lower = -kPi;
    j.upper = kPi;
    scene::Link& l = links[i + 1];
    l.name = "link" + std::to_string(i + 1);
    l.parent_joint = static_cast<int>(i);
    links[i].child_joints.push_back(static_cast<int>(i));
    Eigen::Isometry3d X_LB = Eigen::Isometry3d::Identity();
    X_LB.translation() = Eigen::Vector3d(0.5 * length, 0.0, 0.0);
    l.pieces.push_back(scene::boxPiece(Eigen::Vector3d(length, 2.0 * half_width, 2.0 * half_height), X_LB, l.name));
  }
  PlanarArm arm;
  auto model = std::make_shared<const scene::RobotModel>("planar_arm", std::move(links), std::move(joints));
  arm.filter = scene::AllowedCollisions(*model);
  for (int k = 0; k + 1 < model->numLinks(); ++k) arm.filter.allow(k, k + 1);
  arm.model = std::move(model);
  return arm;
}

}  // namespace mddual::planning::examples
