// MotionBenchMaker problems through yaml-cpp (mbm_problem.h).
#include "mddual/scene/mbm_problem.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <regex>
#include <set>

#include "mddual/scene/builders.h"
#include "scene_detail.h"

namespace mddual::scene {
namespace {

using detail::display;
using detail::quote;

/// A field of a file, for messages and for reading.
class Field {
 public:
  Field(YAML::Node node, std::string file, std::string path)
      : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {}
  bool present() const { return node_.IsDefined() && !node_.IsNull(); }
  Field operator[](const std::string& key) const {
    if (present() && !node_.IsMap()) fail("is not a map");
    return Field(present() ? node_[key] : YAML::Node(YAML::NodeType::Undefined), file_, join(key));
  }
  Field operator[](std::size_t i) const { return Field(node_[i], file_, path_ + "[" + std::to_string(i) + "]"); }
  std::size_t size() const {
    if (!present()) return 0;
    if (!node_.IsSequence()) fail("is not a list");
    return node_.size();
  }
  bool isSequence() const { return node_.IsSequence(); }
  [[noreturn]] void fail(const std::string& what) const {
    throw SceneError(file_ + ": " + (path_.empty() ? "the document" : path_) + ": " + what);
  }
  void require() const {
    if (!present()) fail("missing");
  }
  double number() const {
    require();
    double v = 0.0;
    try {
      v = node_.as<double>();
    } catch (const YAML::Exception&) {
      fail("is not a number");
    }
    if (!std::isfinite(v)) fail("is not finite");
    return v;
  }
  std::string text() const {
    require();
    if (!node_.IsScalar()) fail("is not a string");
    return node_.Scalar();
  }
  std::vector<double> numbers() const {
    require();
    std::vector<double> out;
    for (std::size_t i = 0; i < size(); ++i) out.push_back((*this)[i].number());
    return out;
  }
  std::vector<std::string> texts() const {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < size(); ++i) out.push_back((*this)[i].text());
    return out;
  }
  /// [x, y, z] or {x, y, z}.
  Eigen::Vector3d vector() const {
    require();
    if (node_.IsSequence()) {
      if (size() != 3) fail("needs 3 values, got " + std::to_string(size()));
      return {(*this)[0].number(), (*this)[1].number(), (*this)[2].number()};
    }
    return {(*this)["x"].number(), (*this)["y"].number(), (*this)["z"].number()};
  }
  /// [x, y, z, w] or {x, y, z, w}; normalised (a zero quaternion is refused).
  Eigen::Quaterniond quaternion() const {
    require();
    Eigen::Quaterniond q;
    if (node_.IsSequence()) {
      if (size() != 4) fail("needs 4 values (x, y, z, w), got " + std::to_string(size()));
      q = Eigen::Quaterniond((*this)[3].number(), (*this)[0].number(), (*this)[1].number(), (*this)[2].number());
    } else {
      q = Eigen::Quaterniond((*this)["w"].number(), (*this)["x"].number(), (*this)["y"].number(),
                             (*this)["z"].number());
    }
    if (!(q.norm() > 1e-6)) fail("is not a rotation (zero quaternion)");
    return q.normalized();
  }
  /// A geometry_msgs/Pose: position and orientation, each optional.
  Eigen::Isometry3d pose() const {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    if (!present()) return X;
    if ((*this)["position"].present()) X.translation() = (*this)["position"].vector();
    if ((*this)["orientation"].present()) X.linear() = (*this)["orientation"].quaternion().toRotationMatrix();
    return X;
  }
  const std::string& path() const { return path_; }

