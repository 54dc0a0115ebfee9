#include "cases.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "mddual/constants.h"
#include "mddual/error.h"
#include "mddual/generators.h"
#include "mddual/planning/dense_contact.h"
#include "mddual/planning/example_scenes.h"

namespace mddual::soundness {
namespace {

using Rng = std::mt19937_64;
constexpr int kMaxTries = 1000;

double uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

double logUniform(Rng& rng, double lo, double hi) {
  const double u = uniform(rng, 0.0, 1.0);
  return lo * std::pow(hi / lo, u);
}

/// Each coordinate drawn in a statement of its own (CONTRIBUTING.md).
Eigen::Vector3d randomVector(Rng& rng, double lo, double hi) {
  const double z = uniform(rng, lo, hi);
  const double y = uniform(rng, lo, hi);
  const double x = uniform(rng, lo, hi);
  return {x, y, z};
}

/// Half extents each log-uniform in [lo, hi] (drawn z, y, x: the families'
/// samples were made in that order).
Eigen::Vector3d logUniformHalf(Rng& rng, double lo, double hi) {
  const double z = logUniform(rng, lo, hi);
  const double y = logUniform(rng, lo, hi);
  const double x = logUniform(rng, lo, hi);
  return {x, y, z};
}

Eigen::Vector3d randomUnit(Rng& rng) {
  std::normal_distribution<double> normal;
  for (;;) {
    const double z = normal(rng);
    const double y = normal(rng);
    const double x = normal(rng);
    const Eigen::Vector3d v(x, y, z);
    if (v.norm() > 1e-6) return v.normalized();
  }
}

Eigen::Quaterniond randomRotation(Rng& rng) {
  std::normal_distribution<double> normal;
  const double w = normal(rng);
  const double x = normal(rng);
  const double y = normal(rng);
  const double z = normal(rng);
  return Eigen::Quaterniond(w, x, y, z).normalized();
}

Eigen::Isometry3d pose(const Eigen::Quaterniond& q, const Eigen::Vector3d& p) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() = p;
  return X;
}

Eigen::Quaterniond yaw(double angle) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()));
}

Eigen::AlignedBox3d around(const Eigen::Vector3d& o, double half) {
  return Eigen::AlignedBox3d(o - Eigen::Vector3d::Constant(half), o + Eigen::Vector3d::Constant(half));
}

/// A link of length L and half width w from the body origin along +x.
Box link(double length, double w, double half_z) {
  Box b;
  b.X.translation() = Eigen::Vector3d(0.5 * length, 0.0, 0.0);
  b.half = Eigen::Vector3d(0.5 * length, w, half_z);
  return b;
}

bool startsFree(const Case& c, const Eigen::Isometry3d& X) {
  return detail::sceneGap(c, X) > 0.0;
}

/// An R^3 case of `family` in the box of half side 10 about o.
Case r3Case(const std::string& family, const Eigen::Vector3d& o) {
  Case c;
  c.family = family;
  c.kind = planning::SpaceKind::kR3;
  c.bounds = around(o, 10.0);
  return c;
}

/// `count` translation edges of the fixed-orientation robot of `c` aimed near a
/// random world box (within `aim` of its centre), ends inside the bounds.
void addTranslationEdges(Case& c, Rng& rng, int count, double aim) {
  const Eigen::Vector3d o = c.bounds.center();
  for (int k = 0, tries = 0; k < count && tries < kMaxTries; ++tries) {
    const auto index = std::uniform_int_distribution<std::size_t>(0, c.world.size() - 1)(rng);
    const Eigen::Vector3d centre = c.world[index].X.translation();
    const Eigen::Vector3d start_dir = randomUnit(rng);
    const double start_distance = uniform(rng, 3.0, 8.0);
    const Eigen::Vector3d start = o + start_dir * start_distance;
    const Eigen::Vector3d aim_dir = randomUnit(rng);
    const double aim_distance = uniform(rng, 0.0, aim);
    const Eigen::Vector3d target = centre + aim_dir * aim_distance;
    const double beyond = uniform(rng, -1.0, 6.0);
    const Eigen::Vector3d end = target + (target - start).normalized() * beyond;
    const Eigen::Isometry3d X1 = pose(c.q_fixed, start), X2 = pose(c.q_fixed, end);
    if (!c.bounds.contains(start) || !c.bounds.contains(end) || !startsFree(c, X1)) continue;
    c.edges.emplace_back(X1, X2);
    ++k;
  }
}

