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
//
// A PlanningSpace either owns a state space it made (se2(), se3(), r2(), r3(),
// make()) or wraps a space the user made (wrap()). Layouts wrap() accepts:
//
//   - the space itself is an SE2StateSpace, an SE3StateSpace, or a
//     RealVectorStateSpace of dimension 2 (kR2) or 3 (kR3);
//   - a CompoundStateSpace (not itself SE2/SE3) one of whose direct components
//     is such a space, the "pose part":
//       * named: SpaceWrapOptions::pose_subspace is the component's getName();
//       * unnamed: the FIRST component, refused as ambiguous when a later
//         component is SE2/SE3 too, or when the first is R2/R3 and a later one
//         is R2/R3 too (name the pose part then).
//     The other components are extra coordinates (joints...) the scene ignores:
//     each must be a RealVectorStateSpace, SO2StateSpace, SO3StateSpace or a
//     compound of those (SE2/SE3 included), whose interpolation and bounds the
//     motion validator can follow (boundsExitFraction()). OMPL's
//     CompoundStateSpace::interpolate moves every component with the same t,
//     so the pose part moves exactly as it would alone: motion() holds.
//
// Refused with InvalidInputError naming the space and the reason: an SO2/SO3
// space alone, a RealVectorStateSpace of another dimension, a compound with no
// pose part, an unnamed pose part that is not the first component, an
// ambiguous one, a name that is no direct component, extra components of
// other types, and position bounds that are not set (empty or not finite).
// The bounds are read when wrap() runs: set them before, wrap again after
// changing them. The user's subclasses of these spaces must keep OMPL's
// interpolate() (the state layout is checked with dynamic_cast).
#pragma once

#include <ompl/base/StateSpace.h>
#include <ompl/util/ClassForward.h>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace mddual::planning {

enum class SpaceKind : std::uint8_t { kSE2, kSE3, kR2, kR3 };
const char* toString(SpaceKind kind);

/// Rotations smaller than this (radians) along an SE(2) edge count as none.
inline constexpr double kMinRotationAngle = 1e-12;
/// A quaternion of norm below this is no rotation (PlanningSpace refuses it
/// as zero; the Python module's states too).
inline constexpr double kMinQuaternionNorm = 1e-12;

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
  /// Total rotation angle along the edge: in [0, pi] for the edge between two
  /// OMPL states; an extended edge (edges.h) may turn further.
  double angle = 0.0;
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

/// How PlanningSpace::wrap() reads the pose from a space the user made (see the
/// file comment for the accepted layouts).
struct SpaceWrapOptions {
  /// Name (StateSpace::getName()) of the direct component of a compound space
  /// that holds the pose; empty: the space itself, or its first component.
  std::string pose_subspace;
  /// Pose part R^2: the robot's fixed z. R^2 and R^3: its fixed orientation
  /// (normalised; zero or non-finite quaternions are refused).
  double z = 0.0;
  Eigen::Quaterniond q_WR = Eigen::Quaterniond::Identity();
};

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
  /// Wraps a state space the user made (layouts: file comment); stateSpace()
  /// is then `space` itself, whose layout must not change afterwards (the
  /// pose part's index and the rotation components are found here, once). bounds() are its pose part's position bounds
  /// (z extent [z, z] for kR2, [0, 0] for kSE2).
  static PlanningSpacePtr wrap(const ompl::base::StateSpacePtr& space,
                               const SpaceWrapOptions& options = SpaceWrapOptions());

  SpaceKind kind() const { return kind_; }
  const ompl::base::StateSpacePtr& stateSpace() const { return space_; }
  /// The bounds as given (for kSE2/kR2 only x and y bound the state).
  const Eigen::AlignedBox3d& bounds() const { return bounds_; }
  /// The fixed orientation and z of the translation-only kinds.
  const Eigen::Quaterniond& fixedOrientation() const { return q_fixed_; }
  double fixedZ() const { return z_fixed_; }
  /// Index of the pose part among stateSpace()'s components, or -1 when the
  /// space itself is the pose part.
  int poseComponent() const { return pose_index_; }

  /// The robot's pose X_WR in state `state` (quaternions are normalised).
  Eigen::Isometry3d pose(const ompl::base::State* state) const;
  /// Writes the state whose pose is X_WR (a compound state: its pose part
  /// only, the other components are left as they are). Throws InvalidInputError when the
  /// pose is not one of this space (kSE2: rotation not about z or z != 0;
  /// kR2/kR3: a different orientation or z), within 1e-9, or is not finite.
  void setPose(const Eigen::Isometry3d& X_WR, ompl::base::State* state) const;
  /// The motion OMPL's interpolation executes from s1 to s2 (see above).
  EdgeMotion motion(const ompl::base::State* s1, const ompl::base::State* s2) const;
  /// Whether every SO(2) and SO(3) component of the state (the pose part's and
  /// any other, at any depth of a compound space) satisfies its bounds: a yaw
  /// in [-pi, pi], a quaternion of norm within 1e-9 of 1. OMPL's distance()
  /// and so validSegmentCount() assert on such components, its SO(3)
  /// interpolate() on the quaternion's norm.
  bool rotationsWithinBounds(const ompl::base::State* state) const;
  /// Whether OMPL's interpolation s1 -> s2 changes the orientation.
  bool rotates(const ompl::base::State* s1, const ompl::base::State* s2) const { return motion(s1, s2).rotates(); }
  /// The position bounds as OMPL checks them (the axes the state has).
  bool positionInBounds(const Eigen::Vector3d& p) const;
  /// The first t in [0, 1] at which p(t) = p1 + t (p2 - p1) leaves the position
  /// bounds (p1 inside), or +infinity if it never does.
  double boundsExitFraction(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2) const;
  /// The same over every bounded coordinate of the state that OMPL
  /// interpolates linearly: the pose part's position and, for a wrapped
  /// compound, the extra real-vector components (only coordinates whose value
  /// at s2 is out of bounds count, as above). s1 is assumed within bounds.
  double boundsExitFraction(const ompl::base::State* s1, const ompl::base::State* s2) const;

 private:
  PlanningSpace(SpaceKind kind, const Eigen::AlignedBox3d& bounds, double z, const Eigen::Quaterniond& q_WR);
  PlanningSpace(SpaceKind kind, ompl::base::StateSpacePtr space, int pose_index, const SpaceWrapOptions& options);
  void setFixedPose(double z, const Eigen::Quaterniond& q_WR);
  /// Fills rotation_parts_ from space_ (both constructors, last).
  void findRotationParts();
  /// The pose part of a state of stateSpace().
  const ompl::base::State* poseState(const ompl::base::State* state) const;
  ompl::base::State* poseState(ompl::base::State* state) const;

  SpaceKind kind_;
  Eigen::AlignedBox3d bounds_;
  double z_fixed_ = 0.0;
  Eigen::Quaterniond q_fixed_ = Eigen::Quaterniond::Identity();
  Eigen::Matrix3d R_fixed_ = Eigen::Matrix3d::Identity();
  int position_dims_ = 3;
  int pose_index_ = -1;
  ompl::base::StateSpacePtr space_;
  /// The SO(2) and SO(3) components of space_ at any depth, found once:
  /// rotationsWithinBounds() runs on every motion check, and finding them
  /// with dynamic_cast took 4% of twistycool's motion checks (callgrind;
  /// docs/results/tuning.md).
  struct RotationPart {
    const ompl::base::StateSpace* space;
    std::vector<unsigned int> path;  ///< component indices from the state down to it
  };
  std::vector<RotationPart> rotation_parts_;
};

}  // namespace mddual::planning
