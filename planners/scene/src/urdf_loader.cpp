// URDF files through urdfdom: every collision element of every link, at the
// link's pose with all joints fixed at their origins.
#include <console_bridge/console.h>
#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <string>

#include "mddual/scene/loaders.h"
#include "mddual/scene/robot_model.h"
#include "scene_detail.h"
#include "urdf_detail.h"

namespace mddual::scene::detail {
namespace {

/// Collects urdfdom's console_bridge messages while a file is parsed, so the
/// SceneError can say what the parser objected to (and stderr stays quiet).
class CaptureHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char* /*filename*/, int /*line*/) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) {
      if (!messages_.empty()) messages_ += "; ";
      messages_ += text;
    }
  }
  const std::string& messages() const { return messages_; }

 private:
  std::string messages_;
};

/// console_bridge's handler is process-wide: one parse at a time.
std::mutex& parseMutex() {
  static std::mutex m;
  return m;
}

/// NUL bytes after the text handed to urdfdom. Its parser (TinyXML 2.6)
/// steps over a UTF-8 character by the length its lead byte announces, so a
/// file ending in a truncated multi-byte character (a lead byte 0xC2-0xF4 and
/// fewer continuation bytes) made it step past the string's terminator and
/// read beyond the buffer (found by fuzz_urdf; fuzz/findings/
/// urdf-truncated-utf8). A lead byte announces at most 4 bytes, so after 4
/// more NULs every such step still lands on a NUL inside the string.
constexpr std::size_t kXmlParserPadding = 4;

/// Refuses a joint graph with a loop before urdfdom sees it: urdfdom links a
/// joint's child into its parent's children with shared pointers, so a joint
/// whose parent is its own child, or a chain of joints back to a link above,
/// makes a reference cycle that it leaks when it then rejects the file
/// (found by fuzz_urdf; fuzz/findings/urdf-joint-loop), and a link with two
/// parent joints hangs its tree building. Text that is not well-formed XML is
/// refused here too: urdfdom's own parser accepts some of it (text after the
/// root element), and so would see a loop this check could not read
/// (fuzz/findings/urdf-loop-in-malformed-xml).
void requireJointTree(const std::filesystem::path& file, const std::string& xml) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS) {
    throw SceneError(display(file) + ":" + std::to_string(doc.ErrorLineNum()) +
                     ": not a valid URDF (not well-formed XML: " + doc.ErrorName() + ")");
  }
  const tinyxml2::XMLElement* robot = doc.FirstChildElement("robot");
  if (robot == nullptr) return;
  std::map<std::string, std::pair<std::string, std::string>> parent_of;  // child -> (parent, joint)
  for (const tinyxml2::XMLElement* j = robot->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    const tinyxml2::XMLElement* parent = j->FirstChildElement("parent");
    const tinyxml2::XMLElement* child = j->FirstChildElement("child");
    const char* p = parent ? parent->Attribute("link") : nullptr;
    const char* c = child ? child->Attribute("link") : nullptr;
    if (p == nullptr || c == nullptr) continue;  // urdfdom names what is missing
    const std::string name = j->Attribute("name") ? j->Attribute("name") : "";
    const std::string where = display(file) + ":" + std::to_string(j->GetLineNum()) + ": joint '" + name + "'";
    if (std::string(p) == c) throw SceneError(where + ": its parent and child are the same link '" + p + "'");
    const auto [it, added] = parent_of.emplace(c, std::make_pair(std::string(p), name));
    if (!added) {
      throw SceneError(where + ": link '" + c + "' is already the child of joint '" + it->second.second +
                       "' (a link has one parent joint)");
    }
  }
  // Follow each link's parents up; a link met twice closes a loop.
  for (const auto& [start, unused] : parent_of) {
    std::set<std::string> seen{start};
    for (auto it = parent_of.find(start); it != parent_of.end(); it = parent_of.find(it->second.first)) {
      if (!seen.insert(it->second.first).second) {
        throw SceneError(display(file) + ": the joints form a loop through link '" + it->second.first + "' (joint '" +
                         it->second.second + "'): a URDF robot is a tree");
      }
    }
  }
}

}  // namespace

urdf::ModelInterfaceSharedPtr parseUrdf(const std::filesystem::path& file, std::string xml) {
  requireJointTree(file, xml);
  xml.append(kXmlParserPadding, '\0');
  std::lock_guard<std::mutex> lock(parseMutex());
  CaptureHandler capture;
  console_bridge::OutputHandler* previous = console_bridge::getOutputHandler();
  console_bridge::useOutputHandler(&capture);
  urdf::ModelInterfaceSharedPtr model;
  std::string exception;
  try {
    model = urdf::parseURDF(xml);
  } catch (const std::exception& e) {
    exception = e.what();
  }
  console_bridge::useOutputHandler(previous);
  // urdfdom drops an element it cannot parse (an unknown geometry such as a
  // capsule, a mesh without filename, a malformed vector), logs an error and
  // still returns a model: any logged error is a failure here.
  if (!model || !capture.messages().empty()) {
    std::string why = capture.messages();
    if (!exception.empty()) why += (why.empty() ? "" : "; ") + exception;
    if (why.empty()) why = "urdfdom rejected it";
    throw SceneError(display(file) + ": not a valid URDF (" + why + ")");
  }
  return model;
}