/// Boxes translating toward each other (the robot's frame moves, the world's
/// box stands still: only their relative motion matters). `boxes` world boxes,
/// as triangle meshes when `triangles`.
std::vector<Case> translatingBoxes(Rng& rng, int edges, const Eigen::Vector3d& o, int boxes, bool triangles,
                                   const std::string& family) {
  std::vector<Case> out;
  constexpr int kEdgesPerCase = 4;
  for (int e = 0; e < edges; e += kEdgesPerCase) {
    Case c = r3Case(family, o);
    c.q_fixed = randomRotation(rng);
    Box robot;
    robot.half = logUniformHalf(rng, 0.02, 1.0);
    c.robot.push_back(robot);
    double reach = robot.half.norm();
    for (int i = 0; i < boxes; ++i) {
      Box b;
      const Eigen::Quaterniond q = randomRotation(rng);
      const Eigen::Vector3d p = o + (boxes > 1 ? randomVector(rng, -1.5, 1.5) : Eigen::Vector3d::Zero());
      b.X = pose(q, p);
      b.half = logUniformHalf(rng, 0.02, 1.5);
      c.world.push_back(b);
      reach = std::max(reach, robot.half.norm() + b.half.norm());
    }
    c.world_triangles = triangles;
    addTranslationEdges(c, rng, std::min(kEdgesPerCase, edges - e), 1.2 * reach);
    out.push_back(std::move(c));
  }
  return out;
}

/// SE(2): a link turning about its end past an obstacle on the bisector of its
/// arc: 60% inside the arc and outside the hull of the end poses, 20% inside
/// that hull, 20% beyond the link's reach. One edge per case.
std::vector<Case> rotatingLinkArc(Rng& rng, int edges, const Eigen::Vector3d& o, const std::string& family) {
  std::vector<Case> out;
  for (int e = 0, tries = 0; e < edges && tries < kMaxTries * edges; ++tries) {
    Case c;
    c.family = family;
    c.kind = planning::SpaceKind::kSE2;
    c.bounds = around(o, 5.0);
    const double length = uniform(rng, 1.5, 3.0);
    const double w = uniform(rng, 0.03, 0.1);
    c.robot.push_back(link(length, w, 0.25));
    const double px = uniform(rng, -1.0, 1.0);
    const double py = uniform(rng, -1.0, 1.0);
    const Eigen::Vector3d pivot = o + Eigen::Vector3d(px, py, 0.0);
    const double phi0 = uniform(rng, -kPi, kPi);
    const double theta = uniform(rng, 30.0, 120.0) * kPi / 180.0;
    const double sign = uniform(rng, 0.0, 1.0) < 0.5 ? -1.0 : 1.0;
    const double beta = phi0 + sign * 0.5 * theta;
    // The hull of the two end poses reaches `support` along the bisector.
    const double support = length * std::cos(0.5 * theta) + w * std::sin(0.5 * theta);
    const double kind = uniform(rng, 0.0, 1.0);
    double inner = 0.0, h = 0.0;
    if (kind < 0.6) {
      inner = support + (length - support) * uniform(rng, 0.1, 0.6);
      h = std::min(0.25, (length - support) * uniform(rng, 0.1, 0.4));
    } else if (kind < 0.8) {
      inner = support * uniform(rng, 0.3, 0.8);
      h = uniform(rng, 0.05, 0.2);
    } else {
      inner = std::hypot(length, w) + uniform(rng, 0.02, 0.5);
      h = uniform(rng, 0.05, 0.2);
    }
    Box obstacle;
    obstacle.X = pose(yaw(beta), pivot + (inner + h) * Eigen::Vector3d(std::cos(beta), std::sin(beta), 0.0));
    obstacle.half = Eigen::Vector3d(h, h, 0.5);
    c.world.push_back(obstacle);
    const Eigen::Isometry3d X1 = pose(yaw(phi0), pivot);
    const Eigen::Isometry3d X2 = pose(yaw(phi0 + sign * theta), pivot);
    if (!startsFree(c, X1)) continue;
    c.edges.emplace_back(X1, X2);
    out.push_back(std::move(c));
    ++e;
  }
  return out;
}

