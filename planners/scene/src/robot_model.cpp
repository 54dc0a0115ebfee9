// The articulated robot model: URDF joints and links, mesh look-up and
// forward kinematics (robot_model.h).
#include "mddual/scene/robot_model.h"

#include <urdf_model/model.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <sstream>

#include "scene_detail.h"
#include "urdf_detail.h"

namespace mddual::scene {
namespace {

using detail::display;
using detail::quote;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Largest |value| a joint takes within its limits (0 unless prismatic: a
/// rotation does not move the child frame's origin).
double extension(const Joint& j) {
  if (j.type != JointType::kPrismatic) return 0.0;
  return std::max(std::abs(j.lower), std::abs(j.upper));
}

std::string splitSearchPath(const char* text, std::vector<std::filesystem::path>* out) {
  if (text == nullptr) return {};
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ':')) {
    if (!item.empty()) out->emplace_back(item);
  }
  return text;
}

}  // namespace

const char* toString(JointType type) {
  switch (type) {
    case JointType::kFixed: return "fixed";
    case JointType::kRevolute: return "revolute";
    case JointType::kContinuous: return "continuous";
    case JointType::kPrismatic: return "prismatic";
  }
  return "unknown";
}

RobotModel::RobotModel(std::string name, std::vector<Link> links, std::vector<Joint> joints)
    : name_(std::move(name)), links_(std::move(links)), joints_(std::move(joints)) {
  const std::string who = "robot " + quote(name_);
  if (links_.empty()) throw SceneError(who + ": no links");
  const int nl = numLinks();
  for (int j = 0; j < static_cast<int>(joints_.size()); ++j) {
    Joint& joint = joints_[static_cast<std::size_t>(j)];
    const std::string where = who + ": joint " + quote(joint.name);
    if (joint.parent_link < 0 || joint.parent_link >= nl || joint.child_link <= joint.parent_link ||
        joint.child_link >= nl) {
      throw SceneError(where + ": its links are not in tree order");
    }
    if (link(joint.child_link).parent_joint != j) throw SceneError(where + ": its child link does not name it");
    if (!joint.X_PJ.matrix().allFinite()) throw SceneError(where + ": origin is not finite");
    if (joint.moves()) {
      const double n = joint.axis_J.norm();
      if (!std::isfinite(n) || n < 1e-12) throw SceneError(where + ": axis must be finite and nonzero");
      joint.axis_J /= n;
    }
    if (joint.type == JointType::kContinuous) {
      joint.lower = -kInf;
      joint.upper = kInf;
    } else if (joint.moves() &&
               !(std::isfinite(joint.lower) && std::isfinite(joint.upper) && joint.lower <= joint.upper)) {
      throw SceneError(where + ": limits must be finite with lower <= upper (got " + std::to_string(joint.lower) +
                       ", " + std::to_string(joint.upper) + ")");
    }
    if (!std::isfinite(joint.multiplier) || !std::isfinite(joint.offset)) {
      throw SceneError(where + ": mimic multiplier and offset must be finite");
    }
    if (!joint.moves()) joint.variable = -1;
    if (joint.moves() && !joint.mimic) {
      joint.variable = static_cast<int>(variable_joint_.size());
      variable_joint_.push_back(j);
    }
  }
  for (Joint& joint : joints_) {
    if (!joint.mimic) continue;
    if (joint.variable < 0 || joint.variable >= numVariables()) {
      throw SceneError(who + ": mimic joint " + quote(joint.name) + ": its leader is not a moving joint");
    }
  }
  for (const Joint& joint : joints_) {
    PoseKernel k;
    k.origin_turns = !joint.X_PJ.linear().isIdentity(0.0);
    for (int i = 0; i < 3 && joint.moves() && joint.type != JointType::kPrismatic; ++i) {
      if (joint.axis_J == Eigen::Vector3d::Unit(i)) k.axis = i;
    }
    kernels_.push_back(k);
  }
  for (Link& l : links_) {
    l.radius = 0.0;
    for (const Piece& p : l.pieces) {
      for (const Eigen::Vector3d& v : p.polytope.vertices()) l.radius = std::max(l.radius, v.norm());
    }
  }
}

