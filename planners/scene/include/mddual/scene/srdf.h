// SRDF files (MoveIt's semantic robot description), read with tinyxml2:
// planning groups (joints, links, chains, subgroups), group states, virtual
// joints and the collision matrix (disable_collisions,
// disable_default_collisions, enable_collisions). Elements the planning
// layer does not use (end effectors, passive joints, sphere models) are
// skipped.
//
// Names are kept as written; resolving them against a RobotModel
// (groupVariables, AllowedCollisions) checks every name and throws
// SceneError naming the SRDF, the element and the unknown name.
//
// Thread safety: plain data; the functions are pure.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "mddual/scene/robot_model.h"

namespace mddual::scene {

/// <group>: its members as written.
struct SrdfGroup {
  std::string name;
  std::vector<std::string> joints;
  std::vector<std::string> links;
  std::vector<std::pair<std::string, std::string>> chains;  ///< (base_link, tip_link)
  std::vector<std::string> subgroups;
};

/// <group_state>: named joint values of a group.
struct SrdfGroupState {
  std::string name;
  std::string group;
  std::vector<std::pair<std::string, double>> values;  ///< (joint, value)
};

/// <virtual_joint>: how the robot's root is attached to a frame.
struct SrdfVirtualJoint {
  std::string name;
  std::string type;  ///< fixed, floating or planar
  std::string parent_frame;
  std::string child_link;
};

/// A parsed SRDF.
struct Srdf {
  std::string source;      ///< the file (or label) it came from, for messages
  std::string robot_name;  ///< <robot name="...">
  std::vector<SrdfGroup> groups;
  std::vector<SrdfGroupState> group_states;
  std::vector<SrdfVirtualJoint> virtual_joints;
  /// <disable_collisions link1 link2>: pairs never checked.
  std::vector<std::pair<std::string, std::string>> disabled_pairs;
  /// <disable_default_collisions link>: links checked against no other link
  /// unless a pair re-enables it.
  std::vector<std::string> disabled_links;
  /// <enable_collisions link1 link2>: pairs checked despite disabled_links.
  std::vector<std::pair<std::string, std::string>> enabled_pairs;

  /// The group of that name, or nullptr.
  const SrdfGroup* findGroup(const std::string& name) const;
};

/// Reads an SRDF file. Throws SceneError naming the file (and the line and
/// element) when it cannot be read, is not well-formed XML, has no <robot>
/// root, or an element misses a required attribute or has a value that is
/// not a number.
Srdf loadSrdf(const std::filesystem::path& file);
/// The same on text in memory; `label` names it in messages.
Srdf parseSrdf(const std::string& text, const std::string& label);

/// The variables (RobotModel variable indices, ascending) that group `name`
/// moves: its joints (a mimic joint stands for its leader; fixed joints
/// add nothing), its links' parent joints, the joints on each chain from
/// base_link to tip_link, and its subgroups' variables. Throws SceneError
/// naming the SRDF and the group for an unknown group, joint or link, a
/// chain whose tip is not below its base, a cycle of subgroups, or a group
/// that moves no variable.
std::vector<int> groupVariables(const Srdf& srdf, const RobotModel& model, const std::string& name);

/// The values of group state `state` of group `group` as (variable, value)
/// pairs. Throws SceneError for an unknown state or joint name.
std::vector<std::pair<int, double>> groupStateValues(const Srdf& srdf, const RobotModel& model,
                                                     const std::string& group, const std::string& state);

/// Which contacts the collision checks skip (MoveIt's allowed collision
/// matrix): link pairs of the self check (the SRDF's collision matrix plus
/// any pair added later, such as a scene's matrix) and links allowed to touch
/// the world. Links are RobotModel link indices.
class AllowedCollisions {
 public:
  AllowedCollisions() = default;
  /// An empty filter for `model` (every pair checked).
  explicit AllowedCollisions(const RobotModel& model);
  /// The SRDF's matrix on `model`; throws SceneError naming the SRDF, the
  /// element and the link for a link the model does not have.
  AllowedCollisions(const RobotModel& model, const Srdf& srdf);
  /// Skip (or check) the pair k, l.
  void allow(int k, int l, bool allowed = true);
  /// Whether the pair k, l is skipped.
  bool allowed(int k, int l) const { return allowed_[index(k, l)] != 0; }
  /// Skip (or check) link k against the world.
  void allowWithWorld(int k, bool allowed = true) { world_[static_cast<std::size_t>(k)] = allowed ? 1 : 0; }
  bool allowedWithWorld(int k) const { return world_[static_cast<std::size_t>(k)] != 0; }
  int numLinks() const { return n_; }

 private:
  std::size_t index(int k, int l) const { return static_cast<std::size_t>(k) * static_cast<std::size_t>(n_) + l; }
  int n_ = 0;
  std::vector<char> allowed_;
  std::vector<char> world_;
};

}  // namespace mddual::scene