/// SE(3): a link turning 90 to 170 degrees while it moves; 80% of the
/// obstacles sit on a point of the link at some t of OMPL's interpolation
/// and clear of the screw motion, 20% are moved off by 1 to 3.
std::vector<Case> screwVsInterpolated(Rng& rng, int edges) {
  std::vector<Case> out;
  for (int e = 0, tries = 0; e < edges && tries < kMaxTries * edges; ++tries) {
    Case c;
    c.family = "screw-vs-interpolated";
    c.kind = planning::SpaceKind::kSE3;
    c.bounds = around(Eigen::Vector3d::Zero(), 10.0);
    const double length = uniform(rng, 1.5, 3.0);
    const double w = uniform(rng, 0.03, 0.1);
    c.robot.push_back(link(length, w, w));
    const Eigen::Vector3d p1 = randomVector(rng, -2.0, 2.0);
    const Eigen::Quaterniond q1 = randomRotation(rng);
    const Eigen::Vector3d axis = randomUnit(rng);
    const double theta = uniform(rng, 90.0, 170.0) * kPi / 180.0;
    const Eigen::Quaterniond q2 = q1 * Eigen::Quaterniond(Eigen::AngleAxisd(theta, axis));
    const Eigen::Vector3d move_dir = randomUnit(rng);
    const double move = uniform(rng, 1.0, 4.0);
    const Eigen::Vector3d p2 = p1 + move_dir * move;
    const double tm = uniform(rng, 0.3, 0.7);
    const double along = uniform(rng, 0.6, 1.0);
    const Eigen::Isometry3d Xm = pose(q1.slerp(tm, q2), p1 + tm * (p2 - p1));
    Eigen::Vector3d point = Xm * Eigen::Vector3d(along * length, 0.0, 0.0);
    const bool off_path = uniform(rng, 0.0, 1.0) < 0.2;
    if (off_path) {
      const Eigen::Vector3d dir = randomUnit(rng);
      const double distance = uniform(rng, 1.0, 3.0);
      point += dir * distance;
    }
    Box obstacle;
    const Eigen::Quaterniond qo = randomRotation(rng);
    obstacle.X = pose(qo, point);
    const double h = uniform(rng, 0.02, 0.08);
    obstacle.half = Eigen::Vector3d::Constant(h);
    c.world.push_back(obstacle);
    c.edges.emplace_back(pose(q1, p1), pose(q2, p2));
    if (!startsFree(c, c.edges[0].first)) continue;
    if (!off_path && screwFirstContact(c, 0) < kInf) continue;
    out.push_back(std::move(c));
    ++e;
  }
  return out;
}

/// R^3: a wall 0.004 to 0.04 thick, tilted up to 0.3 rad about z, crossed or
/// passed by a cube of half side 0.1.
std::vector<Case> thinWall(Rng& rng, int edges) {
  std::vector<Case> out;
  constexpr int kEdgesPerCase = 4;
  for (int e = 0; e < edges; e += kEdgesPerCase) {
    Case c = r3Case("thin-wall", Eigen::Vector3d::Zero());
    Box robot;
    robot.half = Eigen::Vector3d::Constant(0.1);
    c.robot.push_back(robot);
    Box wall;
    const double tilt = uniform(rng, -0.3, 0.3);
    const double thickness = logUniform(rng, 0.004, 0.04);
    wall.X = pose(yaw(tilt), Eigen::Vector3d::Zero());
    wall.half = Eigen::Vector3d(0.5 * thickness, 2.0, 2.0);
    c.world.push_back(wall);
    for (int k = 0; k < std::min(kEdgesPerCase, edges - e); ++k) {
      const Eigen::Vector3d a = randomVector(rng, -3.0, 3.0);
      const Eigen::Vector3d b = randomVector(rng, -3.0, 3.0);
      const double xa = uniform(rng, 1.0, 5.0);
      const double xb = uniform(rng, 1.0, 5.0);
      const Eigen::Vector3d start(-xa, a.y(), a.z()), end(xb, b.y(), b.z());
      c.edges.emplace_back(pose(c.q_fixed, start), pose(c.q_fixed, end));
    }
    out.push_back(std::move(c));
  }
  return out;
}

