// RobotModel: an articulated robot read from a URDF (urdfdom): a tree of
// links joined by fixed, revolute, continuous and prismatic joints (mimic
// joints included), each link's collision geometry as convex pieces in the
// link frame, and forward kinematics.
//
// Frames: B is the root link's frame (the robot's base); L is a link's own
// frame (URDF's link frame); J is a joint's frame, placed at X_PJ in its
// parent link's frame P (URDF's joint origin). A revolute joint turns its
// child link about axis_J through J's origin by the joint value (radians); a
// prismatic joint translates it along axis_J by the value (metres).
//
// Variables: one per joint that moves and is not a mimic joint, in tree
// order (depth first from the root; a link's child joints by name), so a
// chain's variables run from the base to the tip. A mimic joint's value is multiplier *
// (its leader's value) + offset; a mimic of a mimic is resolved to the root
// leader. Configurations are vectors of variables (numVariables() entries).
//
// Mesh paths: `package://PKG/rest` and relative paths are looked up in the
// URDF's folder and each of its parents (for package://, a folder named PKG
// on that path, or a child PKG of it), then in each entry of
// RobotLoadOptions::package_path, then in each folder of the environment
// variable MDDUAL_PACKAGE_PATH (':'-separated). A mesh that is found nowhere
// is a SceneError naming the URDF, the link and every place searched.
//
// Thread safety: immutable after loading; linkPoses() is const and may run
// from any number of threads.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "mddual/scene/loaders.h"
#include "mddual/scene/scene.h"

namespace mddual::scene {

enum class JointType : std::uint8_t {
  kFixed,
  kRevolute,    ///< bounded rotation (radians)
  kContinuous,  ///< unbounded rotation (radians; an angle, wraps)
  kPrismatic,   ///< translation along the axis (metres)
};

const char* toString(JointType type);

/// One joint of the tree.
struct Joint {
  std::string name;
  JointType type = JointType::kFixed;
  int parent_link = -1;
  int child_link = -1;
  Eigen::Isometry3d X_PJ = Eigen::Isometry3d::Identity();  ///< joint frame in the parent link's frame
  Eigen::Vector3d axis_J = Eigen::Vector3d::UnitX();       ///< unit axis (frame J)
  /// Limits of the joint's value (continuous: -inf, +inf).
  double lower = 0.0;
  double upper = 0.0;
  /// The variable that drives the joint: its own, or for a mimic joint its
  /// leader's; -1 for a fixed joint.
  int variable = -1;
  bool mimic = false;       ///< value = multiplier * variable + offset
  double multiplier = 1.0;  ///< 1 unless mimic
  double offset = 0.0;      ///< 0 unless mimic
  bool moves() const { return type != JointType::kFixed; }
  /// The joint's value for its variable's value v.
  double value(double v) const { return multiplier * v + offset; }
};

/// One link: its place in the tree and its collision pieces (frame L).
struct Link {
  std::string name;
  int parent_joint = -1;  ///< -1 for the root
  std::vector<int> child_joints;
  std::vector<Piece> pieces;
  /// Largest distance of a piece vertex from the link frame's origin (0
  /// without pieces).
  double radius = 0.0;
};

/// What loadRobotModel takes.
struct RobotLoadOptions {
  LoadOptions load;  ///< primitive and mesh options (recentre_mesh is ignored)
  /// Folders searched for package:// and relative mesh paths after the
  /// URDF's folder and its parents (the CLI's --package-path).
  std::vector<std::filesystem::path> package_path;
  /// Also search MDDUAL_PACKAGE_PATH (the tests turn it off).
  bool use_environment = true;
};

/// See the file comment.
class RobotModel {
 public:
  RobotModel() = default;
  /// Builds a model from its parts (the loader and tests). Links must be in
  /// tree order: link 0 is the root and every joint's parent link comes
  /// before its child link. Variables are numbered in joint order over the
  /// moving non-mimic joints (Joint::variable is set); a mimic joint's
  /// variable must already name its leader's. Throws SceneError naming the joint or link when
  /// the tree or a joint is inconsistent (a bad index, an axis that is not
  /// finite and nonzero, limits with lower > upper or not finite for a
  /// revolute or prismatic joint, a non-finite origin).
  RobotModel(std::string name, std::vector<Link> links, std::vector<Joint> joints);

