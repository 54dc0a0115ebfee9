// SRDF files through tinyxml2 (srdf.h).
#include "mddual/scene/srdf.h"

#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <stdexcept>

#include "scene_detail.h"

namespace mddual::scene {
namespace {

using detail::quote;

/// "file, line N, <element>" for messages.
std::string where(const std::string& source, const tinyxml2::XMLElement* e) {
  return source + ", line " + std::to_string(e->GetLineNum()) + ", <" + e->Name() + ">";
}

std::string requireAttribute(const std::string& source, const tinyxml2::XMLElement* e, const char* name) {
  const char* value = e->Attribute(name);
  if (value == nullptr || *value == '\0') {
    throw SceneError(where(source, e) + ": missing attribute " + quote(name));
  }
  return value;
}

double requireNumber(const std::string& source, const tinyxml2::XMLElement* e, const char* name) {
  const std::string text = requireAttribute(source, e, name);
  // A joint value is one number (multi-dof joints are not supported).
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  while (used < text.size() && std::isspace(static_cast<unsigned char>(text[used]))) ++used;
  if (used == 0 || used != text.size() || !std::isfinite(value)) {
    throw SceneError(where(source, e) + ": attribute " + quote(name) + " is not a finite number (" + quote(text) + ")");
  }
  return value;
}

std::string groupWhere(const Srdf& srdf, const std::string& group) {
  return srdf.source + ": group " + quote(group);
}

void collectVariables(const Srdf& srdf, const RobotModel& model, const std::string& name, std::set<int>* out,
                      std::vector<std::string>* stack) {
  const SrdfGroup* group = srdf.findGroup(name);
  if (group == nullptr) throw SceneError(srdf.source + ": no group " + quote(name));
  if (std::find(stack->begin(), stack->end(), name) != stack->end()) {
    throw SceneError(groupWhere(srdf, name) + ": its subgroups form a cycle");
  }
  stack->push_back(name);
  const std::string at = groupWhere(srdf, name);
  auto addJoint = [&](int j) {
    const Joint& joint = model.joint(j);
    if (joint.moves()) out->insert(joint.variable);
  };
  for (const std::string& joint : group->joints) {
    const int j = model.findJoint(joint);
    if (j < 0) throw SceneError(at + ": joint " + quote(joint) + " is not in robot " + quote(model.name()));
    addJoint(j);
  }
  for (const std::string& link : group->links) {
    const int k = model.findLink(link);
    if (k < 0) throw SceneError(at + ": link " + quote(link) + " is not in robot " + quote(model.name()));
    if (model.link(k).parent_joint >= 0) addJoint(model.link(k).parent_joint);
  }
  for (const auto& [base, tip] : group->chains) {
    const int b = model.findLink(base);
    const int t = model.findLink(tip);
    if (b < 0) throw SceneError(at + ": chain base link " + quote(base) + " is not in robot " + quote(model.name()));
    if (t < 0) throw SceneError(at + ": chain tip link " + quote(tip) + " is not in robot " + quote(model.name()));
    if (model.commonAncestor(b, t) != b) {
      throw SceneError(at + ": chain tip " + quote(tip) + " is not below its base " + quote(base));
    }
    for (int k = t; k != b; k = model.joint(model.link(k).parent_joint).parent_link) {
      addJoint(model.link(k).parent_joint);
    }
  }
  for (const std::string& sub : group->subgroups) collectVariables(srdf, model, sub, out, stack);
  stack->pop_back();
}

}  // namespace

const SrdfGroup* Srdf::findGroup(const std::string& name) const {
  for (const SrdfGroup& g : groups) {
    if (g.name == name) return &g;
  }
  return nullptr;
}

Srdf parseSrdf(const std::string& text, const std::string& label) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    throw SceneError(label + ": not well-formed XML (line " + std::to_string(doc.ErrorLineNum()) + ": " +
                     detail::briefReason(doc.ErrorStr() != nullptr ? doc.ErrorStr() : "unknown error") + ")");
  }
  const tinyxml2::XMLElement* robot = doc.RootElement();
  if (robot == nullptr || std::string(robot->Name()) != "robot") throw SceneError(label + ": no <robot> root element");
  Srdf srdf;
  srdf.source = label;
  if (const char* name = robot->Attribute("name")) srdf.robot_name = name;
  for (const tinyxml2::XMLElement* e = robot->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag == "group") {
      SrdfGroup g;
      g.name = requireAttribute(label, e, "name");
      for (const tinyxml2::XMLElement* m = e->FirstChildElement(); m != nullptr; m = m->NextSiblingElement()) {
        const std::string member = m->Name();
        if (member == "joint") {
          g.joints.push_back(requireAttribute(label, m, "name"));
        } else if (member == "link") {
          g.links.push_back(requireAttribute(label, m, "name"));
        } else if (member == "chain") {
          g.chains.emplace_back(requireAttribute(label, m, "base_link"), requireAttribute(label, m, "tip_link"));
        } else if (member == "group") {
          g.subgroups.push_back(requireAttribute(label, m, "name"));
        }
      }
      if (srdf.findGroup(g.name) != nullptr) throw SceneError(where(label, e) + ": group " + quote(g.name) + " twice");
      srdf.groups.push_back(std::move(g));
    } else if (tag == "group_state") {
      SrdfGroupState s;
      s.name = requireAttribute(label, e, "name");
      s.group = requireAttribute(label, e, "group");
      for (const tinyxml2::XMLElement* j = e->FirstChildElement("joint"); j != nullptr;
           j = j->NextSiblingElement("joint")) {
        s.values.emplace_back(requireAttribute(label, j, "name"), requireNumber(label, j, "value"));
      }
      srdf.group_states.push_back(std::move(s));
    } else if (tag == "virtual_joint") {
      srdf.virtual_joints.push_back({requireAttribute(label, e, "name"), requireAttribute(label, e, "type"),
                                     requireAttribute(label, e, "parent_frame"),
                                     requireAttribute(label, e, "child_link")});
    } else if (tag == "disable_collisions") {
      srdf.disabled_pairs.emplace_back(requireAttribute(label, e, "link1"), requireAttribute(label, e, "link2"));
    } else if (tag == "disable_default_collisions") {
      srdf.disabled_links.push_back(requireAttribute(label, e, "link"));
    } else if (tag == "enable_collisions") {
      srdf.enabled_pairs.emplace_back(requireAttribute(label, e, "link1"), requireAttribute(label, e, "link2"));
    }
  }
  return srdf;
}

