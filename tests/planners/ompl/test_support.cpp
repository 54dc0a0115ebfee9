#include "test_support.h"

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include "mddual/brute_force.h"
#include "mddual/generators.h"

namespace mddual::planning::testing {
namespace {

namespace ob = ompl::base;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

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

void randomState(const PlanningSpace& space, Rng& rng, ob::State* state) {
  const Eigen::AlignedBox3d& b = space.bounds();
  auto u = [&](int k) { return std::uniform_real_distribution<double>(b.min()[k], b.max()[k])(rng); };
  switch (space.kind()) {
    case SpaceKind::kSE2: {
      auto* s = state->as<ob::SE2StateSpace::StateType>();
      s->setXY(u(0), u(1));
      s->setYaw(-std::uniform_real_distribution<double>(-kPi, kPi)(rng));  // (-pi, pi]
      break;
    }
    case SpaceKind::kSE3: {
      auto* s = state->as<ob::SE3StateSpace::StateType>();
      s->setXYZ(u(0), u(1), u(2));
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
    X.linear() = Eigen::AngleAxisd(std::uniform_real_distribution<double>(0.0, max_angle)(rng),
                                   generators::randomUnitVector(rng))
                     .toRotationMatrix() *
                 X.linear();
  }
  space.stateSpace()->copyState(s2, s1);
  space.setPose(X, s2);
}

double distanceToTouching(const MddScene& scene, const Eigen::Isometry3d& X_WR, double margin) {
  double best = kInf;
  std::vector<int> candidates;
  for (const scene::Piece& piece : scene.robot().pieces()) {
    Eigen::AlignedBox3d box = scene::transformedBox(piece.box, X_WR);
    box.min().array() -= margin;
    box.max().array() += margin;
    candidates.clear();
    scene.world().candidates(box, &candidates);
    for (int j : candidates) {
      const scene::Piece& obstacle = scene.world().pieces()[static_cast<std::size_t>(j)];
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

}  // namespace mddual::planning::testing