/// R^3: a box sliding along a face of another with the same orientation, at
/// a gap of +1e-6 (free) or -1e-6 (overlapping) of the bodies' size.
std::vector<Case> grazing(Rng& rng, int edges) {
  std::vector<Case> out;
  for (int e = 0; e < edges; e += 2) {
    Case c = r3Case("grazing", Eigen::Vector3d::Zero());
    c.q_fixed = randomRotation(rng);
    Box robot, world;
    robot.half = randomVector(rng, 0.3, 1.0);
    world.half = randomVector(rng, 0.3, 1.0);
    const Eigen::Vector3d centre = randomVector(rng, -4.0, 4.0);
    world.X = pose(c.q_fixed, centre);
    c.robot.push_back(robot);
    c.world.push_back(world);
    const double size = 2.0 * std::max(robot.half.maxCoeff(), world.half.maxCoeff());
    const int face = std::uniform_int_distribution<int>(0, 2)(rng);
    const int slide = (face + 1) % 3, across = (face + 2) % 3;
    const double side = uniform(rng, 0.0, 1.0) < 0.5 ? -1.0 : 1.0;
    for (double sign : {1.0, -1.0}) {
      if (static_cast<int>(c.edges.size()) + e >= edges) break;
      const double reach = robot.half[slide] + world.half[slide];
      const double run_a = uniform(rng, 0.5, 2.0);
      const double run_b = uniform(rng, 0.5, 2.0);
      const double shift = uniform(rng, -0.8, 0.8) * (robot.half[across] + world.half[across]);
      Eigen::Vector3d a, b;
      a[face] = b[face] = side * (robot.half[face] + world.half[face] + sign * 1e-6 * size);
      a[across] = b[across] = shift;
      a[slide] = -(reach + run_a);
      b[slide] = reach + run_b;
      c.edges.emplace_back(pose(c.q_fixed, world.X * a), pose(c.q_fixed, world.X * b));
    }
    out.push_back(std::move(c));
  }
  return out;
}

Box placed(const Box& b, const Eigen::Isometry3d& X) {
  return Box{X * b.X, b.half};
}

/// The link boxes of an arm case at configuration q, in the world frame: the
/// planar chain's forward kinematics (joint i turns about z at the far end
/// of link i - 1; link i a box from its joint along its own x).
std::vector<Box> armBoxes(const Case& c, const std::vector<double>& q) {
  std::vector<Box> boxes;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double angle = 0.0;
  for (std::size_t i = 0; i < c.arm_lengths.size(); ++i) {
    const double length = c.arm_lengths[i];
    angle += q[i];
    const Eigen::Vector3d dir(std::cos(angle), std::sin(angle), 0.0);
    Box b;
    b.X = pose(yaw(angle), origin + 0.5 * length * dir);
    b.half = Eigen::Vector3d(0.5 * length, c.arm_half_width, c.arm_half_height);
    boxes.push_back(b);
    origin += length * dir;
  }
  return boxes;
}

/// A bound of how fast (per unit of t) any point of the arm moves on the
/// edge q0 -> q1: joint i moves the points beyond it at most |dq_i| times
/// their distance from it, at most the links' lengths from it on plus the
/// far corner's offset.
double armSpeed(const Case& c, const std::vector<double>& q0, const std::vector<double>& q1) {
  const double corner = std::hypot(c.arm_half_width, c.arm_half_height);
  double speed = 0.0;
  for (std::size_t i = 0; i < c.arm_lengths.size(); ++i) {
    double reach = corner;
    for (std::size_t k = i; k < c.arm_lengths.size(); ++k) reach += c.arm_lengths[k];
    speed += std::abs(q1[i] - q0[i]) * reach;
  }
  return speed;
}

