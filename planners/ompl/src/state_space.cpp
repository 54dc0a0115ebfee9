#include "mddual/planning/state_space.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>
#include <ompl/base/spaces/SO3StateSpace.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include "constants.h"
#include "mddual/error.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;

using detail::kInf;
/// OMPL's MAX_QUATERNION_NORM_ERROR (SO3StateSpace.cpp): below 1 - this, the
/// slerp of SO3StateSpace::interpolate is replaced by a copy of the start.
constexpr double kOmplQuaternionTolerance = 1e-9;
/// Below this |q1 . q2| (a half-turn within about 2e-12 rad), the way OMPL's
/// slerp turns is read from its own midpoint, not from the dot's sign: the
/// dot of a half-turn is round-off, which another build of OMPL could round
/// differently.
constexpr double kHalfTurnDotAmbiguity = 1e-12;
/// setPose(): how far a pose may be from the space's poses (rotation matrix
/// entries, and z relative to 1 + |p|).
constexpr double kPoseTolerance = 1e-9;

std::string str(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out.precision(17);
  out << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return out.str();
}

void checkBounds(const Eigen::AlignedBox3d& bounds, int dims, const std::string& who = "PlanningSpace") {
  for (int k = 0; k < dims; ++k) {
    const double lo = bounds.min()[k];
    const double hi = bounds.max()[k];
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) {
      throw InvalidInputError(who + ": position bounds " + str(bounds.min()) + " to " + str(bounds.max()) +
                              " are empty or not finite along axis " + std::to_string(k) + " (need min < max)");
    }
  }
}

/// The first t at which a + t (b - a) leaves [lo, hi] (+inf when b is inside,
/// with RealVectorStateSpace::satisfiesBounds's epsilon slack).
double axisExit(double lo, double hi, double a, double b) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const double d = b - a;
  if (d > 0.0 && b - eps > hi) return (hi + eps - a) / d;
  if (d < 0.0 && b + eps < lo) return (lo - eps - a) / d;
  return kInf;
}

// ---- Layouts of user-made spaces (PlanningSpace::wrap) ----------------------------

/// Whether `space` can be a pose part, and of which kind.
bool poseKindOf(const ob::StateSpace& space, SpaceKind* kind) {
  if (dynamic_cast<const ob::SE2StateSpace*>(&space)) {
    *kind = SpaceKind::kSE2;
    return true;
  }
  if (dynamic_cast<const ob::SE3StateSpace*>(&space)) {
    *kind = SpaceKind::kSE3;
    return true;
  }
  if (const auto* rv = dynamic_cast<const ob::RealVectorStateSpace*>(&space)) {
    if (rv->getDimension() == 2 || rv->getDimension() == 3) {
      *kind = rv->getDimension() == 2 ? SpaceKind::kR2 : SpaceKind::kR3;
      return true;
    }
  }
  return false;
}

bool rotatingKind(SpaceKind kind) {
  return kind == SpaceKind::kSE2 || kind == SpaceKind::kSE3;
}

/// "'name' (what it is)" for messages.
std::string describe(const ob::StateSpace& space) {
  std::string what;
  if (dynamic_cast<const ob::SE2StateSpace*>(&space)) {
    what = "SE2StateSpace";
  } else if (dynamic_cast<const ob::SE3StateSpace*>(&space)) {
    what = "SE3StateSpace";
  } else if (const auto* rv = dynamic_cast<const ob::RealVectorStateSpace*>(&space)) {
    what = "RealVectorStateSpace of dimension " + std::to_string(rv->getDimension());
  } else if (dynamic_cast<const ob::SO2StateSpace*>(&space)) {
    what = "SO2StateSpace";
  } else if (dynamic_cast<const ob::SO3StateSpace*>(&space)) {
    what = "SO3StateSpace";
  } else if (const auto* c = dynamic_cast<const ob::CompoundStateSpace*>(&space)) {
    what = "CompoundStateSpace of " + std::to_string(c->getSubspaceCount()) + " components";
  } else {
    what = "state space of OMPL type " + std::to_string(space.getType());
  }
  return "'" + space.getName() + "' (" + what + ")";
}