Srdf loadSrdf(const std::filesystem::path& file) {
  detail::requireFile(file);
  return parseSrdf(detail::requireShallowXml(file), detail::display(file));
}

std::vector<int> groupVariables(const Srdf& srdf, const RobotModel& model, const std::string& name) {
  std::set<int> variables;
  std::vector<std::string> stack;
  collectVariables(srdf, model, name, &variables, &stack);
  if (variables.empty()) throw SceneError(groupWhere(srdf, name) + ": moves no joint (an empty group)");
  return {variables.begin(), variables.end()};
}

std::vector<std::pair<int, double>> groupStateValues(const Srdf& srdf, const RobotModel& model,
                                                     const std::string& group, const std::string& state) {
  for (const SrdfGroupState& s : srdf.group_states) {
    if (s.group != group || s.name != state) continue;
    std::vector<std::pair<int, double>> out;
    for (const auto& [joint, value] : s.values) {
      const int j = model.findJoint(joint);
      if (j < 0) {
        throw SceneError(srdf.source + ": group_state " + quote(state) + ": joint " + quote(joint) +
                         " is not in robot " + quote(model.name()));
      }
      if (model.joint(j).moves() && !model.joint(j).mimic) out.emplace_back(model.joint(j).variable, value);
    }
    return out;
  }
  throw SceneError(srdf.source + ": no group_state " + quote(state) + " of group " + quote(group));
}

AllowedCollisions::AllowedCollisions(const RobotModel& model)
    : n_(model.numLinks()),
      allowed_(static_cast<std::size_t>(n_) * static_cast<std::size_t>(n_), 0),
      world_(static_cast<std::size_t>(n_), 0) {}

AllowedCollisions::AllowedCollisions(const RobotModel& model, const Srdf& srdf) : AllowedCollisions(model) {
  auto linkOf = [&](const std::string& name, const char* element) {
    const int k = model.findLink(name);
    if (k < 0) {
      throw SceneError(srdf.source + ": <" + element + ">: link " + quote(name) + " is not in robot " +
                       quote(model.name()));
    }
    return k;
  };
  for (const std::string& link : srdf.disabled_links) {
    const int k = linkOf(link, "disable_default_collisions");
    for (int l = 0; l < n_; ++l) allow(k, l);
  }
  for (const auto& [a, b] : srdf.disabled_pairs)
    allow(linkOf(a, "disable_collisions"), linkOf(b, "disable_collisions"));
  for (const auto& [a, b] : srdf.enabled_pairs) {
    allow(linkOf(a, "enable_collisions"), linkOf(b, "enable_collisions"), false);
  }
}

void AllowedCollisions::allow(int k, int l, bool allowed) {
  allowed_[index(k, l)] = allowed ? 1 : 0;
  allowed_[index(l, k)] = allowed ? 1 : 0;
}

}  // namespace mddual::scene