/// The planar arm of three links turning one joint 30 to 120 degrees (the
/// others fixed) past a small box: 60% of the boxes on a point of a link
/// beyond the joint at a t in [0.3, 0.7] of the edge, 20% beyond the arm's
/// reach, 20% anywhere within it. One edge per case, the start free.
std::vector<Case> armRotatingLink(Rng& rng, int edges, const std::string& family) {
  std::vector<Case> out;
  for (int e = 0, tries = 0; e < edges && tries < kMaxTries * edges; ++tries) {
    Case c;
    c.family = family;
    c.kind = planning::SpaceKind::kR3;  // unused: arm cases live in joint space
    c.bounds = around(Eigen::Vector3d::Zero(), 5.0);
    const double l3 = uniform(rng, 0.4, 1.0);
    const double l2 = uniform(rng, 0.4, 1.0);
    const double l1 = uniform(rng, 0.4, 1.0);
    c.arm_lengths = {l1, l2, l3};
    c.arm_half_width = uniform(rng, 0.02, 0.06);
    c.arm_half_height = 0.05;
    std::vector<double> q0(3);
    for (double& v : q0) v = uniform(rng, -1.2, 1.2);
    const int joint = std::uniform_int_distribution<int>(0, 2)(rng);
    const double theta = uniform(rng, 30.0, 120.0) * kPi / 180.0;
    double sign = uniform(rng, 0.0, 1.0) < 0.5 ? -1.0 : 1.0;
    if (std::abs(q0[static_cast<std::size_t>(joint)] + sign * theta) > kPi) sign = -sign;
    std::vector<double> q1 = q0;
    q1[static_cast<std::size_t>(joint)] += sign * theta;
    const double reach = l1 + l2 + l3;
    const double kind = uniform(rng, 0.0, 1.0);
    const double h = uniform(rng, 0.03, 0.1);
    Eigen::Vector3d centre;
    if (kind < 0.6) {
      const double tm = uniform(rng, 0.3, 0.7);
      std::vector<double> qm(3);
      for (std::size_t v = 0; v < 3; ++v) qm[v] = q0[v] + tm * (q1[v] - q0[v]);
      const auto link = std::uniform_int_distribution<int>(joint, 2)(rng);
      const Box b = armBoxes(c, qm)[static_cast<std::size_t>(link)];
      const double along = uniform(rng, 0.4, 1.0);
      centre = b.X * Eigen::Vector3d(along * b.half.x(), 0.0, 0.0);
    } else if (kind < 0.8) {
      const double angle = uniform(rng, -kPi, kPi);
      const double r = reach + 2.0 * h + uniform(rng, 0.05, 0.5);
      centre = Eigen::Vector3d(r * std::cos(angle), r * std::sin(angle), 0.0);
    } else {
      const double angle = uniform(rng, -kPi, kPi);
      const double r = uniform(rng, 0.2, reach);
      centre = Eigen::Vector3d(r * std::cos(angle), r * std::sin(angle), 0.0);
    }
    Box obstacle;
    const double spin = uniform(rng, -kPi, kPi);
    obstacle.X = pose(yaw(spin), centre);
    obstacle.half = Eigen::Vector3d(h, h, 0.1);
    c.world.push_back(obstacle);
    c.arm_edges.emplace_back(q0, q1);
    if (!(detail::armGap(c, q0) > 0.0)) continue;
    out.push_back(std::move(c));
    ++e;
  }
  return out;
}

/// The 15 separating axes of two boxes (unit; the degenerate cross products
/// of parallel edges left out).
std::vector<Eigen::Vector3d> axes(const Box& a, const Box& b) {
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < 3; ++i) out.push_back(a.X.linear().col(i));
  for (int i = 0; i < 3; ++i) out.push_back(b.X.linear().col(i));
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d n = a.X.linear().col(i).cross(b.X.linear().col(j));
      if (n.norm() > 1e-9) out.push_back(n.normalized());
    }
  }
  return out;
}

/// Half the width of box b's projection on the unit axis n.
double radius(const Box& b, const Eigen::Vector3d& n) {
  return (b.X.linear().transpose() * n).cwiseAbs().dot(b.half);
}

/// The eight corners of b in its owner's frame.
std::vector<Eigen::Vector3d> corners(const Box& b) {
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector3d& p : generators::box(b.half)) points.push_back(b.X * p);
  return points;
}

/// Largest distance of a robot point from the body origin.
double robotRadius(const Case& c) {
  double r = 0.0;
  for (const Box& b : c.robot) r = std::max(r, b.X.translation().norm() + b.half.norm());
  return r;
}

/// The exact first contact of the translation X1 -> X2 (same rotation).
double exactTranslationContact(const Case& c, const Eigen::Isometry3d& X1, const Eigen::Isometry3d& X2) {
  const Eigen::Vector3d v = X2.translation() - X1.translation();
  double first = kInf;
  for (const Box& r : c.robot) {
    const Box a = placed(r, X1);
    for (const Box& b : c.world) {
      double lo = 0.0, hi = 1.0;
      for (const Eigen::Vector3d& n : axes(a, b)) {
        const double s0 = n.dot(a.X.translation() - b.X.translation());
        const double reach = radius(a, n) + radius(b, n);
        const double vn = n.dot(v);
        if (vn == 0.0) {
          if (std::abs(s0) > reach) lo = kInf;
          continue;
        }
        const double t0 = (-reach - s0) / vn, t1 = (reach - s0) / vn;
        lo = std::max(lo, std::min(t0, t1));
        hi = std::min(hi, std::max(t0, t1));
      }
      if (lo <= hi) first = std::min(first, lo);
    }
  }
  return first;
}