/// Extra components the motion validator can follow: linear (real vectors,
/// bounds exits computed) or always within bounds along an edge (SO2: OMPL
/// normalises the interpolated angle; SO3: the slerp keeps unit norm).
bool supportedExtra(const ob::StateSpace& space) {
  if (dynamic_cast<const ob::RealVectorStateSpace*>(&space) || dynamic_cast<const ob::SO2StateSpace*>(&space) ||
      dynamic_cast<const ob::SO3StateSpace*>(&space)) {
    return true;
  }
  const auto* c = dynamic_cast<const ob::CompoundStateSpace*>(&space);
  if (!c || c->getSubspaceCount() == 0) return false;
  for (unsigned int i = 0; i < c->getSubspaceCount(); ++i) {
    if (!supportedExtra(*c->getSubspace(i))) return false;
  }
  return true;
}

/// boundsExitFraction over the real-vector coordinates of an extra component.
double extraExit(const ob::StateSpace& space, const ob::State* s1, const ob::State* s2) {
  if (const auto* rv = dynamic_cast<const ob::RealVectorStateSpace*>(&space)) {
    const ob::RealVectorBounds& b = rv->getBounds();
    const double* a = s1->as<ob::RealVectorStateSpace::StateType>()->values;
    const double* e = s2->as<ob::RealVectorStateSpace::StateType>()->values;
    double exit = kInf;
    for (unsigned int k = 0; k < rv->getDimension(); ++k)
      exit = std::min(exit, axisExit(b.low[k], b.high[k], a[k], e[k]));
    return exit;
  }
  double exit = kInf;
  if (const auto* c = dynamic_cast<const ob::CompoundStateSpace*>(&space)) {
    const auto* c1 = s1->as<ob::CompoundState>();
    const auto* c2 = s2->as<ob::CompoundState>();
    for (unsigned int i = 0; i < c->getSubspaceCount(); ++i) {
      exit = std::min(exit, extraExit(*c->getSubspace(i), c1->components[i], c2->components[i]));
    }
  }
  return exit;
}

/// The pose part of a wrapped space: its index (-1: the space itself) and kind.
std::pair<int, SpaceKind> locatePosePart(const ob::StateSpace& space, const std::string& name) {
  const std::string who = "PlanningSpace::wrap: state space " + describe(space);
  SpaceKind kind = SpaceKind::kSE3;
  if (poseKindOf(space, &kind)) {
    if (!name.empty()) {
      throw InvalidInputError(who + " is itself the pose part; pose_subspace '" + name +
                              "' names a component of a compound space and must be empty here");
    }
    return {-1, kind};
  }
  const auto* c = dynamic_cast<const ob::CompoundStateSpace*>(&space);
  if (!c || c->getSubspaceCount() == 0) {
    throw InvalidInputError(who +
                            " is not an SE2, SE3, R^2 or R^3 space (RealVectorStateSpace of dimension 2 or 3), nor a "
                            "compound space with one of those as a component");
  }
  const int n = static_cast<int>(c->getSubspaceCount());
  auto sub = [&](int i) -> const ob::StateSpace& { return *c->getSubspace(static_cast<unsigned int>(i)); };
  std::string names;
  for (int i = 0; i < n; ++i) names += (i ? ", " : "") + describe(sub(i));
  int index = -1;
  if (!name.empty()) {
    for (int i = 0; i < n && index < 0; ++i) {
      if (sub(i).getName() == name) index = i;
    }
    if (index < 0) {
      throw InvalidInputError(who + " has no direct component named '" + name + "' (components: " + names + ")");
    }
    if (!poseKindOf(sub(index), &kind)) {
      throw InvalidInputError(who + ": the named pose part " + describe(sub(index)) +
                              " is not an SE2, SE3, R^2 or R^3 space");
    }
  } else {
    if (!poseKindOf(sub(0), &kind)) {
      for (int i = 1; i < n; ++i) {
        SpaceKind other;
        if (poseKindOf(sub(i), &other)) {
          throw InvalidInputError(who + ": the first component " + describe(sub(0)) +
                                  " is not a pose part; component " + describe(sub(i)) +
                                  " could be: name it in SpaceWrapOptions::pose_subspace");
        }
      }
      throw InvalidInputError(
          who + " has no pose part: no component is an SE2, SE3, R^2 or R^3 space (components: " + names + ")");
    }
    for (int i = 1; i < n; ++i) {
      SpaceKind other;
      if (poseKindOf(sub(i), &other) && (rotatingKind(other) || !rotatingKind(kind))) {
        throw InvalidInputError(who + ": the pose part is ambiguous, the first component " + describe(sub(0)) + " or " +
                                describe(sub(i)) + ": name it in SpaceWrapOptions::pose_subspace");
      }
    }
    index = 0;
  }
  for (int i = 0; i < n; ++i) {
    if (i != index && !supportedExtra(sub(i))) {
      throw InvalidInputError(who + ": the extra component " + describe(sub(i)) +
                              " is not a RealVectorStateSpace, SO2StateSpace, SO3StateSpace or a compound of those; "
                              "the motion validator cannot follow its bounds along an edge");
    }
  }
  return {index, kind};
}