Eigen::Isometry3d toIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  Eigen::Quaterniond q(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z);
  if (!(q.norm() > 0.0)) q = Eigen::Quaterniond::Identity();
  X.linear() = q.normalized().toRotationMatrix();
  return X;
}

void addCollision(const urdf::Collision& collision, const Eigen::Isometry3d& X_RL, const MeshSearch& search,
                  const LoadOptions& options, const std::string& where, std::vector<Piece>* out,
                  std::vector<std::string>* warnings, MeshCounts* counts) {
  if (!collision.geometry) throw SceneError(where + ": no geometry");
  const Eigen::Isometry3d X_RG = X_RL * toIsometry(collision.origin);
  const double tol = options.primitive_tolerance;
  switch (collision.geometry->type) {
    case urdf::Geometry::BOX: {
      const auto& box = static_cast<const urdf::Box&>(*collision.geometry);
      out->push_back(boxPiece(Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z), X_RG, where + " (box)"));
      return;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& cyl = static_cast<const urdf::Cylinder&>(*collision.geometry);
      out->push_back(cylinderPiece(cyl.radius, cyl.length, X_RG, tol, where + " (cylinder)"));
      return;
    }
    case urdf::Geometry::SPHERE: {
      const auto& sphere = static_cast<const urdf::Sphere&>(*collision.geometry);
      out->push_back(spherePiece(sphere.radius, X_RG, tol, where + " (sphere)"));
      return;
    }
    case urdf::Geometry::MESH: {
      const auto& mesh = static_cast<const urdf::Mesh&>(*collision.geometry);
      std::filesystem::path path;
      try {
        path = resolveMeshPath(mesh.filename, search.urdf, search.package_path, search.use_environment);
      } catch (const SceneError& e) {
        throw SceneError(where + ": " + e.what());
      }
      const Eigen::Vector3d scale(mesh.scale.x, mesh.scale.y, mesh.scale.z);
      LoadOptions mesh_options = options;
      mesh_options.recentre_mesh = false;  // a URDF places its meshes itself
      std::vector<Piece> pieces;
      MeshInfo info;
      try {
        pieces = meshPiecesWithOrigin(path, scale, X_RG, mesh_options, where + " (mesh " + quote(mesh.filename) + ")",
                                      &info);
      } catch (const SceneError& e) {
        throw SceneError(where + ": mesh " + quote(mesh.filename) + ": " + e.what());
      }
      if (warnings != nullptr) {
        for (const std::string& w : info.warnings) warnings->push_back(where + ": " + w);
      }
      if (counts != nullptr) counts->add(info, mesh_options.mesh_convex_hull);
      for (Piece& p : pieces) out->push_back(std::move(p));
      return;
    }
  }
  throw SceneError(where + ": unsupported geometry type");
}

bool isUrdf(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".urdf";
}

std::vector<Piece> urdfPieces(const std::filesystem::path& file, const LoadOptions& options, std::string* robot_name,
                              std::vector<std::string>* warnings, MeshCounts* counts) {
  requireFile(file);
  requirePositiveTolerance(options.primitive_tolerance, display(file));
  // urdfdom's XML parser recurses once per nesting level: checked first.
  const urdf::ModelInterfaceSharedPtr model = parseUrdf(file, requireShallowXml(file));
  if (robot_name != nullptr) *robot_name = model->getName();
  const urdf::LinkConstSharedPtr root = model->getRoot();
  if (!root) throw SceneError(display(file) + ": no root link");
  const MeshSearch search{file, {}, true};
  const std::string name = file.filename().string();

  // Depth-first from the root, composing joint origins (joints at zero).
  std::vector<Piece> pieces;
  std::vector<std::pair<urdf::LinkConstSharedPtr, Eigen::Isometry3d>> stack = {{root, Eigen::Isometry3d::Identity()}};
  while (!stack.empty()) {
    const auto [link, X_RL] = stack.back();
    stack.pop_back();
    for (std::size_t i = 0; i < link->collision_array.size(); ++i) {
      const std::string where = name + ": link " + quote(link->name) + ", collision " + std::to_string(i);
      if (!link->collision_array[i]) continue;
      addCollision(*link->collision_array[i], X_RL, search, options, where, &pieces, warnings, counts);
    }
    for (const urdf::JointSharedPtr& joint : link->child_joints) {
      const urdf::LinkConstSharedPtr child = model->getLink(joint->child_link_name);
      if (!child) {
        throw SceneError(display(file) + ": joint " + quote(joint->name) + ": child link " +
                         quote(joint->child_link_name) + " not found");
      }
      stack.emplace_back(child, X_RL * toIsometry(joint->parent_to_joint_origin_transform));
    }
  }
  return pieces;
}

}  // namespace mddual::scene::detail