int RobotModel::findLink(const std::string& name) const {
  for (int k = 0; k < numLinks(); ++k) {
    if (links_[static_cast<std::size_t>(k)].name == name) return k;
  }
  return -1;
}

int RobotModel::findJoint(const std::string& name) const {
  for (int j = 0; j < static_cast<int>(joints_.size()); ++j) {
    if (joints_[static_cast<std::size_t>(j)].name == name) return j;
  }
  return -1;
}

int RobotModel::linkIndex(const std::string& name) const {
  const int k = findLink(name);
  if (k < 0) throw SceneError("robot " + quote(name_) + ": no link " + quote(name));
  return k;
}

int RobotModel::jointIndex(const std::string& name) const {
  const int j = findJoint(name);
  if (j < 0) throw SceneError("robot " + quote(name_) + ": no joint " + quote(name));
  return j;
}

int RobotModel::variableIndex(const std::string& name) const {
  const Joint& j = joint(jointIndex(name));
  if (!j.moves()) throw SceneError("robot " + quote(name_) + ": joint " + quote(name) + " is fixed");
  if (j.mimic) throw SceneError("robot " + quote(name_) + ": joint " + quote(name) + " is a mimic joint");
  return j.variable;
}

std::vector<double> RobotModel::defaultConfiguration() const {
  std::vector<double> q(static_cast<std::size_t>(numVariables()), 0.0);
  for (int v = 0; v < numVariables(); ++v) {
    const Joint& j = joint(variableJoint(v));
    if (0.0 < j.lower || 0.0 > j.upper) q[static_cast<std::size_t>(v)] = 0.5 * (j.lower + j.upper);
  }
  return q;
}

void RobotModel::linkPoses(const double* q, std::vector<Eigen::Isometry3d>* X_BL) const {
  X_BL->resize(links_.size());
  (*X_BL)[0].setIdentity();
  for (std::size_t k = 1; k < links_.size(); ++k) {
    const std::size_t ji = static_cast<std::size_t>(links_[k].parent_joint);
    const Joint& j = joints_[ji];
    const PoseKernel& kernel = kernels_[ji];
    const Eigen::Isometry3d& P = (*X_BL)[static_cast<std::size_t>(j.parent_link)];
    Eigen::Isometry3d& X = (*X_BL)[k];
    // X = P * X_PJ, without the products that an origin with no turn (most
    // URDF joints) does not need.
    X.translation().noalias() = P.translation() + P.linear() * j.X_PJ.translation();
    if (kernel.origin_turns) {
      X.linear().noalias() = P.linear() * j.X_PJ.linear();
    } else {
      X.linear() = P.linear();
    }
    if (!j.moves()) continue;
    const double value = j.value(q[j.variable]);
    if (j.type == JointType::kPrismatic) {
      X.translation() += X.linear() * (value * j.axis_J);
      continue;
    }
    // A turn about a coordinate axis mixes two columns; any other axis goes
    // through its rotation matrix.
    if (kernel.axis < 0) {
      X.linear() = X.linear() * Eigen::AngleAxisd(value, j.axis_J).toRotationMatrix();
      continue;
    }
    const double c = std::cos(value);
    const double s = std::sin(value);
    const int u = (kernel.axis + 1) % 3;
    const int v = (kernel.axis + 2) % 3;
    const Eigen::Vector3d cu = X.linear().col(u);
    const Eigen::Vector3d cv = X.linear().col(v);
    X.linear().col(u) = c * cu + s * cv;
    X.linear().col(v) = c * cv - s * cu;
  }
}

