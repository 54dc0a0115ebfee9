#include "test_support.h"

#include <gtest/gtest.h>

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "mddual/brute_force.h"
#include "mddual/generators.h"
#include "mddual/scene/loaders.h"
#include "mddual/scene/problem_config.h"

namespace mddual::planning::testing {
namespace {

namespace ob = ompl::base;
/// checkEdge's dense FCL check: the sample step, as a fraction of the edge.
constexpr double kDenseEdgeStep = 1e-4;

long envInt(const char* name, long fallback) {
  const char* v = std::getenv(name);
  if (!v || !*v) return fallback;
  return std::strtol(v, nullptr, 10);
}

/// Distance from the origin to the convex polygon `loop` of polytope p (frame
/// of p).
double originToFace(const ConvexPolytope& p, int f) {
  const IndexRange loop = p.faceVertices(f);
  const Eigen::Vector3d& n = p.faceNormal(f);
  const Eigen::Vector3d q = -(n.dot(-p.vertex(loop[0]))) * n;  // projection of the origin on the plane
  bool inside = true;
  double best = kInf;
  for (int k = 0; k < loop.size(); ++k) {
    const Eigen::Vector3d& a = p.vertex(loop[k]);
    const Eigen::Vector3d& b = p.vertex(loop[(k + 1) % loop.size()]);
    if ((b - a).cross(q - a).dot(n) < 0.0) inside = false;
    const double s = std::clamp((-a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + s * (b - a)).norm());
  }
  return inside ? std::abs(n.dot(p.vertex(loop[0]))) : best;
}

/// The first FCL-invalid fraction near `f` (to the right), or +inf.
double fclInvalidNear(const Fixture& fx, const ob::State* s1, const ob::State* s2, double f) {
  for (double eps = 1e-11; eps <= 1e-4; eps *= 4.0) {
    const double t = std::min(1.0, f + eps);
    if (!fclValidAt(fx, s1, s2, t)) return t;
    if (t == 1.0) break;
  }
  return kInf;
}

}  // namespace

int scale() {
  return static_cast<int>(std::max(1L, envInt("MDDUAL_PLANNING_SCALE", 1)));
}
std::uint64_t seed() {
  return static_cast<std::uint64_t>(envInt("MDDUAL_PLANNING_SEED", 1));
}

Fixture makeFixture(const examples::ExampleScene& scene, SpaceKind kind, const MddSceneOptions& options) {
  Fixture fx;
  fx.scene = scene;
  fx.space = examples::makeSpace(scene, kind);
  fx.mdd = std::make_shared<MddScene>(scene.robot, scene.world, options);
  fx.fcl = std::make_shared<FclScene>(scene.robot, scene.world);
  fx.si = std::make_shared<ob::SpaceInformation>(fx.space->stateSpace());
  fx.mdd_checker = std::make_shared<MddStateValidityChecker>(fx.si, fx.space, fx.mdd);
  fx.mdd_motion = std::make_shared<MddMotionValidator>(fx.si, fx.space, fx.mdd);
  fx.si->setStateValidityChecker(fx.mdd_checker);
  fx.si->setMotionValidator(fx.mdd_motion);
  fx.si->setup();
  fx.fcl_si = std::make_shared<ob::SpaceInformation>(fx.space->stateSpace());
  fx.fcl_checker = std::make_shared<FclStateValidityChecker>(fx.fcl_si, fx.space, fx.fcl);
  fx.fcl_si->setStateValidityChecker(fx.fcl_checker);
  fx.fcl_si->setMotionValidator(std::make_shared<ob::DiscreteMotionValidator>(fx.fcl_si));
  fx.fcl_si->setup();
  return fx;
}

std::vector<examples::ExampleScene> standardScenes(std::uint64_t s) {
  return {examples::primitivesScene(s), examples::meshScene(s), examples::planarScene(s), examples::blobScene(s)};
}

namespace {

namespace fs = std::filesystem;

fs::path scratchDir() {
  const fs::path dir = fs::temp_directory_path() / ("mddual_planning_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

void writeFile(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

std::string urdfOrigin(const Eigen::Vector3d& p, const Eigen::Vector3d& rpy) {
  std::ostringstream o;
  o.precision(17);
  o << "<origin xyz=\"" << p.x() << " " << p.y() << " " << p.z() << "\" rpy=\"" << rpy.x() << " " << rpy.y() << " "
    << rpy.z() << "\"/>";
  return o.str();
}

/// URDF of one link with the given collision elements.
std::string urdf(const std::string& name, const std::vector<std::string>& collisions) {
  std::string text = "<?xml version=\"1.0\"?>\n<robot name=\"" + name + "\">\n  <link name=\"base\">\n";
  for (const std::string& c : collisions) text += "    <collision>" + c + "</collision>\n";
  return text + "  </link>\n</robot>\n";
}

/// OBJ text of the triangles of L-shaped prisms (non-convex), one per pose.
std::string lPrismsObj(const std::vector<Eigen::Isometry3d>& poses, double size) {
  const std::vector<Eigen::Vector2d> ell{{0, 0}, {2, 0}, {2, 0.7}, {0.7, 0.7}, {0.7, 2}, {0, 2}};
  std::ostringstream o;
  o.precision(17);
  int base = 1;
  for (const Eigen::Isometry3d& X : poses) {
    const int k = static_cast<int>(ell.size());
    for (const double z : {-0.4, 0.4}) {
      for (const Eigen::Vector2d& q : ell) {
        const Eigen::Vector3d v = X * (size * Eigen::Vector3d(q.x() - 0.7, q.y() - 0.7, z));
        o << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
      }
    }
    // Caps as fans from the reflex corner (vertex 3 sees every other vertex),
    // then the side quads.
    for (int j = 4; j < k + 3; ++j) {
      const int a = 3;
      const int b = j % k;
      const int c = (j + 1) % k;
      if (b == a || c == a) continue;
      o << "f " << base + a << " " << base + c << " " << base + b << "\n";
      o << "f " << base + k + a << " " << base + k + b << " " << base + k + c << "\n";
    }
    for (int j = 0; j < k; ++j) {
      const int a = j;
      const int b = (j + 1) % k;
      o << "f " << base + a << " " << base + b << " " << base + k + b << "\n";
      o << "f " << base + a << " " << base + k + b << " " << base + k + a << "\n";
    }
    base += 2 * k;
  }
  return o.str();
}

examples::ExampleScene fromFiles(const std::string& name, scene::RigidBody robot, scene::World world,
                                 const Eigen::AlignedBox3d& bounds, SpaceKind kind) {
  examples::ExampleScene s;
  s.name = name;
  s.robot = std::make_shared<scene::RigidBody>(std::move(robot));
  s.world = std::make_shared<scene::World>(std::move(world));
  s.bounds = bounds;
  s.kind = kind;
  return s;
}

}  // namespace

examples::ExampleScene configScene(const std::string& name) {
  const scene::ProblemConfig config =
      scene::readProblemConfig(fs::path(MDDUAL_CONFIGS_DIR) / name / (name + ".cfg"), {"mdd_rrtconnect"});
  scene::ProblemScene p = scene::loadProblemScene(config);
  const SpaceKind kind = p.space == scene::SpaceKind::kSE2 ? SpaceKind::kSE2 : SpaceKind::kSE3;
  return fromFiles(name, std::move(p.robot), std::move(p.world), p.bounds, kind);
}

std::vector<examples::ExampleScene> fileScenes(std::uint64_t s) {
  Rng rng(s * 7919 + 11);
  auto u = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  const fs::path dir = scratchDir();
  // (a) URDF primitives: boxes, cylinders and spheres at random poses.
  std::vector<std::string> obstacles;
  for (int i = 0; i < 45; ++i) {
    const Eigen::Vector3d p = generators::drawVector(std::uniform_real_distribution<double>(0, 10), rng);
    // yaw, pitch, roll: the order GCC evaluated the constructor's arguments
    // (C++ leaves it unspecified), kept so the seeded scenes stay as they were.
    const double yaw = u(-3, 3);
    const double pitch = u(-1.5, 1.5);
    const double roll = u(-3, 3);
    const Eigen::Vector3d rpy(roll, pitch, yaw);
    std::ostringstream g;
    if (i % 3 == 0) {
      g << "<geometry><box size=\"" << u(0.3, 1.8) << " " << u(0.3, 1.8) << " " << u(0.3, 1.8) << "\"/></geometry>";
    } else if (i % 3 == 1) {
      g << "<geometry><cylinder radius=\"" << u(0.2, 0.7) << "\" length=\"" << u(0.5, 2.0) << "\"/></geometry>";
    } else {
      g << "<geometry><sphere radius=\"" << u(0.2, 0.8) << "\"/></geometry>";
    }
    obstacles.push_back(urdfOrigin(p, rpy) + g.str());
  }
  writeFile(dir / "world.urdf", urdf("primitives_world", obstacles));
  writeFile(
      dir / "robot.urdf",
      urdf("primitives_robot",
           {urdfOrigin({0, 0, 0}, {0, 0, 0}) + "<geometry><box size=\"0.6 0.4 0.3\"/></geometry>",
            urdfOrigin({0, 0, 0.35}, {0, 0, 0}) + "<geometry><cylinder radius=\"0.15\" length=\"0.4\"/></geometry>",
            urdfOrigin({0.35, 0, 0}, {0, 0, 0}) + "<geometry><sphere radius=\"0.15\"/></geometry>"}));
  const Eigen::AlignedBox3d cube(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(10.0));
  // Curved primitives circumscribed within 1 cm (the default 1 mm gives
  // spheres of thousands of vertices, too heavy for the brute-force measures).
  scene::LoadOptions coarse;
  coarse.primitive_tolerance = 0.01;
  examples::ExampleScene urdf_scene = fromFiles("urdf", scene::loadBody(dir / "robot.urdf", coarse),
                                                scene::loadWorld(dir / "world.urdf", coarse), cube, SpaceKind::kSE3);
  // (b) A non-convex OBJ world and robot: both become triangles.
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < 25; ++i) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = generators::randomRotation(rng);
    X.translation() = generators::drawVector(std::uniform_real_distribution<double>(0, 10), rng);
    poses.push_back(X);
  }
  writeFile(dir / "world.obj", lPrismsObj(poses, 1.2));
  writeFile(dir / "robot.obj", lPrismsObj({Eigen::Isometry3d::Identity()}, 0.35));
  examples::ExampleScene mesh_scene = fromFiles("meshfile", scene::loadBody(dir / "robot.obj"),
                                                scene::loadWorld(dir / "world.obj"), cube, SpaceKind::kSE3);
  return {urdf_scene, mesh_scene, configScene("maze_se2"), configScene("cubicles")};
}

const std::vector<examples::ExampleScene>& allScenes() {
  static const std::vector<examples::ExampleScene> scenes = [] {
    std::vector<examples::ExampleScene> all = standardScenes(seed());
    for (examples::ExampleScene& f : fileScenes(seed())) all.push_back(std::move(f));
    all.push_back(examples::trapScene());
    return all;
  }();
  return scenes;
}

std::string sceneName(int index) {
  static const char* kNames[] = {"primitives", "mesh",     "planar",   "blobs", "urdf",
                                 "meshfile",   "maze_se2", "cubicles", "trap"};
  return kNames[index];
}

void randomState(const PlanningSpace& space, Rng& rng, ob::State* state) {
  const Eigen::AlignedBox3d& b = space.bounds();
  auto u = [&](int k) { return std::uniform_real_distribution<double>(b.min()[k], b.max()[k])(rng); };
  // Coordinates drawn last first: the order GCC evaluated the setters'
  // arguments (C++ leaves it unspecified), kept so seeded states stay.
  switch (space.kind()) {
    case SpaceKind::kSE2: {
      auto* s = state->as<ob::SE2StateSpace::StateType>();
      const double y = u(1);
      const double x = u(0);
      s->setXY(x, y);
      s->setYaw(-std::uniform_real_distribution<double>(-kPi, kPi)(rng));  // (-pi, pi]
      break;
    }
    case SpaceKind::kSE3: {
      auto* s = state->as<ob::SE3StateSpace::StateType>();
      const double z = u(2);
      const double y = u(1);
      const double x = u(0);
      s->setXYZ(x, y, z);
      const Eigen::Quaterniond q(generators::randomRotation(rng));
      s->rotation().x = q.x();
      s->rotation().y = q.y();
      s->rotation().z = q.z();
      s->rotation().w = q.w();
      break;
    }
    case SpaceKind::kR2:
    case SpaceKind::kR3: {
      double* v = state->as<ob::RealVectorStateSpace::StateType>()->values;
      v[0] = u(0);
      v[1] = u(1);
      if (space.kind() == SpaceKind::kR3) v[2] = u(2);
      break;
    }
  }
}

void randomValidState(const ob::SpaceInformation& si, const PlanningSpace& space, Rng& rng, ob::State* state) {
  do {
    randomState(space, rng, state);
  } while (!si.isValid(state));
}

void randomEdgeEnd(const PlanningSpace& space, const ob::State* s1, double max_length, bool rotate, double max_angle,
                   Rng& rng, ob::State* s2) {
  Eigen::Isometry3d X = space.pose(s1);
  Eigen::Vector3d d = generators::randomUnitVector(rng);
  if (space.kind() == SpaceKind::kSE2 || space.kind() == SpaceKind::kR2) d.z() = 0.0;
  if (d.norm() < 1e-6) d = Eigen::Vector3d::UnitX();
  d.normalize();
  X.translation() += std::uniform_real_distribution<double>(0.0, max_length)(rng) * d;
  if (rotate && space.kind() == SpaceKind::kSE2) {
    X.linear() =
        Eigen::AngleAxisd(std::uniform_real_distribution<double>(-max_angle, max_angle)(rng), Eigen::Vector3d::UnitZ())
            .toRotationMatrix() *
        X.linear();
  } else if (rotate && space.kind() == SpaceKind::kSE3) {
    // The axis before the angle, as GCC evaluated the constructor's arguments.
    const Eigen::Vector3d axis = generators::randomUnitVector(rng);
    const double angle = std::uniform_real_distribution<double>(0.0, max_angle)(rng);
    X.linear() = Eigen::AngleAxisd(angle, axis).toRotationMatrix() * X.linear();
  }
  space.stateSpace()->copyState(s2, s1);
  space.setPose(X, s2);
}

double distanceToTouching(const MddScene& scene, const Eigen::Isometry3d& X_WR, double margin) {
  double best = kInf;
  std::vector<int> candidates;
  for (const scene::Piece& piece : scene.robot().pieces()) {
    const Eigen::AlignedBox3d box_W = scene::transformedBox(piece.box, X_WR);
    const Eigen::Vector3d c_W = X_WR * piece.centre;
    Eigen::AlignedBox3d box = box_W;
    box.min().array() -= margin;
    box.max().array() += margin;
    candidates.clear();
    scene.world().candidates(box, &candidates);
    for (int j : candidates) {
      const scene::Piece& obstacle = scene.world().pieces()[static_cast<std::size_t>(j)];
      // The spheres' and the boxes' gaps bound a separated pair's distance
      // from below: a pair whose sphere gap or box gap exceeds `margin` is
      // skipped (the candidates' box test grows the box per axis, which keeps
      // pairs up to sqrt(3) margin apart across its corners).
      const double sphere_gap = (c_W - obstacle.centre).norm() - piece.radius - obstacle.radius;
      if (sphere_gap > margin || box_W.exteriorDistance(obstacle.box) > margin) continue;
      const MinkowskiDifference m =
          MinkowskiDifference::build(obstacle.polytope, Eigen::Isometry3d::Identity(), piece.polytope, X_WR);
      for (int f = 0; f < m.polytope.numFaces(); ++f) best = std::min(best, originToFace(m.polytope, f));
    }
  }
  return best;
}

double touchTolerance(const MddScene& scene, const Eigen::Isometry3d& X_WR) {
  return 1e-9 * (1.0 + scene.robot().radius() + X_WR.translation().norm());
}

bool fclValidAt(const Fixture& fx, const ob::State* s1, const ob::State* s2, double t) {
  ob::ScopedState<> state(fx.space->stateSpace());
  fx.space->stateSpace()->interpolate(s1, s2, t, state.get());
  return fx.fcl_si->isValid(state.get());
}

double denseFirstInvalid(const Fixture& fx, const ob::State* s1, const ob::State* s2, double from, double step,
                         int* samples) {
  const EdgeMotion m = fx.space->motion(s1, s2);
  const double speed = m.length() + m.angle * fx.scene.robot->radius();
  ob::ScopedState<> state(fx.space->stateSpace());
  double t = from;
  int n = 0;
  while (true) {
    fx.space->stateSpace()->interpolate(s1, s2, t, state.get());
    ++n;
    if (!fx.fcl_si->isValid(state.get())) {
      if (samples) *samples += n;
      return t;
    }
    if (t >= 1.0) break;
    double advance = step;
    if (speed > 0.0) {
      const Eigen::Isometry3d X = fx.space->pose(state.get());
      const double d = fx.fcl->distance(X);
      // Distance to the position bounds (the edge leaves them at most that fast).
      const Eigen::AlignedBox3d& b = fx.space->bounds();
      const int dims = (fx.space->kind() == SpaceKind::kSE2 || fx.space->kind() == SpaceKind::kR2) ? 2 : 3;
      double db = kInf;
      for (int k = 0; k < dims; ++k) {
        db = std::min({db, X.translation()[k] - b.min()[k], b.max()[k] - X.translation()[k]});
      }
      double skip = d / speed;
      if (m.length() > 0.0) skip = std::min(skip, db / m.length());
      advance = std::max(step, 0.5 * skip);
    }
    t = std::min(1.0, t + advance);
  }
  if (samples) *samples += n;
  return kInf;
}

double fclBisect(const Fixture& fx, const ob::State* s1, const ob::State* s2, double lo, double hi, double width) {
  while (hi - lo > width) {
    const double mid = 0.5 * (lo + hi);
    if (fclValidAt(fx, s1, s2, mid)) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return hi;
}

std::string describe(const EdgeTally& t) {
  char line[480];
  std::snprintf(line, sizeof line,
                "edges: %d, valid %d, misses %d, early %d, fractions checked %d (errors %d, grazing %d, FCL late %d, "
                "worst %.2e), rotating false alarms %d, lastValid by the first step %d (%d below the search's bound), "
                "FCL samples %d",
                t.edges, t.valid, t.misses, t.early, t.fraction_checked, t.fraction_errors, t.grazing, t.fcl_late,
                t.worst_fraction_error, t.false_alarms, t.first_step, t.first_step_below_bound, t.samples);
  return line;
}

std::string edgeString(const Fixture& fx, const ob::State* s1, const ob::State* s2) {
  std::ostringstream o;
  o.precision(17);
  o << "\n  edge (" << toString(fx.space->kind()) << ", x y z qw qx qy qz):";
  for (const ob::State* s : {s1, s2}) {
    const Eigen::Isometry3d X = fx.space->pose(s);
    const Eigen::Quaterniond q(X.linear());
    o << "\n    " << X.translation().x() << " " << X.translation().y() << " " << X.translation().z() << " " << q.w()
      << " " << q.x() << " " << q.y() << " " << q.z();
  }
  return o.str();
}

void checkEdge(const Fixture& fx, const ob::State* s1, const ob::State* s2, EdgeTally* tally) {
  ++tally->edges;
  const MddMotionValidator& mv = *fx.mdd_motion;
  const bool valid = mv.checkMotion(s1, s2);
  ob::ScopedState<> last(fx.space->stateSpace());
  std::pair<ob::State*, double> lv(last.get(), -1.0);
  EXPECT_EQ(mv.checkMotion(s1, s2, lv), valid) << fx.scene.name << " edge " << tally->edges << edgeString(fx, s1, s2);
  const EdgeMotion motion = fx.space->motion(s1, s2);
  if (valid) {
    ++tally->valid;
    EXPECT_EQ(lv.second, -1.0) << "lastValid touched on a valid edge" << edgeString(fx, s1, s2);
    const double t = denseFirstInvalid(fx, s1, s2, 0.0, kDenseEdgeStep, &tally->samples);
    if (t != kInf) {
      ob::ScopedState<> st(fx.space->stateSpace());
      fx.space->stateSpace()->interpolate(s1, s2, t, st.get());
      const Eigen::Isometry3d X = fx.space->pose(st.get());
      const double d = distanceToTouching(*fx.mdd, X, 1e-6);
      if (d > touchTolerance(*fx.mdd, X)) {
        ++tally->misses;
        ADD_FAILURE() << fx.scene.name << ": MISS, edge valid for MDD but FCL collides at t = " << t
                      << " (distance to touching " << d << ", rotates " << motion.rotates() << ")"
                      << edgeString(fx, s1, s2);
      }
    }
    return;
  }
  // Invalid: lastValid is a valid state before the first invalid fraction
  // (lastValid's own bound: EdgeQuery::kLastValid; on translation edges at
  // most one discrete step, its tolerance, before kFirstContact's exact
  // contact, and equal to it when marked exact; another lower bound on
  // rotating ones).
  const EdgeContact first = mv.firstInvalid(s1, s2);
  const EdgeContact bound = mv.firstInvalid(s1, s2, EdgeQuery::kLastValid);
  ASSERT_TRUE(first.collides);
  ASSERT_TRUE(bound.collides);
  // One step of OMPL's discrete check of the edge (validSegmentCount asserts
  // on rotations out of their bounds: no step there, as in the validator).
  const double step =
      fx.space->rotationsWithinBounds(s2) ? 1.0 / std::max(1u, fx.si->getStateSpace()->validSegmentCount(s1, s2)) : 1.0;
  if (!motion.rotates()) {
    EXPECT_LE(bound.fraction, first.fraction) << edgeString(fx, s1, s2);
    EXPECT_GE(bound.fraction, first.fraction - step - 1e-12) << edgeString(fx, s1, s2);
    if (bound.exact) {
      EXPECT_EQ(bound.fraction, first.fraction) << edgeString(fx, s1, s2);
    }
  }
  EXPECT_GE(lv.second, 0.0) << edgeString(fx, s1, s2);
  EXPECT_LE(lv.second, bound.fraction) << edgeString(fx, s1, s2);
  EXPECT_TRUE(fx.si->isValid(last.get())) << "lastValid is not valid" << edgeString(fx, s1, s2);
  // The first-step shortcut: on a rotating edge whose state one discrete
  // step in collides, (s1, 0), within that step of the first contact (which
  // the first-contact search must then find within the step too).
  // Otherwise lastValid is the kLastValid search's bound, backed off.
  const bool first_step = motion.rotates() && mv.discardedLastValidFraction() == 0.0 && step < 1.0 &&
                          lv.second == 0.0 && fx.mdd->collides(motion.pose(step));
  if (first_step) {
    ++tally->first_step;
    tally->first_step_below_bound += bound.fraction > 1e-3 ? 1 : 0;
    EXPECT_LE(first.fraction, step + 1e-12)
        << "lastValid 0 by the first step, the first contact later" << edgeString(fx, s1, s2);
  } else if (lv.second < bound.fraction) {
    EXPECT_LE(bound.fraction - lv.second, 1e-3)
        << "lastValid backed off far (" << lv.second << " vs " << bound.fraction << ")" << edgeString(fx, s1, s2);
  }
  if (first.start_collides) return;
  // No FCL-invalid state before either bound of the first invalid fraction
  // (exact or a bound).
  const double t_fcl = denseFirstInvalid(fx, s1, s2, 0.0, kDenseEdgeStep, &tally->samples);
  if (t_fcl < std::max(first.fraction, bound.fraction) - 1e-9) {
    ob::ScopedState<> st(fx.space->stateSpace());
    fx.space->stateSpace()->interpolate(s1, s2, t_fcl, st.get());
    const Eigen::Isometry3d X = fx.space->pose(st.get());
    if (distanceToTouching(*fx.mdd, X, 1e-6) > touchTolerance(*fx.mdd, X)) {
      ++tally->early;
      ADD_FAILURE() << fx.scene.name << ": FCL collides at t = " << t_fcl << " before our first contact "
                    << first.fraction << " or lastValid's bound " << bound.fraction << " (rotates " << motion.rotates()
                    << ")" << edgeString(fx, s1, s2);
    }
    return;
  }
  if (motion.rotates()) {
    if (t_fcl == kInf) ++tally->false_alarms;
    return;
  }
  // Translation edge: the exact fraction against an FCL bisection.
  ++tally->fraction_checked;
  double hi = fclInvalidNear(fx, s1, s2, first.fraction);
  if (hi == kInf) {
    // FCL sees no collision just after our contact: a grazing touch. Check it
    // is one on the brute force.
    const Eigen::Isometry3d X = motion.pose(first.fraction);
    const double d = first.contact.robot_piece < 0 ? 0.0 : distanceToTouching(*fx.mdd, X, 1e-6);
    if (d <= 10 * touchTolerance(*fx.mdd, X)) {
      ++tally->grazing;
    } else {
      ++tally->fraction_errors;
      ADD_FAILURE() << fx.scene.name << ": no FCL collision after our first contact " << first.fraction
                    << " (distance to touching there " << d << ")" << edgeString(fx, s1, s2);
    }
    return;
  }
  const double lo = std::max(0.0, first.fraction - 1e-6);
  if (!fclValidAt(fx, s1, s2, lo)) {
    ++tally->fraction_errors;
    ADD_FAILURE() << fx.scene.name << ": FCL invalid at " << lo << " before our first contact " << first.fraction
                  << edgeString(fx, s1, s2);
    return;
  }
  const double f_fcl = fclBisect(fx, s1, s2, lo, hi, 1e-13);
  const double err = std::abs(f_fcl - first.fraction);
  if (err > 1e-9 && f_fcl > first.fraction) {
    // FCL's intersection test can miss a penetration of a few 1e-7 (a pinned
    // case in test_motion): FCL later than us is FCL late when the brute
    // force has us touching at our fraction (FCL is free just before it).
    const Eigen::Isometry3d X = motion.pose(first.fraction);
    if (distanceToTouching(*fx.mdd, X, 1e-6) <= 10 * touchTolerance(*fx.mdd, X)) {
      ++tally->fcl_late;
      return;
    }
  }
  tally->worst_fraction_error = std::max(tally->worst_fraction_error, err);
  if (err > 1e-9) {
    ++tally->fraction_errors;
    ADD_FAILURE() << fx.scene.name << ": first contact " << first.fraction << ", FCL bisection " << f_fcl
                  << edgeString(fx, s1, s2);
  }
}

}  // namespace mddual::planning::testing