 private:
  std::string join(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  YAML::Node node_;
  std::string file_;
  std::string path_;
};

Field loadYaml(const std::filesystem::path& file) {
  detail::requireFile(file);
  try {
    return Field(YAML::LoadFile(file.string()), display(file), "");
  } catch (const YAML::ParserException& e) {
    throw SceneError(display(file) + ": not valid YAML (line " + std::to_string(e.mark.line + 1) + ", column " +
                     std::to_string(e.mark.column + 1) + ": " + e.msg + ")");
  } catch (const YAML::Exception& e) {
    throw SceneError(display(file) + ": cannot be read (" + std::string(e.what()) + ")");
  }
}

std::vector<std::pair<std::string, double>> jointState(const Field& state) {
  std::vector<std::pair<std::string, double>> out;
  const Field js = state["joint_state"];
  if (!js.present()) return out;
  const std::vector<std::string> names = js["name"].texts();
  const Field positions = js["position"];
  if (positions.size() != names.size()) {
    positions.fail("has " + std::to_string(positions.size()) + " values for " + std::to_string(names.size()) +
                   " names");
  }
  for (std::size_t i = 0; i < names.size(); ++i) out.emplace_back(names[i], positions[i].number());
  return out;
}

/// A cone along z (base at -h/2, apex at +h/2), circumscribed like the
/// cylinders (the sides of the base within `tolerance` of the circle).
Piece conePiece(double radius, double height, const Eigen::Isometry3d& X_OC, double tolerance, std::string origin) {
  const int k = cylinderSides(radius, tolerance);
  const double r = radius / std::cos(kPi / k);
  std::vector<Eigen::Vector3d> points = {Eigen::Vector3d(0, 0, height / 2)};
  for (int i = 0; i < k; ++i) {
    const double a = 2 * kPi * i / k;
    points.emplace_back(r * std::cos(a), r * std::sin(a), -height / 2);
  }
  return convexPiece(points, X_OC, std::move(origin));
}

void addPrimitive(const Field& primitive, const Eigen::Isometry3d& X_WP, const LoadOptions& options,
                  const std::string& origin, std::vector<Piece>* out) {
  const Field type = primitive["type"];
  type.require();
  std::string name;
  try {
    const int number = std::stoi(type.text());
    const char* names[] = {"", "box", "sphere", "cylinder", "cone"};
    if (number >= 1 && number <= 4) name = names[number];
  } catch (const std::exception&) {
    name = detail::lowerCase(type.text());
  }
  const std::vector<double> d = primitive["dimensions"].numbers();
  auto need = [&](std::size_t n) {
    if (d.size() != n) {
      primitive["dimensions"].fail("a " + name + " needs " + std::to_string(n) + " values, got " +
                                   std::to_string(d.size()));
    }
    for (double v : d) {
      if (!(v > 0.0)) primitive["dimensions"].fail("sizes must be > 0");
    }
  };
  const std::string label = origin + " (" + name + ")";
  try {
    if (name == "box") {
      need(3);
      out->push_back(boxPiece(Eigen::Vector3d(d[0], d[1], d[2]), X_WP, label));
    } else if (name == "sphere") {
      need(1);
      out->push_back(spherePiece(d[0], X_WP, options.primitive_tolerance, label));
    } else if (name == "cylinder") {
      need(2);
      out->push_back(cylinderPiece(d[1], d[0], X_WP, options.primitive_tolerance, label));
    } else if (name == "cone") {
      need(2);
      out->push_back(conePiece(d[1], d[0], X_WP, options.primitive_tolerance, label));
    } else {
      type.fail("unknown primitive type " + quote(type.text()) + " (box, sphere, cylinder or cone)");
    }
  } catch (const SceneError& e) {
    if (std::string(e.what()).find(primitive.path()) != std::string::npos) throw;
    primitive.fail(e.what());
  }
}

void addMesh(const Field& mesh, const Eigen::Isometry3d& X_WM, const LoadOptions& options, const std::string& origin,
             std::vector<Piece>* out, std::vector<std::string>* warnings) {
  const Field vertices = mesh["vertices"];
  const Field triangles = mesh["triangles"];
  vertices.require();
  triangles.require();
  VertexArray v(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i) v.row(static_cast<Eigen::Index>(i)) = vertices[i].vector();
  TriangleArray t(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const Field tri = triangles[i].isSequence() ? triangles[i] : triangles[i]["vertex_indices"];
    const std::vector<double> idx = tri.numbers();
    if (idx.size() != 3) tri.fail("a triangle needs 3 vertex indices");
    for (int c = 0; c < 3; ++c) {
      const double x = idx[static_cast<std::size_t>(c)];
      if (x < 0 || x >= static_cast<double>(vertices.size()) || x != std::floor(x)) {
        tri.fail("vertex index " + std::to_string(x) + " is not one of the " + std::to_string(vertices.size()) +
                 " vertices");
      }
      t(static_cast<Eigen::Index>(i), c) = static_cast<int>(x);
    }
  }
  MeshInfo info;
  try {
    std::vector<Piece> pieces = meshArrayPieces(v, t, X_WM, options, origin + " (mesh)", &info);
    for (Piece& p : pieces) out->push_back(std::move(p));
  } catch (const SceneError& e) {
    mesh.fail(e.what());
  }
  if (warnings != nullptr) warnings->insert(warnings->end(), info.warnings.begin(), info.warnings.end());
}

/// The shortest decimal text that reads back as x (at most 17 digits).
std::string shortestText(double x) {
  char text[32];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, x);
    if (std::strtod(text, nullptr) == x) break;
  }
  return text;
}

}  // namespace

