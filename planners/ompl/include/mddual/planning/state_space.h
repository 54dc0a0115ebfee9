// PlanningSpace: the OMPL state space of a rigid-body planning problem and the
// map between its states and the robot's pose X_WR (pose of the body frame R in
// the world W). Four kinds:
//
//   kSE2  (x, y, yaw): X_WR = translation (x, y, 0), rotation yaw about +z;
//   kSE3  (x, y, z, quaternion);
//   kR2   (x, y): orientation and z fixed at given values;
//   kR3   (x, y, z): orientation fixed at a given value.
//
// Guarantee: motion() describes exactly the motion OMPL's own interpolation
// (StateSpace::interpolate) executes between two states, which the motion
// validators reason about:
//   - position: the straight line p(t) = p1 + t (p2 - p1)
//     (RealVectorStateSpace::interpolate);
//   - SE(2) yaw: the shorter way round, by |diff| when |diff| <= pi, otherwise
//     by 2 pi - |diff| the other way (SO2StateSpace::interpolate);
//   - SE(3) orientation: slerp along the shorter arc (the sign of q2 flipped
//     when q1 . q2 < 0), constant angular speed about a fixed axis of the start
//     body frame; when |q1 . q2| > 1 - 1e-9 (OMPL's MAX_QUATERNION_NORM_ERROR)
//     SO3StateSpace::interpolate copies q1 for every t, so the edge keeps the
//     start orientation although s2 itself may differ by up to ~9e-5 rad:
//     EdgeMotion then has angle 0 and X_end = s2's own pose.
// An SE(2) yaw change below kMinRotationAngle (1e-12 rad) is treated as none
// (it moves no robot point by more than 1e-12 of the robot radius, far below
// the core's touching tolerance of 1e-10 of the pair's size); X_end is then s2's
// own pose, checked as a state.
#pragma once

#include <ompl/base/StateSpace.h>
#include <ompl/util/ClassForward.h>
#include <Eigen/Geometry>
#include <cstdint>

namespace mddual::planning {

enum class SpaceKind : std::uint8_t { kSE2, kSE3, kR2, kR3 };
const char* toString(SpaceKind kind);

/// Rotations smaller than this (radians) along an SE(2) edge count as none.
inline constexpr double kMinRotationAngle = 1e-12;

/// The robot frame's motion along an edge s1 -> s2 (t in [0, 1]):
///   p(t) = p_start + t (p_end - p_start),
///   R(t) = R(q_start) * AngleAxis(t * angle, axis_R)   (axis in the start body frame).
/// X_end is the pose of s2 itself; it equals pose(1) up to round-off except for
/// the sub-threshold rotations described above, where the validators check it
/// as a separate state.
struct EdgeMotion {
  Eigen::Vector3d p_start = Eigen::Vector3d::Zero();
  Eigen::Vector3d p_end = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_start = Eigen::Quaterniond::Identity();
  Eigen::Matrix3d R_start = Eigen::Matrix3d::Identity();  ///< q_start as a matrix
  Eigen::Vector3d axis_R = Eigen::Vector3d::UnitZ();
  double angle = 0.0;  ///< total rotation angle along the edge, in [0, pi]
  Eigen::Isometry3d X_end = Eigen::Isometry3d::Identity();

  bool rotates() const { return angle > 0.0; }
  /// Length of the translation (world units).
  double length() const { return (p_end - p_start).norm(); }
  Eigen::Vector3d position(double t) const { return p_start + t * (p_end - p_start); }
  Eigen::Quaterniond orientation(double t) const;
  Eigen::Isometry3d pose(double t) const;
  /// X_end differs from pose(1) (sub-threshold rotation): check it separately.
  bool endDiffers() const;
};

OMPL_CLASS_FORWARD(PlanningSpace);

/// A planning space of one of the four kinds: owns the OMPL state space (with
/// the position bounds set) and maps states to poses and back. Immutable after
/// construction; every method is const and thread-safe.
class PlanningSpace {
 public:
  /// Position bounds: x, y of `bounds` for kSE2/kR2, x, y, z otherwise. Throw
  /// InvalidInputError for an empty or non-finite box, or a box with a zero
  /// extent along a bounded axis (OMPL requires low < high).
  static PlanningSpacePtr se2(const Eigen::AlignedBox3d& bounds);
  static PlanningSpacePtr se3(const Eigen::AlignedBox3d& bounds);
  /// Translation in x, y; z and the orientation fixed (q_WR normalised; throws
  /// InvalidInputError for a zero or non-finite quaternion or z).
  static PlanningSpacePtr r2(const Eigen::AlignedBox3d& bounds, double z = 0.0,
                             const Eigen::Quaterniond& q_WR = Eigen::Quaterniond::Identity());
  /// Translation in x, y, z; orientation fixed.
  static PlanningSpacePtr r3(const Eigen::AlignedBox3d& bounds,
                             const Eigen::Quaterniond& q_WR = Eigen::Quaterniond::Identity());
  /// Any kind; z and q_WR are used only by the kinds that fix them.
  static PlanningSpacePtr make(SpaceKind kind, const Eigen::AlignedBox3d& bounds, double z = 0.0,
                               const Eigen::Quaterniond& q_WR = Eigen::Quaterniond::Identity());

  SpaceKind kind() const { return kind_; }
  const ompl::base::StateSpacePtr& stateSpace() const { return space_; }
  /// The bounds as given (for kSE2/kR2 only x and y bound the state).
  const Eigen::AlignedBox3d& bounds() const { return bounds_; }
  /// The fixed orientation and z of the translation-only kinds.
  const Eigen::Quaterniond& fixedOrientation() const { return q_fixed_; }
  double fixedZ() const { return z_fixed_; }

  /// The robot's pose X_WR in state `state` (quaternions are normalised).
  Eigen::Isometry3d pose(const ompl::base::State* state) const;
  /// Writes the state whose pose is X_WR. Throws InvalidInputError when the
  /// pose is not one of this space (kSE2: rotation not about z or z != 0;
  /// kR2/kR3: a different orientation or z), within 1e-9, or is not finite.
  void setPose(const Eigen::Isometry3d& X_WR, ompl::base::State* state) const;
  /// The motion OMPL's interpolation executes from s1 to s2 (see above).
  EdgeMotion motion(const ompl::base::State* s1, const ompl::base::State* s2) const;
  /// Whether OMPL's interpolation s1 -> s2 changes the orientation.
  bool rotates(const ompl::base::State* s1, const ompl::base::State* s2) const { return motion(s1, s2).rotates(); }
  /// The position bounds as OMPL checks them (the axes the state has).
  bool positionInBounds(const Eigen::Vector3d& p) const;
  /// The first t in [0, 1] at which p(t) = p1 + t (p2 - p1) leaves the position
  /// bounds (p1 inside), or +infinity if it never does.
  double boundsExitFraction(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2) const;

 private:
  PlanningSpace(SpaceKind kind, const Eigen::AlignedBox3d& bounds, double z, const Eigen::Quaterniond& q_WR);

  SpaceKind kind_;
  Eigen::AlignedBox3d bounds_;
  double z_fixed_ = 0.0;
  Eigen::Quaterniond q_fixed_ = Eigen::Quaterniond::Identity();
  Eigen::Matrix3d R_fixed_ = Eigen::Matrix3d::Identity();
  int position_dims_ = 3;
  ompl::base::StateSpacePtr space_;
};

}  // namespace mddual::planning