  const std::string& name() const { return name_; }
  const std::vector<Link>& links() const { return links_; }
  const std::vector<Joint>& joints() const { return joints_; }
  const Link& link(int k) const { return links_[static_cast<std::size_t>(k)]; }
  const Joint& joint(int j) const { return joints_[static_cast<std::size_t>(j)]; }
  int numLinks() const { return static_cast<int>(links_.size()); }
  int numVariables() const { return static_cast<int>(variable_joint_.size()); }
  /// The joint that owns variable v (a non-mimic moving joint).
  int variableJoint(int v) const { return variable_joint_[static_cast<std::size_t>(v)]; }
  /// Name of variable v (its joint's name).
  const std::string& variableName(int v) const { return joint(variableJoint(v)).name; }
  /// Index of the link or joint of that name; throws SceneError naming it
  /// (and the robot) when there is none.
  int linkIndex(const std::string& name) const;
  int jointIndex(const std::string& name) const;
  /// -1 when there is no link or joint of that name.
  int findLink(const std::string& name) const;
  int findJoint(const std::string& name) const;
  /// The variable of joint `name`; throws SceneError when the joint does not
  /// exist, is fixed or is a mimic joint.
  int variableIndex(const std::string& name) const;
  /// All variables at 0, or at the middle of their limits when 0 is outside.
  std::vector<double> defaultConfiguration() const;

  /// The pose X_BL of every link in the root frame for the configuration q
  /// (numVariables() values). `X_BL` is resized to numLinks().
  void linkPoses(const double* q, std::vector<Eigen::Isometry3d>* X_BL) const;
  std::vector<Eigen::Isometry3d> linkPoses(const std::vector<double>& q) const;

  /// The joints on the path from the root to link k, root first (fixed ones
  /// included).
  std::vector<int> jointPath(int k) const;
  /// The last link that is an ancestor of both (or equal to one of) k and l.
  int commonAncestor(int k, int l) const;
  /// Upper bound of |x - o_j| over the points x of link k's pieces and every
  /// configuration within the joint limits, o_j the origin of joint j (j on
  /// k's jointPath): what a turn of j by an angle a can move a point of k (at
  /// most a times it). Sums the distances between the origins of the
  /// joints from j to k, the prismatic joints' largest extension on the way,
  /// and link k's radius.
  double reach(int j, int k) const;

 private:
  /// What linkPoses needs per joint beyond Joint, set up once: the
  /// coordinate axis of a revolute joint turning about +x, +y or +z (-1 for
  /// any other axis), and whether the joint's origin turns the frame.
  struct PoseKernel {
    int axis = -1;
    bool origin_turns = true;
  };
  std::string name_;
  std::vector<Link> links_;
  std::vector<Joint> joints_;
  std::vector<int> variable_joint_;
  std::vector<PoseKernel> kernels_;
};

/// Reads a URDF (see the file comment). `warnings` (if not null) receives
/// the meshes' load warnings and the joints taken as fixed (floating and
/// planar joints). Throws SceneError naming the file and the element for an
/// unreadable or malformed URDF, a mesh that is not found (with every place
/// searched) or cannot be read, a mimic joint whose leader is missing or
/// fixed, or a joint with bad limits or axis.
RobotModel loadRobotModel(const std::filesystem::path& urdf, const RobotLoadOptions& options = {},
                          std::vector<std::string>* warnings = nullptr);

/// Where a URDF's mesh `filename` is (see the file comment): the first
/// existing file of the search. file:// is stripped, other URI schemes are
/// refused. Throws SceneError naming `filename` and every place searched when
/// none exists.
std::filesystem::path resolveMeshPath(const std::string& filename, const std::filesystem::path& urdf,
                                      const std::vector<std::filesystem::path>& package_path, bool use_environment);

}  // namespace mddual::scene