std::vector<Eigen::Isometry3d> RobotModel::linkPoses(const std::vector<double>& q) const {
  if (static_cast<int>(q.size()) != numVariables()) {
    throw SceneError("robot " + quote(name_) + ": a configuration needs " + std::to_string(numVariables()) +
                     " values (got " + std::to_string(q.size()) + ")");
  }
  std::vector<Eigen::Isometry3d> X_BL;
  linkPoses(q.data(), &X_BL);
  return X_BL;
}

std::vector<int> RobotModel::jointPath(int k) const {
  std::vector<int> path;
  for (int l = k; link(l).parent_joint >= 0; l = joint(link(l).parent_joint).parent_link) {
    path.push_back(link(l).parent_joint);
  }
  std::reverse(path.begin(), path.end());
  return path;
}

int RobotModel::commonAncestor(int k, int l) const {
  // Parents have smaller indices than their children: walk the larger up.
  while (k != l) {
    if (k > l) {
      k = joint(link(k).parent_joint).parent_link;
    } else {
      l = joint(link(l).parent_joint).parent_link;
    }
  }
  return k;
}

double RobotModel::reach(int j, int k) const {
  const std::vector<int> path = jointPath(k);
  const auto it = std::find(path.begin(), path.end(), j);
  if (it == path.end()) {
    throw SceneError("robot " + quote(name_) + ": joint " + quote(joint(j).name) + " does not move link " +
                     quote(link(k).name));
  }
  double r = extension(joint(*it)) + link(k).radius;
  for (auto m = it + 1; m != path.end(); ++m) r += joint(*m).X_PJ.translation().norm() + extension(joint(*m));
  return r;
}

std::filesystem::path resolveMeshPath(const std::string& filename, const std::filesystem::path& urdf,
                                      const std::vector<std::filesystem::path>& package_path, bool use_environment) {
  if (filename.empty()) throw SceneError("mesh without a filename");
  std::string name = filename;
  std::string package;
  const std::string file_scheme = "file://";
  const std::string package_scheme = "package://";
  if (name.rfind(file_scheme, 0) == 0) {
    name = name.substr(file_scheme.size());
    if (std::filesystem::path(name).is_absolute()) return name;
  } else if (name.rfind(package_scheme, 0) == 0) {
    name = name.substr(package_scheme.size());
    const std::size_t slash = name.find('/');
    if (slash == std::string::npos || slash == 0 || slash + 1 == name.size()) {
      throw SceneError("mesh " + quote(filename) + ": a package URI is package://PACKAGE/PATH");
    }
    package = name.substr(0, slash);
    name = name.substr(slash + 1);
  } else {
    const std::size_t colon = name.find("://");
    if (colon != std::string::npos) {
      throw SceneError("mesh " + quote(filename) + ": URI scheme " + quote(name.substr(0, colon)) +
                       " is not supported");
    }
    if (std::filesystem::path(name).is_absolute()) {
      if (std::filesystem::is_regular_file(name)) return name;
      throw SceneError("mesh " + quote(filename) + " not found");
    }
  }
  // The folders to look in, in order.
  std::vector<std::filesystem::path> roots;
  std::filesystem::path dir = std::filesystem::absolute(urdf).lexically_normal().parent_path();
  while (true) {
    roots.push_back(dir);
    if (!dir.has_parent_path() || dir.parent_path() == dir) break;
    dir = dir.parent_path();
  }
  roots.insert(roots.end(), package_path.begin(), package_path.end());
  std::string environment;
  if (use_environment) environment = splitSearchPath(std::getenv("MDDUAL_PACKAGE_PATH"), &roots);

  std::vector<std::string> searched;
  auto tryPath = [&](const std::filesystem::path& p) {
    searched.push_back(display(p));
    return std::filesystem::is_regular_file(p);
  };
  for (const std::filesystem::path& root : roots) {
    if (package.empty()) {
      if (tryPath(root / name)) return root / name;
      continue;
    }
    if (root.filename() == package && tryPath(root / name)) return root / name;
    if (tryPath(root / package / name)) return root / package / name;
  }
  std::string message = "mesh " + quote(filename) + " not found; searched:";
  for (const std::string& s : searched) message += " " + s + ";";
  message += " add its folder with --package-path DIR or MDDUAL_PACKAGE_PATH";
  if (use_environment) message += environment.empty() ? " (unset)" : " (" + environment + ")";
  throw SceneError(message);
}