/// R^3: one flat mesh obstacle near the origin, in a random orientation (a
/// box of half.z() 0, meshed by buildScene in `flat_strips` strips), one kind
/// a case in turn: a large flat triangle pair (4 to 9 across), a strip (1 to
/// 4 long, 0.001 to 0.02 wide: two needle triangles) or a sheet of slivers
/// (2 to 4 by 0.4 to 1.2, in 32 to 64 strips: triangles 50 to 640 times as
/// long as high). A box of 0.02 to 0.6 across in a random orientation
/// aimed at a point of the plane up to its radius beyond the rectangle: 3
/// edges in 4 cross the plane there (or stop short), 1 in 4 slide along it
/// at -0.02 to +0.05 from touching it.
std::vector<Case> sliverMesh(Rng& rng, int edges) {
  std::vector<Case> out;
  constexpr int kEdgesPerCase = 4;
  for (int e = 0; e < edges; e += kEdgesPerCase) {
    Case c = r3Case("sliver-mesh", Eigen::Vector3d::Zero());
    c.q_fixed = randomRotation(rng);
    c.world_triangles = true;
    Box robot;
    robot.half = logUniformHalf(rng, 0.01, 0.3);
    c.robot.push_back(robot);
    // The kinds in turn: a large flat pair, a strip, a sheet.
    const int kind = static_cast<int>(out.size() % 3);
    double hx = 0.0, hy = 0.0;
    if (kind == 0) {
      hx = uniform(rng, 2.0, 4.5);
      hy = uniform(rng, 2.0, 4.5);
    } else if (kind == 1) {
      hx = uniform(rng, 0.5, 2.0);
      hy = 0.5 * logUniform(rng, 0.001, 0.02);
    } else {
      hx = uniform(rng, 1.0, 2.0);
      hy = uniform(rng, 0.2, 0.6);
      c.flat_strips = std::uniform_int_distribution<int>(32, 64)(rng);
    }
    Box flat;
    const Eigen::Quaterniond q = randomRotation(rng);
    flat.X = pose(q, randomVector(rng, -1.0, 1.0));
    flat.half = Eigen::Vector3d(hx, hy, 0.0);
    c.world.push_back(flat);
    const Eigen::Vector3d n = flat.X.linear().col(2);
    const double support = radius(placed(robot, pose(c.q_fixed, Eigen::Vector3d::Zero())), n);
    const double r = robot.half.norm();
    for (int k = 0, tries = 0; k < std::min(kEdgesPerCase, edges - e) && tries < kMaxTries; ++tries) {
      const double ay = uniform(rng, -1.0, 1.0);
      const double ax = uniform(rng, -1.0, 1.0);
      const Eigen::Vector3d target = flat.X * Eigen::Vector3d(ax * (hx + r), ay * (hy + r), 0.0);
      const bool slide = uniform(rng, 0.0, 1.0) < 0.25;
      Eigen::Vector3d dir = randomUnit(rng);
      const double before = uniform(rng, 1.0, 4.0);
      const double after = uniform(rng, slide ? 1.0 : -0.5, 4.0);
      Eigen::Vector3d via = target;
      if (slide) {
        dir -= dir.dot(n) * n;
        if (dir.norm() < 0.1) continue;
        dir.normalize();
        const double offset = support + uniform(rng, -0.02, 0.05);
        via += (uniform(rng, 0.0, 1.0) < 0.5 ? -offset : offset) * n;
      } else if (std::abs(dir.dot(n)) < 0.3) {
        continue;
      }
      const Eigen::Vector3d start = via - before * dir, end = via + after * dir;
      const Eigen::Isometry3d X1 = pose(c.q_fixed, start), X2 = pose(c.q_fixed, end);
      if (!c.bounds.contains(start) || !c.bounds.contains(end) || !startsFree(c, X1)) continue;
      c.edges.emplace_back(X1, X2);
      ++k;
    }
    out.push_back(std::move(c));
  }
  return out;
}

/// The flat box b (half.z() 0) cut across its y side into `strips` strips of
/// two triangles each, as mesh pieces.
std::vector<scene::Piece> flatTriangles(const Box& b, int strips) {
  const Eigen::Vector3d u = 2.0 * b.half.x() * b.X.linear().col(0);
  const Eigen::Vector3d v = 2.0 * b.half.y() / strips * b.X.linear().col(1);
  const Eigen::Vector3d corner = b.X * Eigen::Vector3d(-b.half.x(), -b.half.y(), 0.0);
  std::vector<scene::Piece> out;
  const auto add = [&out](const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r) {
    out.push_back(
        scene::Piece::make(ConvexPolytope::fromPoints({p, q, r}), scene::PieceKind::kTriangle, "world sliver"));
  };
  for (int k = 0; k < strips; ++k) {
    const Eigen::Vector3d o = corner + static_cast<double>(k) * v;
    add(o, o + u, o + u + v);
    add(o, o + u + v, o + v);
  }
  return out;
}

}  // namespace