std::vector<MbmProblemFiles> listMbmProblems(const std::filesystem::path& dir) {
  if (!std::filesystem::is_directory(dir)) throw SceneError(display(dir) + ": not a directory");
  static const std::regex kName("(scene|request|trajectory)(\\d+)\\.yaml");
  std::map<int, MbmProblemFiles> found;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    std::smatch m;
    const std::string name = entry.path().filename().string();
    if (!std::regex_match(name, m, kName)) continue;
    const int number = std::stoi(m[2].str());
    MbmProblemFiles& p = found[number];
    p.number = number;
    const std::string kind = m[1].str();
    (kind == "scene" ? p.scene : kind == "request" ? p.request : p.trajectory) = entry.path();
  }
  std::vector<MbmProblemFiles> out;
  for (auto& [number, p] : found) {
    if (p.scene.empty() && p.request.empty()) {
      throw SceneError(display(p.trajectory) + ": no scene and request files for this trajectory");
    }
    if (p.scene.empty()) throw SceneError(display(p.request) + ": no scene file for this request");
    if (p.request.empty()) throw SceneError(display(p.scene) + ": no request file for this scene");
    out.push_back(p);
  }
  if (out.empty()) throw SceneError(display(dir) + ": no problems (sceneNNNN.yaml and requestNNNN.yaml)");
  return out;
}

MbmRequest loadMbmRequest(const std::filesystem::path& file) {
  const Field doc = loadYaml(file);
  MbmRequest r;
  r.group = doc["group_name"].text();
  if (doc["planner_id"].present()) r.planner_id = doc["planner_id"].text();
  if (doc["allowed_planning_time"].present()) r.allowed_planning_time = doc["allowed_planning_time"].number();
  r.start = jointState(doc["start_state"]);
  const Field goals = doc["goal_constraints"];
  if (goals.size() == 0) goals.fail("missing (a request needs joint goal constraints)");
  const Field joints = goals[0]["joint_constraints"];
  if (joints.size() == 0) joints.fail("missing (only joint goals are supported)");
  for (std::size_t i = 0; i < joints.size(); ++i) {
    JointGoal g;
    g.joint = joints[i]["joint_name"].text();
    g.position = joints[i]["position"].number();
    if (joints[i]["tolerance_above"].present()) g.tolerance_above = joints[i]["tolerance_above"].number();
    if (joints[i]["tolerance_below"].present()) g.tolerance_below = joints[i]["tolerance_below"].number();
    r.goal.push_back(g);
  }
  return r;
}