Eigen::Quaterniond unitQuaternion(const Eigen::Quaterniond& q, const char* what) {
  const double n = q.norm();
  if (!std::isfinite(n) || n < kMinQuaternionNorm) {
    throw InvalidInputError(std::string("PlanningSpace: ") + what + " is zero or not finite");
  }
  return Eigen::Quaterniond(q.coeffs() / n);
}

/// The dot product of two SO(3) states exactly as SO3StateSpace::interpolate
/// and arcLength compute it: x, y, z, w added left to right. The sign picks
/// the way OMPL's slerp turns; for a half-turn it is a few 1e-17, and
/// Eigen's Vector4d::dot (pairwise, vectorised) gave the opposite sign on
/// 2.5% of edges q2 = q1 * AngleAxis(pi, random axis): the motion checked
/// turned the other way from the one OMPL executes (hostile-input hunt).
double omplQuaternionDot(const ob::SO3StateSpace::StateType& a, const ob::SO3StateSpace::StateType& b) {
  double dq = a.x * b.x;
  dq += a.y * b.y;
  dq += a.z * b.z;
  dq += a.w * b.w;
  return dq;
}

Eigen::Quaterniond toEigen(const ob::SO3StateSpace::StateType& q) {
  Eigen::Quaterniond e(q.w, q.x, q.y, q.z);
  const double n = e.norm();
  if (n > 0.0 && std::isfinite(n)) e.coeffs() /= n;
  return e;
}

}  // namespace

const char* toString(SpaceKind kind) {
  switch (kind) {
    case SpaceKind::kSE2: return "SE2";
    case SpaceKind::kSE3: return "SE3";
    case SpaceKind::kR2: return "R2";
    case SpaceKind::kR3: return "R3";
  }
  return "?";
}

// ---- EdgeMotion ------------------------------------------------------------------

Eigen::Quaterniond EdgeMotion::orientation(double t) const {
  if (angle == 0.0) return q_start;
  return q_start * Eigen::Quaterniond(Eigen::AngleAxisd(t * angle, axis_R));
}

Eigen::Isometry3d EdgeMotion::pose(double t) const {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = angle == 0.0 ? R_start : orientation(t).toRotationMatrix();
  X.translation() = position(t);
  return X;
}

bool EdgeMotion::endDiffers() const {
  if (X_end.translation() != p_end) return true;
  if (angle == 0.0) return X_end.linear() != R_start;
  return X_end.linear() != orientation(1.0).toRotationMatrix();
}

// ---- PlanningSpace ---------------------------------------------------------------