double boxGap(const Box& a, const Box& b) {
  const Eigen::Vector3d d = b.X.translation() - a.X.translation();
  double gap = -kInf;
  for (const Eigen::Vector3d& n : axes(a, b)) gap = std::max(gap, std::abs(n.dot(d)) - radius(a, n) - radius(b, n));
  return gap;
}

namespace detail {
double sceneGap(const Case& c, const Eigen::Isometry3d& X_WR) {
  double gap = kInf;
  for (const Box& r : c.robot) {
    const Box a = placed(r, X_WR);
    for (const Box& b : c.world) {
      gap = std::min(gap, boxGap(a, b));
      if (gap <= 0.0) return gap;
    }
  }
  return gap;
}

double armGap(const Case& c, const std::vector<double>& q) {
  const std::vector<Box> links = armBoxes(c, q);
  double gap = kInf;
  for (std::size_t i = 0; i < links.size(); ++i) {
    for (const Box& b : c.world) gap = std::min(gap, boxGap(links[i], b));
    for (std::size_t k = i + 2; k < links.size(); ++k) gap = std::min(gap, boxGap(links[i], links[k]));
    if (gap <= 0.0) return gap;
  }
  return gap;
}
}  // namespace detail

const std::vector<std::string>& familyNames() {
  // A family's seed depends on its place here (makeFamily): a new family goes
  // last, so that the others keep their samples.
  static const std::vector<std::string> names = {
      "translating-boxes", "obb-hierarchy",   "rotating-link-arc", "screw-vs-interpolated",
      "thin-wall",         "far-from-origin", "grazing",           "arm-rotating-link",
      "sliver-mesh"};
  return names;
}

std::vector<Case> makeFamily(const std::string& family, std::uint64_t seed, int edges) {
  const auto& names = familyNames();
  const auto it = std::find(names.begin(), names.end(), family);
  if (it == names.end()) throw InvalidInputError("soundness: unknown case family '" + family + "'");
  Rng rng(seed * 1000003u + static_cast<std::uint64_t>(it - names.begin()));
  const Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  if (family == "translating-boxes") return translatingBoxes(rng, edges, origin, 1, false, family);
  if (family == "obb-hierarchy") return translatingBoxes(rng, edges, origin, 3, true, family);
  if (family == "rotating-link-arc") return rotatingLinkArc(rng, edges, origin, family);
  if (family == "screw-vs-interpolated") return screwVsInterpolated(rng, edges);
  if (family == "thin-wall") return thinWall(rng, edges);
  if (family == "grazing") return grazing(rng, edges);
  if (family == "sliver-mesh") return sliverMesh(rng, edges);
  if (family == "arm-rotating-link") return armRotatingLink(rng, edges, family);
  // far-from-origin: half translating boxes, half rotating links, at 1e6.
  std::vector<Case> out = translatingBoxes(rng, edges / 2, Eigen::Vector3d::Constant(1e6), 1, false, family);
  for (Case& c : rotatingLinkArc(rng, edges - edges / 2, Eigen::Vector3d(1e6, 1e6, 0.0), family)) {
    out.push_back(std::move(c));
  }
  return out;
}

Scene buildScene(const Case& c) {
  Scene s;
  if (c.isArm()) {
    std::vector<scene::Piece> world;
    for (const Box& b : c.world) world.push_back(planning::examples::convexPiece(corners(b), "world box"));
    s.world = std::make_shared<scene::World>(std::move(world), c.family + " world");
    const planning::examples::PlanarArm arm =
        planning::examples::planarArm(c.arm_lengths, c.arm_half_width, c.arm_half_height);
    std::vector<int> group;
    for (int v = 0; v < arm.model->numVariables(); ++v) group.push_back(v);
    s.arm_space = planning::ArmSpace::make(arm.model, group);
    s.arm = std::make_shared<planning::ArmScene>(arm.model, s.world, arm.filter);
    return s;
  }
  s.space = planning::PlanningSpace::make(c.kind, c.bounds, 0.0, c.q_fixed);
  std::vector<scene::Piece> robot, world;
  for (const Box& b : c.robot) robot.push_back(planning::examples::convexPiece(corners(b), "robot box"));
  for (const Box& b : c.world) {
    if (c.world_triangles && b.half.z() == 0.0) {
      for (scene::Piece& p : flatTriangles(b, c.flat_strips)) world.push_back(p);
    } else if (c.world_triangles) {
      for (scene::Piece& p : planning::examples::boxTriangles(b.half, b.X, "world mesh box")) world.push_back(p);
    } else {
      world.push_back(planning::examples::convexPiece(corners(b), "world box"));
    }
  }
  s.robot = std::make_shared<scene::RigidBody>(std::move(robot), c.family + " robot");
  s.world = std::make_shared<scene::World>(std::move(world), c.family + " world");
  return s;
}