RobotModel loadRobotModel(const std::filesystem::path& urdf_file, const RobotLoadOptions& options,
                          std::vector<std::string>* warnings) {
  detail::requireFile(urdf_file);
  detail::requirePositiveTolerance(options.load.primitive_tolerance, display(urdf_file));
  detail::requireMeshConvexTolerance(options.load.mesh_convex_tolerance, display(urdf_file));
  const urdf::ModelInterfaceSharedPtr model = detail::parseUrdf(urdf_file, detail::requireShallowXml(urdf_file));
  const urdf::LinkConstSharedPtr root = model->getRoot();
  const std::string file = urdf_file.filename().string();
  if (!root) throw SceneError(display(urdf_file) + ": no root link");
  const detail::MeshSearch search{urdf_file, options.package_path, options.use_environment};
  LoadOptions load = options.load;
  load.recentre_mesh = false;

  // Links depth first from the root (a link's child joints by name, as
  // urdfdom keeps them), so that every parent comes before its children.
  std::vector<Link> links;
  std::vector<Joint> joints;
  std::vector<urdf::JointConstSharedPtr> urdf_joints;
  std::vector<std::pair<urdf::LinkConstSharedPtr, int>> stack = {{root, -1}};
  while (!stack.empty()) {
    const auto [ulink, parent_joint] = stack.back();
    stack.pop_back();
    const int k = static_cast<int>(links.size());
    Link link;
    link.name = ulink->name;
    link.parent_joint = parent_joint;
    for (std::size_t i = 0; i < ulink->collision_array.size(); ++i) {
      if (!ulink->collision_array[i]) continue;
      const std::string where = file + ": link " + quote(ulink->name) + ", collision " + std::to_string(i);
      detail::addCollision(*ulink->collision_array[i], Eigen::Isometry3d::Identity(), search, load, where, &link.pieces,
                           warnings, nullptr);
    }
    links.push_back(std::move(link));
    if (parent_joint >= 0) joints[static_cast<std::size_t>(parent_joint)].child_link = k;
    std::vector<urdf::JointSharedPtr> children = ulink->child_joints;
    std::sort(children.begin(), children.end(), [](const auto& a, const auto& b) { return a->name > b->name; });
    for (const urdf::JointSharedPtr& uj : children) {
      const std::string where = file + ": joint " + quote(uj->name);
      const urdf::LinkConstSharedPtr child = model->getLink(uj->child_link_name);
      if (!child) throw SceneError(where + ": child link " + quote(uj->child_link_name) + " not found");
      Joint joint;
      joint.name = uj->name;
      joint.parent_link = k;
      joint.X_PJ = detail::toIsometry(uj->parent_to_joint_origin_transform);
      joint.axis_J = Eigen::Vector3d(uj->axis.x, uj->axis.y, uj->axis.z);
      switch (uj->type) {
        case urdf::Joint::REVOLUTE: joint.type = JointType::kRevolute; break;
        case urdf::Joint::CONTINUOUS: joint.type = JointType::kContinuous; break;
        case urdf::Joint::PRISMATIC: joint.type = JointType::kPrismatic; break;
        case urdf::Joint::FIXED: joint.type = JointType::kFixed; break;
        default:
          joint.type = JointType::kFixed;
          if (warnings != nullptr) {
            warnings->push_back(where + ": a floating or planar joint, taken as fixed at its origin");
          }
      }
      if (uj->limits) {
        joint.lower = uj->limits->lower;
        joint.upper = uj->limits->upper;
      }
      if (joint.moves() && joint.type != JointType::kContinuous && !uj->limits) {
        throw SceneError(where + ": a " + std::string(toString(joint.type)) + " joint needs <limit>");
      }
      joints.push_back(joint);
      urdf_joints.push_back(uj);
      stack.emplace_back(child, static_cast<int>(joints.size()) - 1);
    }
  }
  // Joints in the order their child links were visited (tree order), so
  // that variables follow the chain from the root.
  std::vector<int> order(joints.size());
  for (std::size_t j = 0; j < joints.size(); ++j) order[j] = static_cast<int>(j);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return joints[std::size_t(a)].child_link < joints[std::size_t(b)].child_link; });
  std::vector<Joint> sorted;
  std::vector<urdf::JointConstSharedPtr> sorted_urdf;
  for (int j : order) {
    sorted.push_back(joints[static_cast<std::size_t>(j)]);
    sorted_urdf.push_back(urdf_joints[static_cast<std::size_t>(j)]);
    links[static_cast<std::size_t>(sorted.back().child_link)].parent_joint = static_cast<int>(sorted.size()) - 1;
  }
  for (Link& l : links) l.child_joints.clear();
  for (std::size_t j = 0; j < sorted.size(); ++j) {
    links[static_cast<std::size_t>(sorted[j].parent_link)].child_joints.push_back(static_cast<int>(j));
  }
  // Mimic joints: resolved to their root leader after the variables exist.
  std::map<std::string, int> index;
  for (std::size_t j = 0; j < sorted.size(); ++j) index[sorted[j].name] = static_cast<int>(j);
  for (std::size_t j = 0; j < sorted.size(); ++j) {
    const urdf::JointMimicSharedPtr& mimic = sorted_urdf[j]->mimic;
    if (!mimic || !sorted[j].moves()) continue;
    const std::string where = file + ": joint " + quote(sorted[j].name);
    double multiplier = mimic->multiplier;
    double offset = mimic->offset;
    std::string leader = mimic->joint_name;
    for (int hops = 0;; ++hops) {
      const auto it = index.find(leader);
      if (it == index.end()) throw SceneError(where + ": mimics " + quote(leader) + ", which does not exist");
      const urdf::JointMimicSharedPtr& next = sorted_urdf[static_cast<std::size_t>(it->second)]->mimic;
      if (!next) break;
      if (hops > static_cast<int>(sorted.size())) throw SceneError(where + ": its mimic joints form a cycle");
      offset = multiplier * next->offset + offset;
      multiplier *= next->multiplier;
      leader = next->joint_name;
    }
    const Joint& lead = sorted[static_cast<std::size_t>(index[leader])];
    if (!lead.moves()) throw SceneError(where + ": mimics " + quote(leader) + ", a fixed joint");
    sorted[j].mimic = true;
    sorted[j].multiplier = multiplier;
    sorted[j].offset = offset;
    sorted[j].variable = index[leader];  // the leader's joint index for now
  }
  // Variables in joint order (as the constructor numbers them); a mimic
  // joint takes its leader's.
  std::vector<int> variable_of(sorted.size(), -1);
  int variables = 0;
  for (std::size_t j = 0; j < sorted.size(); ++j) {
    if (sorted[j].moves() && !sorted[j].mimic) variable_of[j] = variables++;
  }
  for (Joint& joint : sorted) {
    if (joint.mimic) joint.variable = variable_of[static_cast<std::size_t>(joint.variable)];
  }
  try {
    return RobotModel(model->getName(), std::move(links), std::move(sorted));
  } catch (const SceneError& e) {  // the model's own checks (limits, axes): name the file
    throw SceneError(display(urdf_file) + ": " + e.what());
  }
}

}  // namespace mddual::scene