MbmTrajectory loadMbmTrajectory(const std::filesystem::path& file) {
  const Field doc = loadYaml(file);
  const Field jt = doc["joint_trajectory"];
  MbmTrajectory t;
  t.joint_names = jt["joint_names"].texts();
  if (t.joint_names.empty()) jt["joint_names"].fail("missing (a trajectory names its joints)");
  std::set<std::string> seen;
  for (std::size_t i = 0; i < t.joint_names.size(); ++i) {
    if (!seen.insert(t.joint_names[i]).second) {
      jt["joint_names"][i].fail("repeats joint " + quote(t.joint_names[i]));
    }
  }
  const Field points = jt["points"];
  if (points.size() == 0) points.fail("missing (a trajectory needs at least one point)");
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Field positions = points[i]["positions"];
    t.points.push_back(positions.numbers());
    if (t.points.back().size() != t.joint_names.size()) {
      positions.fail("has " + std::to_string(t.points.back().size()) + " values for " +
                     std::to_string(t.joint_names.size()) + " joints");
    }
  }
  return t;
}

void saveMbmTrajectory(const std::filesystem::path& file, const MbmTrajectory& trajectory,
                       const std::vector<std::string>& comment) {
  YAML::Emitter out;
  out << YAML::BeginMap << YAML::Key << "joint_trajectory" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "joint_names" << YAML::Value << YAML::Flow << trajectory.joint_names;
  out << YAML::Key << "points" << YAML::Value << YAML::BeginSeq;
  for (const std::vector<double>& point : trajectory.points) {
    std::vector<std::string> values;
    for (double x : point) values.push_back(shortestText(x));
    out << YAML::BeginMap << YAML::Key << "positions" << YAML::Value << YAML::Flow << values << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap << YAML::EndMap;
  // Written beside the file, then renamed over it: no half-written file.
  std::filesystem::path part = file;
  part += ".part";
  {
    std::ofstream f(part);
    for (const std::string& line : comment) f << "# " << line << "\n";
    f << out.c_str() << "\n";
    if (!f.flush()) throw SceneError(display(file) + ": cannot be written (" + std::strerror(errno) + ")");
  }
  std::error_code ec;
  std::filesystem::rename(part, file, ec);
  if (ec) {
    std::filesystem::remove(part, ec);
    throw SceneError(display(file) + ": cannot be written (" + ec.message() + ")");
  }
}

std::vector<double> applyJointValues(const RobotModel& model, std::vector<double> base,
                                     const std::vector<std::pair<std::string, double>>& values,
                                     const std::string& what) {
  for (const auto& [name, value] : values) {
    const int j = model.findJoint(name);
    if (j < 0) throw SceneError(what + ": joint " + quote(name) + " is not in robot " + quote(model.name()));
    const Joint& joint = model.joint(j);
    if (!std::isfinite(value)) throw SceneError(what + ": joint " + quote(name) + ": value is not finite");
    if (!joint.moves() || joint.mimic) continue;
    base[static_cast<std::size_t>(joint.variable)] = value;
  }
  return base;
}

MbmScene loadMbmScene(const std::filesystem::path& file, const RobotModel& model, const LoadOptions& options) {
  const Field doc = loadYaml(file);
  const std::string name = file.filename().string();
  MbmScene scene;
  scene.robot_state = jointState(doc["robot_state"]);
  const std::vector<double> q =
      applyJointValues(model, model.defaultConfiguration(), scene.robot_state, display(file) + ": robot_state");
  // Frames: W, the fixed frames, the robot's links.
  std::map<std::string, Eigen::Isometry3d> frames = {{"", Eigen::Isometry3d::Identity()},
                                                     {"world", Eigen::Isometry3d::Identity()}};
  const Field fixed = doc["fixed_frame_transforms"];
  for (std::size_t i = 0; i < fixed.size(); ++i) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    const Field t = fixed[i]["transform"];
    X.translation() = t["translation"].vector();
    X.linear() = t["rotation"].quaternion().toRotationMatrix();
    const std::string child = fixed[i]["child_frame_id"].text();
    if (child == model.link(0).name) scene.X_WB = X;
    frames[child] = X;
  }
  const std::vector<Eigen::Isometry3d> X_BL = model.linkPoses(q);
  for (int k = 0; k < model.numLinks(); ++k) frames.emplace(model.link(k).name, scene.X_WB * X_BL[std::size_t(k)]);

  const Field objects = doc["world"]["collision_objects"];
  std::vector<std::string> object_ids;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const Field object = objects[i];
    const std::string id = object["id"].present() ? object["id"].text() : std::to_string(i);
    object_ids.push_back(id);
    std::string frame = object["header"]["frame_id"].present() ? object["header"]["frame_id"].text() : "world";
    if (!frame.empty() && frame[0] == '/') frame = frame.substr(1);
    const auto f = frames.find(frame);
    if (f == frames.end()) object["header"]["frame_id"].fail("unknown frame " + quote(frame));
    const Eigen::Isometry3d X_WO = f->second * object["pose"].pose();
    const std::string origin = name + ": object " + quote(id);
    const Field primitives = object["primitives"];
    const Field primitive_poses = object["primitive_poses"];
    if (primitive_poses.size() != primitives.size()) {
      primitive_poses.fail("has " + std::to_string(primitive_poses.size()) + " poses for " +
                           std::to_string(primitives.size()) + " primitives");
    }
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      addPrimitive(primitives[p], X_WO * primitive_poses[p].pose(), options,
                   origin + ", primitive " + std::to_string(p), &scene.pieces);
    }
    const Field meshes = object["meshes"];
    const Field mesh_poses = object["mesh_poses"];
    if (mesh_poses.size() != meshes.size()) {
      mesh_poses.fail("has " + std::to_string(mesh_poses.size()) + " poses for " + std::to_string(meshes.size()) +
                      " meshes");
    }
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      addMesh(meshes[m], X_WO * mesh_poses[m].pose(), options, origin + ", mesh " + std::to_string(m), &scene.pieces,
              &scene.warnings);
    }
  }
  // The allowed collision matrix: link pairs, and links against objects.
  const Field acm = doc["allowed_collision_matrix"];
  const std::vector<std::string> entries = acm["entry_names"].texts();
  const Field values = acm["entry_values"];
  if (values.present() && values.size() != entries.size()) {
    values.fail("has " + std::to_string(values.size()) + " rows for " + std::to_string(entries.size()) + " names");
  }
  for (std::size_t a = 0; a < values.size(); ++a) {
    const Field row = values[a]["enabled"];
    if (row.size() != entries.size()) row.fail("needs " + std::to_string(entries.size()) + " values");
    const int ka = model.findLink(entries[a]);
    int allowed_objects = 0;
    for (std::size_t b = 0; b < entries.size(); ++b) {
      const std::string v = detail::lowerCase(row[b].text());
      if (v != "true" && v != "1") continue;
      const int kb = model.findLink(entries[b]);
      if (ka >= 0 && kb >= 0) scene.allowed_link_pairs.emplace_back(ka, kb);
      if (ka >= 0 && kb < 0 && std::find(object_ids.begin(), object_ids.end(), entries[b]) != object_ids.end()) {
        ++allowed_objects;
      }
    }
    if (ka >= 0 && allowed_objects > 0) {
      if (allowed_objects == static_cast<int>(object_ids.size())) {
        scene.links_allowed_with_world.push_back(ka);
      } else {
        scene.warnings.push_back(name + ": allowed_collision_matrix: link " + quote(entries[a]) +
                                 " is allowed to touch some objects only; it is checked against all of them");
      }
    }
  }
  return scene;
}

}  // namespace mddual::scene