PlanningSpace::PlanningSpace(SpaceKind kind, const Eigen::AlignedBox3d& bounds, double z,
                             const Eigen::Quaterniond& q_WR)
    : kind_(kind), bounds_(bounds) {
  position_dims_ = (kind == SpaceKind::kSE2 || kind == SpaceKind::kR2) ? 2 : 3;
  checkBounds(bounds, position_dims_);
  setFixedPose(z, q_WR);
  ob::RealVectorBounds rb(static_cast<unsigned int>(position_dims_));
  for (int k = 0; k < position_dims_; ++k) {
    rb.setLow(static_cast<unsigned int>(k), bounds.min()[k]);
    rb.setHigh(static_cast<unsigned int>(k), bounds.max()[k]);
  }
  switch (kind) {
    case SpaceKind::kSE2: {
      auto s = std::make_shared<ob::SE2StateSpace>();
      s->setBounds(rb);
      space_ = s;
      break;
    }
    case SpaceKind::kSE3: {
      auto s = std::make_shared<ob::SE3StateSpace>();
      s->setBounds(rb);
      space_ = s;
      break;
    }
    case SpaceKind::kR2:
    case SpaceKind::kR3: {
      auto s = std::make_shared<ob::RealVectorStateSpace>(static_cast<unsigned int>(position_dims_));
      s->setBounds(rb);
      space_ = s;
      break;
    }
  }
  findRotationParts();
}

PlanningSpace::PlanningSpace(SpaceKind kind, ob::StateSpacePtr space, int pose_index, const SpaceWrapOptions& options)
    : kind_(kind), pose_index_(pose_index), space_(std::move(space)) {
  position_dims_ = (kind == SpaceKind::kSE2 || kind == SpaceKind::kR2) ? 2 : 3;
  const ob::StateSpace* part = space_.get();
  if (pose_index_ >= 0)
    part = space_->as<ob::CompoundStateSpace>()->getSubspace(static_cast<unsigned int>(pose_index_)).get();
  const ob::RealVectorBounds* rb = nullptr;
  switch (kind) {
    case SpaceKind::kSE2: rb = &dynamic_cast<const ob::SE2StateSpace&>(*part).getBounds(); break;
    case SpaceKind::kSE3: rb = &dynamic_cast<const ob::SE3StateSpace&>(*part).getBounds(); break;
    case SpaceKind::kR2:
    case SpaceKind::kR3: rb = &dynamic_cast<const ob::RealVectorStateSpace&>(*part).getBounds(); break;
  }
  setFixedPose(options.z, options.q_WR);
  const double z_extent = kind == SpaceKind::kR2 ? z_fixed_ : 0.0;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(z_extent), hi = Eigen::Vector3d::Constant(z_extent);
  for (int k = 0; k < position_dims_; ++k) {
    const auto u = static_cast<std::size_t>(k);
    lo[k] = u < rb->low.size() ? rb->low[u] : std::numeric_limits<double>::quiet_NaN();
    hi[k] = u < rb->high.size() ? rb->high[u] : std::numeric_limits<double>::quiet_NaN();
  }
  bounds_ = Eigen::AlignedBox3d(lo, hi);
  checkBounds(bounds_, position_dims_,
              "PlanningSpace::wrap: state space '" + space_->getName() + "' (pose part '" + part->getName() +
                  "'; set its bounds before wrapping)");
  findRotationParts();
}

void PlanningSpace::setFixedPose(double z, const Eigen::Quaterniond& q_WR) {
  if (kind_ == SpaceKind::kR2 || kind_ == SpaceKind::kR3) {
    q_fixed_ = unitQuaternion(q_WR, "the fixed orientation");
    R_fixed_ = q_fixed_.toRotationMatrix();
  }
  if (kind_ == SpaceKind::kR2) {
    if (!std::isfinite(z)) throw InvalidInputError("PlanningSpace::r2: the fixed z is not finite");
    z_fixed_ = z;
  }
}

PlanningSpacePtr PlanningSpace::wrap(const ob::StateSpacePtr& space, const SpaceWrapOptions& options) {
  if (!space) throw InvalidInputError("PlanningSpace::wrap: the state space is null");
  const std::pair<int, SpaceKind> part = locatePosePart(*space, options.pose_subspace);
  return PlanningSpacePtr(new PlanningSpace(part.second, space, part.first, options));
}