ompl::base::State* makeState(const Scene& s, const Eigen::Isometry3d& X) {
  ompl::base::State* state = s.space->stateSpace()->allocState();
  s.space->setPose(X, state);
  return state;
}

std::pair<ompl::base::State*, ompl::base::State*> makeEdgeStates(const Case& c, const Scene& s, int edge) {
  const auto e = static_cast<std::size_t>(edge);
  if (!c.isArm()) return {makeState(s, c.edges[e].first), makeState(s, c.edges[e].second)};
  const ompl::base::StateSpacePtr& space = s.arm_space->stateSpace();
  ompl::base::State* a = space->allocState();
  ompl::base::State* b = space->allocState();
  s.arm_space->setState(a, c.arm_edges[e].first.data());
  s.arm_space->setState(b, c.arm_edges[e].second.data());
  return {a, b};
}

double startGap(const Case& c, int edge) {
  const auto e = static_cast<std::size_t>(edge);
  return c.isArm() ? detail::armGap(c, c.arm_edges[e].first) : detail::sceneGap(c, c.edges[e].first);
}

Truth groundTruth(const Case& c, const Scene& s, int edge, double min_step) {
  if (c.isArm()) {
    // Joint-space edges: q(t) = q0 + t (q1 - q0) (OMPL's interpolation of a
    // RealVector space); relative speeds of two links at most twice a point's.
    const auto& [q0, q1] = c.arm_edges[static_cast<std::size_t>(edge)];
    std::vector<double> q(q0.size());
    const auto gap = [&](double t) {
      for (std::size_t v = 0; v < q.size(); ++v) q[v] = q0[v] + t * (q1[v] - q0[v]);
      return detail::armGap(c, q);
    };
    Truth truth;
    truth.dense_contact = planning::denseFirstContact(gap, 2.0 * armSpeed(c, q0, q1), min_step);
    truth.collides = truth.dense_contact < kInf;
    return truth;
  }
  const auto& [X1, X2] = c.edges[static_cast<std::size_t>(edge)];
  const ompl::base::StateSpacePtr& space = s.space->stateSpace();
  ompl::base::State* a = makeState(s, X1);
  ompl::base::State* b = makeState(s, X2);
  ompl::base::State* scratch = space->allocState();
  const auto at = [&](double t) {
    space->interpolate(a, b, t, scratch);
    return s.space->pose(scratch);
  };
  const double angle = Eigen::AngleAxisd(X1.linear().transpose() * X2.linear()).angle();
  const double speed = (X2.translation() - X1.translation()).norm() + angle * robotRadius(c);
  Truth truth;
  truth.dense_contact = denseFirstContact(c, at, speed, min_step);
  truth.collides = truth.dense_contact < kInf;
  if (X1.linear() == X2.linear()) truth.exact_contact = exactTranslationContact(c, X1, X2);
  space->freeState(scratch);
  space->freeState(b);
  space->freeState(a);
  return truth;
}

double screwFirstContact(const Case& c, int edge, double min_step) {
  const auto& [X1, X2] = c.edges[static_cast<std::size_t>(edge)];
  // The world motion M(t) with M(1) X1 = X2: a turn by t * theta about the
  // axis u through c, and a slide of t * slide along u.
  const Eigen::Isometry3d D = X2 * X1.inverse();
  const Eigen::AngleAxisd turn(D.linear());
  const Eigen::Vector3d u = turn.axis();
  const double slide = u.dot(D.translation());
  const Eigen::Vector3d across = D.translation() - slide * u;
  const Eigen::Matrix3d A = Eigen::Matrix3d::Identity() - D.linear();
  const Eigen::Vector3d centre = A.completeOrthogonalDecomposition().solve(across);
  const auto at = [&](double t) {
    Eigen::Isometry3d M = Eigen::Isometry3d::Identity();
    M.linear() = Eigen::AngleAxisd(t * turn.angle(), u).toRotationMatrix();
    M.translation() = centre - M.linear() * centre + t * slide * u;
    return M * X1;
  };
  const Eigen::Vector3d offset = X1.translation() - centre;
  const double arm = (offset - u.dot(offset) * u).norm() + robotRadius(c);
  return denseFirstContact(c, at, std::abs(slide) + turn.angle() * arm, min_step);
}

}  // namespace mddual::soundness
