#include "mddual/planning/path_verifier.h"

#include <ompl/base/ScopedState.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "mddual/brute_force.h"
#include "mddual/error.h"

namespace mddual::planning {

namespace ob = ompl::base;

namespace {

/// OMPL's default longest_valid_segment_fraction.
constexpr double kOmplDefaultSegmentFraction = 0.01;
/// Check (b) asks FCL's distance only where it pays: a distance query costs
/// about 10-15 collide() calls on mesh scenes (apartment: 16 ms against 1.2
/// ms), so when the last distance let the sampling skip fewer than this many
/// steps, the next kDenseRun samples are checked with collide() alone, at
/// every step (the check's baseline resolution, so no state it would have
/// sampled is left out).
constexpr double kDistancePaysSteps = 16.0;
constexpr int kDenseRun = 32;

MddSceneOptions strictOptions(const scene::RigidBody& robot, const VerifierOptions& o) {
  MddSceneOptions m;
  m.refinement_levels = o.refinement_levels;
  m.rotation_tolerance = o.rotation_tolerance_rel * std::ldexp(1.0, o.refinement_levels) * robot.radius();
  return m;
}

}  // namespace

PathVerifier::PathVerifier(std::shared_ptr<const scene::RigidBody> robot, std::shared_ptr<const scene::World> world,
                           const Eigen::AlignedBox3d& bounds, const VerifierOptions& options)
    : robot_(std::move(robot)), world_(std::move(world)), bounds_(bounds), options_(options) {
  if (!robot_ || !world_) throw InvalidInputError("PathVerifier: null robot or world");
  if (!(options_.rotation_tolerance_rel >= 1e-6) || options_.refinement_levels < 0 || options_.refinement_levels > 8 ||
      !(options_.resolution_divisor >= 1.0) || !(options_.penetration_tolerance_rel >= 0.0)) {
    throw InvalidInputError("PathVerifier: options out of range");
  }
  if (bounds.isEmpty()) throw InvalidInputError("PathVerifier: empty bounds");
  mdd_ = std::make_shared<MddScene>(robot_, world_, strictOptions(*robot_, options_));
  fcl_ = std::make_shared<FclScene>(robot_, world_);
  step_ = kOmplDefaultSegmentFraction * bounds.diagonal().norm() / options_.resolution_divisor;
  if (!(step_ > 0.0)) throw InvalidInputError("PathVerifier: the bounds have no extent");
}

bool PathVerifier::bruteForcePenetrates(const Eigen::Isometry3d& X_WR) const {
  const double tol = options_.penetration_tolerance_rel * (1.0 + robot_->radius() + X_WR.translation().norm());
  std::vector<int> candidates;
  for (const scene::Piece& piece : robot_->pieces()) {
    candidates.clear();
    world_->candidates(scene::transformedBox(piece.box, X_WR), &candidates);
    for (int j : candidates) {
      const scene::Piece& obstacle = world_->pieces()[static_cast<std::size_t>(j)];
      const MinkowskiDifference m =
          MinkowskiDifference::build(obstacle.polytope, Eigen::Isometry3d::Identity(), piece.polytope, X_WR);
      // The origin lies in M = A - B (A and B overlap) at depth min_f h_f when
      // every face offset is positive (M = {x : n_f . x <= h_f}).
      double depth = std::numeric_limits<double>::infinity();
      for (int f = 0; f < m.polytope.numFaces(); ++f) depth = std::min(depth, m.polytope.faceOffset(f));
      if (depth > tol) return true;
    }
  }
  return false;
}

double PathVerifier::denseFcl(const PlanningSpace& space, const ob::State* s1, const ob::State* s2, ob::State* work,
                              VerifyResult* result) const {
  const Eigen::Isometry3d X1 = space.pose(s1);
  const Eigen::Isometry3d X2 = space.pose(s2);
  const double angle = Eigen::AngleAxisd(X1.linear().transpose() * X2.linear()).angle();
  // Largest distance any robot point moves over the whole segment (OMPL
  // rotates the shorter way at constant speed about the body origin).
  const double speed = (X2.translation() - X1.translation()).norm() + std::abs(angle) * robot_->radius();
  const double n = std::max(1.0, std::ceil(speed / step_));
  const double min_advance = 1.0 / n;
  int dense_left = 0;  // samples still to check without a distance query
  double t = 0.0;
  while (true) {
    space.stateSpace()->interpolate(s1, s2, t, work);
    const Eigen::Isometry3d X = space.pose(work);
    ++result->fcl_samples;
    double advance = min_advance;
    if (fcl_->collides(X)) {
      if (bruteForcePenetrates(X)) return t;
      ++result->fcl_unconfirmed;
    } else if (dense_left > 0) {
      --dense_left;
    } else if (speed > 0.0) {
      const double d = fcl_->distance(X);
      if (d > 0.0 && std::isfinite(d)) advance = std::max(advance, 0.5 * d / speed);
      if (std::isinf(d)) advance = 1.0;  // an empty world
      if (advance < kDistancePaysSteps * min_advance) dense_left = kDenseRun;
    }
    if (t >= 1.0) break;
    t = std::min(1.0, t + advance);
  }
  return -1.0;
}

VerifyResult PathVerifier::verify(const PlanningSpace& space, const std::vector<const ob::State*>& states) const {
  const auto start = std::chrono::steady_clock::now();
  VerifyResult r;
  // The problem's position bounds (x and y for the planar kinds), whatever
  // the bounds of the space the path comes from.
  const bool planar = space.kind() == SpaceKind::kSE2 || space.kind() == SpaceKind::kR2;
  for (const ob::State* s : states) {
    const Eigen::Vector3d p = space.pose(s).translation();
    for (int k = 0; k < (planar ? 2 : 3); ++k) {
      if (!(p[k] >= bounds_.min()[k] && p[k] <= bounds_.max()[k])) r.out_of_bounds = true;
    }
  }
  // (a) exact MDD edge check (a one-state path: that state).
  if (states.size() == 1) {
    int queries = 0;
    if (mdd_->collides(space.pose(states[0]), &queries)) {
      r.mdd_collision = true;
      r.mdd_segment = 0;
    }
    r.mdd_pair_queries += queries;
  }
  for (std::size_t i = 0; i + 1 < states.size(); ++i) {
    const EdgeContact c = mdd_->checkEdge(space.motion(states[i], states[i + 1]), /*first_contact=*/false);
    r.mdd_pair_queries += c.pair_queries;
    if (c.collides) {
      r.mdd_collision = true;
      r.mdd_segment = static_cast<int>(i);
      break;
    }
  }
  const auto mdd_end = std::chrono::steady_clock::now();
  r.mdd_seconds = std::chrono::duration<double>(mdd_end - start).count();
  // (b) dense FCL check, the states themselves first (OMPL's SO(3)
  // interpolation may not end exactly at s2).
  if (!r.mdd_collision || options_.always_run_both) {
    for (std::size_t i = 0; i < states.size() && !r.fcl_collision; ++i) {
      const Eigen::Isometry3d X = space.pose(states[i]);
      ++r.fcl_samples;
      if (fcl_->collides(X)) {
        if (bruteForcePenetrates(X)) {
          r.fcl_collision = true;
          r.fcl_segment = static_cast<int>(i == 0 ? 0 : i - 1);
          r.fcl_fraction = i == 0 ? 0.0 : 1.0;
        } else {
          ++r.fcl_unconfirmed;
        }
      }
    }
    ob::ScopedState<> work(space.stateSpace());
    for (std::size_t i = 0; i + 1 < states.size() && !r.fcl_collision; ++i) {
      const double t = denseFcl(space, states[i], states[i + 1], work.get(), &r);
      if (t >= 0.0) {
        r.fcl_collision = true;
        r.fcl_segment = static_cast<int>(i);
        r.fcl_fraction = t;
      }
    }
  }
  r.valid = !r.mdd_collision && !r.fcl_collision && !r.out_of_bounds;
  const auto end = std::chrono::steady_clock::now();
  r.fcl_seconds = std::chrono::duration<double>(end - mdd_end).count();
  r.seconds = std::chrono::duration<double>(end - start).count();
  return r;
}

VerifyResult PathVerifier::verify(const PlanningSpace& space, const ompl::geometric::PathGeometric& path) const {
  std::vector<const ob::State*> states;
  states.reserve(path.getStateCount());
  for (std::size_t i = 0; i < path.getStateCount(); ++i) states.push_back(path.getState(static_cast<unsigned>(i)));
  return verify(space, states);
}

}  // namespace mddual::planning