const ob::State* PlanningSpace::poseState(const ob::State* state) const {
  if (pose_index_ < 0) return state;
  return state->as<ob::CompoundState>()->components[pose_index_];
}

ob::State* PlanningSpace::poseState(ob::State* state) const {
  if (pose_index_ < 0) return state;
  return state->as<ob::CompoundState>()->components[pose_index_];
}

PlanningSpacePtr PlanningSpace::make(SpaceKind kind, const Eigen::AlignedBox3d& bounds, double z,
                                     const Eigen::Quaterniond& q_WR) {
  if (kind != SpaceKind::kSE2 && kind != SpaceKind::kSE3 && kind != SpaceKind::kR2 && kind != SpaceKind::kR3) {
    throw InvalidInputError("PlanningSpace::make: unknown space kind " + std::to_string(static_cast<int>(kind)));
  }
  return PlanningSpacePtr(new PlanningSpace(kind, bounds, z, q_WR));
}
PlanningSpacePtr PlanningSpace::se2(const Eigen::AlignedBox3d& bounds) {
  return make(SpaceKind::kSE2, bounds);
}
PlanningSpacePtr PlanningSpace::se3(const Eigen::AlignedBox3d& bounds) {
  return make(SpaceKind::kSE3, bounds);
}
PlanningSpacePtr PlanningSpace::r2(const Eigen::AlignedBox3d& bounds, double z, const Eigen::Quaterniond& q_WR) {
  return make(SpaceKind::kR2, bounds, z, q_WR);
}
PlanningSpacePtr PlanningSpace::r3(const Eigen::AlignedBox3d& bounds, const Eigen::Quaterniond& q_WR) {
  return make(SpaceKind::kR3, bounds, 0.0, q_WR);
}

