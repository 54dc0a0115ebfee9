// Arm problems (arm_problem.h).
#include "mddual/planning/arm_problem.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mddual/error.h"

namespace mddual::planning {
namespace {

std::string quote(const std::string& s) {
  return "'" + clipForMessage(s, 200) + "'";
}

/// Throws unless every group variable of q is within its joint's limits.
void requireWithinLimits(const scene::RobotModel& model, const std::vector<int>& group, const std::vector<double>& q,
                         const std::string& what) {
  for (int v : group) {
    const scene::Joint& j = model.joint(model.variableJoint(v));
    const double x = q[static_cast<std::size_t>(v)];
    if (x < j.lower || x > j.upper) {
      throw scene::SceneError(what + ": joint " + quote(j.name) + " = " + std::to_string(x) +
                              " is outside its limits [" + std::to_string(j.lower) + ", " + std::to_string(j.upper) +
                              "]");
    }
  }
}

/// Throws when q collides, naming the pair.
void requireFree(const ArmScene& scene, const std::vector<double>& q, const std::string& what) {
  ArmContact c;
  if (!scene.collides(q.data(), &c)) return;
  const scene::RobotModel& m = scene.model();
  const std::string other = c.other_link >= 0
                                ? "link " + quote(m.link(c.other_link).name)
                                : quote(scene.world().pieces()[static_cast<std::size_t>(c.world_piece)].origin);
  throw scene::SceneError(what + " is in collision: link " + quote(m.link(c.link).name) + " touches " + other);
}

}  // namespace

ArmRobot loadArmRobot(const std::filesystem::path& urdf, const std::filesystem::path& srdf,
                      const scene::RobotLoadOptions& options) {
  ArmRobot robot;
  robot.model = std::make_shared<const scene::RobotModel>(scene::loadRobotModel(urdf, options));
  robot.srdf = scene::loadSrdf(srdf);
  scene::AllowedCollisions check(*robot.model, robot.srdf);  // throws for an unknown link
  for (const scene::SrdfGroup& g : robot.srdf.groups) scene::groupVariables(robot.srdf, *robot.model, g.name);
  return robot;
}

ArmProblem loadArmProblem(const ArmRobot& robot, const scene::MbmProblemFiles& files,
                          const ArmProblemOptions& options) {
  const scene::RobotModel& model = *robot.model;
  ArmProblem p;
  p.files = files;
  const std::string dir = files.scene.parent_path().filename().string();
  char number[16];
  std::snprintf(number, sizeof number, "%04d", files.number);
  p.name = (dir.empty() ? "problem" : dir) + "-" + number;
  p.request = scene::loadMbmRequest(files.request);
  const scene::MbmScene mbm = scene::loadMbmScene(files.scene, model, options.load);
  p.warnings = mbm.warnings;
  p.group = options.group.empty() ? p.request.group : options.group;
  const std::string request_name = files.request.string();
  if (robot.srdf.findGroup(p.group) == nullptr) {
    throw scene::SceneError(request_name + ": group_name: the SRDF " + robot.srdf.source + " has no group " +
                            quote(p.group));
  }
  const std::vector<int> group = scene::groupVariables(robot.srdf, model, p.group);

  // The world, the allowed collisions (SRDF, then the scene's matrix).
  p.world = std::make_shared<const scene::World>(mbm.pieces, dir);
  scene::AllowedCollisions allowed(model, robot.srdf);
  for (const auto& [k, l] : mbm.allowed_link_pairs) allowed.allow(k, l);
  for (int k : mbm.links_allowed_with_world) allowed.allowWithWorld(k);
  p.scene = std::make_shared<const ArmScene>(robot.model, p.world, allowed, mbm.X_WB, options.scene);

  // Start: the scene's robot state, then the request's start state. Goal: the
  // start with the goal constraints' positions.
  const std::vector<double> scene_state = scene::applyJointValues(model, model.defaultConfiguration(), mbm.robot_state,
                                                                  files.scene.string() + ": robot_state");
  p.start = scene::applyJointValues(model, scene_state, p.request.start, request_name + ": start_state");
  p.goal = p.start;
  for (const scene::JointGoal& g : p.request.goal) {
    const int j = model.findJoint(g.joint);
    const std::string where = request_name + ": goal_constraints: joint " + quote(g.joint);
    if (j < 0) throw scene::SceneError(where + " is not in robot " + quote(model.name()));
    const int v = model.joint(j).variable;
    if (model.joint(j).mimic || std::find(group.begin(), group.end(), v) == group.end()) {
      throw scene::SceneError(where + " is not a joint of group " + quote(p.group));
    }
    p.goal[static_cast<std::size_t>(v)] = g.position;
  }
  requireWithinLimits(model, group, p.start, request_name + ": start_state");
  requireWithinLimits(model, group, p.goal, request_name + ": goal_constraints");
  p.space = ArmSpace::make(robot.model, group, p.start);
  requireFree(*p.scene, p.start, request_name + ": the start state");
  requireFree(*p.scene, p.goal, request_name + ": the goal state");
  return p;
}

std::vector<std::vector<double>> armTrajectoryStates(const ArmProblem& p, const scene::MbmTrajectory& trajectory,
                                                     const std::string& what) {
  const scene::RobotModel& model = p.space->model();
  const std::vector<int>& group = p.space->variables();
  for (const std::string& name : trajectory.joint_names) {
    const int j = model.findJoint(name);
    const bool in_group = j >= 0 && !model.joint(j).mimic &&
                          std::find(group.begin(), group.end(), model.joint(j).variable) != group.end();
    if (!in_group)
      throw scene::SceneError(what + ": joint_names: joint " + quote(name) + " is not in group " + quote(p.group));
  }
  for (int v : group) {
    const std::string& name = model.variableName(v);
    if (std::find(trajectory.joint_names.begin(), trajectory.joint_names.end(), name) == trajectory.joint_names.end()) {
      throw scene::SceneError(what + ": joint_names: lacks joint " + quote(name) + " of group " + quote(p.group));
    }
  }
  std::vector<std::vector<double>> states;
  for (std::size_t i = 0; i < trajectory.points.size(); ++i) {
    std::vector<std::pair<std::string, double>> values;
    for (std::size_t k = 0; k < trajectory.joint_names.size(); ++k) {
      values.emplace_back(trajectory.joint_names[k], trajectory.points[i][k]);
    }
    const std::string where = what + ": points[" + std::to_string(i) + "]";
    states.push_back(scene::applyJointValues(model, p.start, values, where));
    requireWithinLimits(model, group, states.back(), where);
  }
  return states;
}

scene::MbmTrajectory armTrajectory(const ArmProblem& p, const std::vector<std::vector<double>>& states) {
  scene::MbmTrajectory t;
  const scene::RobotModel& model = p.space->model();
  for (int v : p.space->variables()) t.joint_names.push_back(model.variableName(v));
  for (const std::vector<double>& q : states) {
    std::vector<double>& point = t.points.emplace_back();
    for (int v : p.space->variables()) point.push_back(q[static_cast<std::size_t>(v)]);
  }
  return t;
}

}  // namespace mddual::planning