Eigen::Isometry3d PlanningSpace::pose(const ob::State* full) const {
  const ob::State* state = poseState(full);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  switch (kind_) {
    case SpaceKind::kSE2: {
      const auto* s = state->as<ob::SE2StateSpace::StateType>();
      X.linear() = Eigen::AngleAxisd(s->getYaw(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
      X.translation() = Eigen::Vector3d(s->getX(), s->getY(), 0.0);
      break;
    }
    case SpaceKind::kSE3: {
      const auto* s = state->as<ob::SE3StateSpace::StateType>();
      X.linear() = toEigen(s->rotation()).toRotationMatrix();
      X.translation() = Eigen::Vector3d(s->getX(), s->getY(), s->getZ());
      break;
    }
    case SpaceKind::kR2: {
      const double* v = state->as<ob::RealVectorStateSpace::StateType>()->values;
      X.linear() = R_fixed_;
      X.translation() = Eigen::Vector3d(v[0], v[1], z_fixed_);
      break;
    }
    case SpaceKind::kR3: {
      const double* v = state->as<ob::RealVectorStateSpace::StateType>()->values;
      X.linear() = R_fixed_;
      X.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
      break;
    }
  }
  return X;
}

void PlanningSpace::setPose(const Eigen::Isometry3d& X_WR, ob::State* full) const {
  ob::State* state = poseState(full);
  const Eigen::Vector3d p = X_WR.translation();
  const Eigen::Matrix3d R = X_WR.linear();
  if (!p.allFinite() || !R.allFinite()) throw InvalidInputError("PlanningSpace::setPose: the pose is not finite");
  if (!(R.transpose() * R - Eigen::Matrix3d::Identity()).isZero(kPoseTolerance) || R.determinant() < 0.0) {
    throw InvalidInputError("PlanningSpace::setPose: the pose's linear part is not a rotation");
  }
  const double z_tol = kPoseTolerance * (1.0 + p.norm());
  switch (kind_) {
    case SpaceKind::kSE2: {
      if (std::abs(R(2, 2) - 1.0) > kPoseTolerance || std::abs(p.z()) > z_tol) {
        throw InvalidInputError("PlanningSpace::setPose: an SE2 pose rotates about +z only and has z = 0; got z = " +
                                std::to_string(p.z()) + ", R(2,2) = " + std::to_string(R(2, 2)));
      }
      auto* s = state->as<ob::SE2StateSpace::StateType>();
      s->setXY(p.x(), p.y());
      s->setYaw(std::atan2(R(1, 0), R(0, 0)));
      break;
    }
    case SpaceKind::kSE3: {
      auto* s = state->as<ob::SE3StateSpace::StateType>();
      s->setXYZ(p.x(), p.y(), p.z());
      Eigen::Quaterniond q(R);
      q.normalize();
      s->rotation().x = q.x();
      s->rotation().y = q.y();
      s->rotation().z = q.z();
      s->rotation().w = q.w();
      break;
    }
    case SpaceKind::kR2:
    case SpaceKind::kR3: {
      if (!(R - R_fixed_).isZero(kPoseTolerance)) {
        throw InvalidInputError(std::string("PlanningSpace::setPose: a ") + toString(kind_) +
                                " pose has the space's fixed orientation");
      }
      if (kind_ == SpaceKind::kR2 && std::abs(p.z() - z_fixed_) > z_tol) {
        throw InvalidInputError("PlanningSpace::setPose: an R2 pose has z = " + std::to_string(z_fixed_) + "; got " +
                                std::to_string(p.z()));
      }
      double* v = state->as<ob::RealVectorStateSpace::StateType>()->values;
      v[0] = p.x();
      v[1] = p.y();
      if (kind_ == SpaceKind::kR3) v[2] = p.z();
      break;
    }
  }
}

EdgeMotion PlanningSpace::motion(const ob::State* s1, const ob::State* s2) const {
  EdgeMotion m;
  const Eigen::Isometry3d X1 = pose(s1);
  m.X_end = pose(s2);
  m.p_start = X1.translation();
  m.p_end = m.X_end.translation();
  m.R_start = X1.linear();
  switch (kind_) {
    case SpaceKind::kSE2: {
      // SO2StateSpace::interpolate: the shorter way, |diff| <= pi going forward.
      const double yaw1 = poseState(s1)->as<ob::SE2StateSpace::StateType>()->getYaw();
      const double yaw2 = poseState(s2)->as<ob::SE2StateSpace::StateType>()->getYaw();
      // std::remainder: the same as one turn added or taken for yaws within
      // [-pi, pi] (ties at +-pi kept), and within [-pi, pi] for any other (a
      // yaw of 1e300 gave an angle of 1e300, and a search without end).
      const double diff = std::remainder(yaw2 - yaw1, 2.0 * kPi);
      if (std::abs(diff) >= kMinRotationAngle) {
        m.angle = std::abs(diff);
        m.axis_R = Eigen::Vector3d(0.0, 0.0, diff > 0.0 ? 1.0 : -1.0);
      }
      m.q_start = Eigen::Quaterniond(Eigen::AngleAxisd(yaw1, Eigen::Vector3d::UnitZ()));
      break;
    }
    case SpaceKind::kSE3: {
      const auto& r1 = poseState(s1)->as<ob::SE3StateSpace::StateType>()->rotation();
      const auto& r2 = poseState(s2)->as<ob::SE3StateSpace::StateType>()->rotation();
      // A zero (or non-finite) quaternion is no rotation: OMPL's SO(3)
      // interpolate, asked below near a half-turn tie, aborts on it.
      unitQuaternion(Eigen::Quaterniond(r1.w, r1.x, r1.y, r1.z), "motion: s1's quaternion");
      unitQuaternion(Eigen::Quaterniond(r2.w, r2.x, r2.y, r2.z), "motion: s2's quaternion");
      m.q_start = toEigen(r1);
      const double dq = omplQuaternionDot(r1, r2);
      // SO3StateSpace's arcLength(): 0 when |dq| > 1 - 1e-9, then interpolate() copies q1.
      if (std::abs(dq) <= 1.0 - kOmplQuaternionTolerance) {
        const double theta = std::acos(std::abs(dq));
        Eigen::Quaterniond q1 = toEigen(r1);
        Eigen::Quaterniond q2 = toEigen(r2);
        // Near a half-turn the sign is a few 1e-17 and, were OMPL built with
        // fused multiply-adds (another CPU, other flags), could differ from
        // ours: OMPL's own midpoint tells which way it turns (it is
        // (q1 +- q2) / sqrt(2), at 0.71 from +-q2, far from any tie).
        bool negate = dq < 0.0;
        if (std::abs(dq) < kHalfTurnDotAmbiguity) {
          ob::State* mid = space_->allocState();
          space_->interpolate(s1, s2, 0.5, mid);
          const auto& rm = poseState(mid)->as<ob::SE3StateSpace::StateType>()->rotation();
          negate = omplQuaternionDot(rm, r2) < 0.0;
          space_->freeState(mid);
        }
        if (negate) q2.coeffs() = -q2.coeffs();
        const Eigen::Quaterniond rel = q1.conjugate() * q2;  // w >= 0: the shorter arc
        const double n = rel.vec().norm();
        if (n > 0.0) {
          m.angle = 2.0 * theta;
          m.axis_R = rel.vec() / n;
        }
        m.q_start = q1;
      }
      break;
    }
    case SpaceKind::kR2:
    case SpaceKind::kR3: m.q_start = q_fixed_; break;
  }
  return m;
}

bool PlanningSpace::positionInBounds(const Eigen::Vector3d& p) const {
  // RealVectorStateSpace::satisfiesBounds, with its epsilon slack.
  constexpr double eps = std::numeric_limits<double>::epsilon();
  for (int k = 0; k < position_dims_; ++k) {
    if (p[k] - eps > bounds_.max()[k] || p[k] + eps < bounds_.min()[k]) return false;
  }
  return true;
}

void PlanningSpace::findRotationParts() {
  // The space itself or any component of a compound space, at any depth.
  std::vector<unsigned int> path;
  const auto visit = [&](const auto& self, const ob::StateSpace& space) -> void {
    if (dynamic_cast<const ob::SO2StateSpace*>(&space) != nullptr ||
        dynamic_cast<const ob::SO3StateSpace*>(&space) != nullptr) {
      rotation_parts_.push_back(RotationPart{&space, path});
      return;
    }
    if (const auto* c = dynamic_cast<const ob::CompoundStateSpace*>(&space)) {
      for (unsigned int i = 0; i < c->getSubspaceCount(); ++i) {
        path.push_back(i);
        self(self, *c->getSubspace(i));
        path.pop_back();
      }
    }
  };
  rotation_parts_.clear();
  visit(visit, *space_);
}

bool PlanningSpace::rotationsWithinBounds(const ob::State* state) const {
  for (const RotationPart& part : rotation_parts_) {
    const ob::State* s = state;
    for (const unsigned int i : part.path) s = s->as<ob::CompoundState>()->components[i];
    if (!part.space->satisfiesBounds(s)) return false;
  }
  return true;
}

double PlanningSpace::boundsExitFraction(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2) const {
  double exit = kInf;
  for (int k = 0; k < position_dims_; ++k)
    exit = std::min(exit, axisExit(bounds_.min()[k], bounds_.max()[k], p1[k], p2[k]));
  return exit == kInf ? kInf : std::max(0.0, exit);
}

double PlanningSpace::boundsExitFraction(const ob::State* s1, const ob::State* s2) const {
  double exit = boundsExitFraction(pose(s1).translation(), pose(s2).translation());
  if (pose_index_ >= 0) {
    const auto* compound = space_->as<ob::CompoundStateSpace>();
    const auto* c1 = s1->as<ob::CompoundState>();
    const auto* c2 = s2->as<ob::CompoundState>();
    for (unsigned int i = 0; i < compound->getSubspaceCount(); ++i) {
      if (static_cast<int>(i) == pose_index_) continue;
      exit = std::min(exit, extraExit(*compound->getSubspace(i), c1->components[i], c2->components[i]));
    }
  }
  return exit == kInf ? kInf : std::max(0.0, exit);
}

}  // namespace mddual::planning
