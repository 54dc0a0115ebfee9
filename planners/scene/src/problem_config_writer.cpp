// Writing OMPL.app benchmark configs, the pose convention, and the helpers
// the reader shares.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "mddual/defaults.h"
#include "mddual/scene/problem_config.h"
#include "problem_config_detail.h"
#include "scene_detail.h"

namespace mddual::scene {
namespace detail {

std::optional<double> parseNumber(const std::string& text) {
  const char* first = text.data();
  const char* last = first + text.size();
  if (first != last && *first == '+') ++first;
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(first, last, value);
  if (first == last || ec != std::errc() || ptr != last || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::string formatNumber(double value) {
  char buffer[64];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof(buffer), "%.*g", precision, value);
    const std::optional<double> back = parseNumber(buffer);
    if (back && *back == value) break;
  }
  return buffer;
}

bool isKnownObjective(const std::string& objective) {
  return objective == "length" || objective == "max_min_clearance" || objective == "mechanical_work";
}

bool sameRotation(const PoseSpec& start, const PoseSpec& goal, SpaceKind kind) {
  const Eigen::Quaterniond a(toIsometry(start, kind).linear());
  const Eigen::Quaterniond b(toIsometry(goal, kind).linear());
  return a.angularDistance(b) <= 1e-9;
}

}  // namespace detail

namespace {

using detail::formatNumber;
using detail::quote;

/// Throws unless `value` reads back as itself from a "key = value" line.
void requireWritable(const std::string& key, const std::string& value) {
  if (value.find_first_of("#\n\r") != std::string::npos) {
    throw SceneError("cannot write " + key + " = " + quote(value) + ": values cannot contain '#' or line breaks");
  }
  if (!value.empty() && (std::isspace(static_cast<unsigned char>(value.front())) != 0 ||
                         std::isspace(static_cast<unsigned char>(value.back())) != 0)) {
    throw SceneError("cannot write " + key + " = " + quote(value) + ": leading or trailing blanks would be lost");
  }
}

void requireKey(const std::string& key) {
  if (key.empty() || key.find_first_of("=#;[] \t\n\r") != std::string::npos) {
    throw SceneError("cannot write the key " + quote(key) + ": empty or with '=', '#', ';', '[', ']' or blanks");
  }
  for (const char ch : key) {
    if (std::tolower(static_cast<unsigned char>(ch)) != ch) {
      throw SceneError("cannot write the key " + quote(key) + ": keys are lower case (the reader lower-cases them)");
    }
  }
}

void line(std::ostream& out, const std::string& key, const std::string& value) {
  requireKey(key);
  requireWritable(key, value);
  out << key << " = " << value << "\n";
}

void number(std::ostream& out, const std::string& key, double value) {
  if (!std::isfinite(value)) throw SceneError("cannot write " + key + ": not a finite number");
  line(out, key, formatNumber(value));
}

void pose(std::ostream& out, const std::string& prefix, const PoseSpec& p, bool planar) {
  if (planar && (p.position.z() != 0.0 || p.axis != Eigen::Vector3d::UnitZ())) {
    throw SceneError("cannot write " + prefix + ": a planar pose needs z = 0 and the axis (0, 0, 1)");
  }
  number(out, prefix + ".x", p.position.x());
  number(out, prefix + ".y", p.position.y());
  if (!planar) {
    number(out, prefix + ".z", p.position.z());
    number(out, prefix + ".axis.x", p.axis.x());
    number(out, prefix + ".axis.y", p.axis.y());
    number(out, prefix + ".axis.z", p.axis.z());
  }
  number(out, prefix + ".theta", p.theta);
}

bool sameBox(const std::optional<Eigen::AlignedBox3d>& a, const std::optional<Eigen::AlignedBox3d>& b) {
  if (a.has_value() != b.has_value()) return false;
  return !a || (a->min() == b->min() && a->max() == b->max());
}

}  // namespace

bool isPlanar(SpaceKind kind) {
  return kind == SpaceKind::kSE2 || kind == SpaceKind::kR2;
}
bool isTranslationOnly(SpaceKind kind) {
  return kind == SpaceKind::kR2 || kind == SpaceKind::kR3;
}

const char* toString(SpaceKind kind) {
  switch (kind) {
    case SpaceKind::kSE2: return "se2";
    case SpaceKind::kSE3: return "se3";
    case SpaceKind::kR2: return "r2";
    case SpaceKind::kR3: return "r3";
  }
  return "?";
}

Eigen::Isometry3d toIsometry(const PoseSpec& pose, SpaceKind kind) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  if (isPlanar(kind)) {
    X.translation() = Eigen::Vector3d(pose.position.x(), pose.position.y(), 0.0);
    X.linear() = Eigen::AngleAxisd(pose.theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return X;
  }
  X.translation() = pose.position;
  // OMPL's SO3StateSpace::StateType::setAxisAngle: the axis is normalised, a
  // (near) zero axis gives the identity. Scaled by its largest component
  // first: the norm of an axis such as (1e308, 1e308, 0) overflows.
  const double largest = pose.axis.cwiseAbs().maxCoeff();
  if (!(largest > 0.0)) return X;
  const Eigen::Vector3d scaled = pose.axis / largest;
  if (scaled.norm() * largest >= 1e-9)
    X.linear() = Eigen::AngleAxisd(pose.theta, scaled.normalized()).toRotationMatrix();
  return X;
}

bool ProblemConfig::operator==(const ProblemConfig& o) const {
  return name == o.name && robot == o.robot && world == o.world && space == o.space && start == o.start &&
         goal == o.goal && sameBox(volume, o.volume) && objective == o.objective &&
         objective_threshold == o.objective_threshold && threshold == o.threshold &&
         solution_length == o.solution_length && mesh_convex_tolerance == o.mesh_convex_tolerance &&
         space_parameters == o.space_parameters && time_limit == o.time_limit && mem_limit == o.mem_limit &&
         run_count == o.run_count && output == o.output && save_paths == o.save_paths && simplify == o.simplify &&
         planners == o.planners;
}

std::filesystem::path resolvePath(const ProblemConfig& config, const std::filesystem::path& p) {
  return p.is_absolute() ? p : config.file.parent_path() / p;
}

void writeProblemConfig(const ProblemConfig& c, const std::filesystem::path& cfg) {
  const bool planar = isPlanar(c.space);
  if (isTranslationOnly(c.space) && !detail::sameRotation(c.start, c.goal, c.space)) {
    throw SceneError("cannot write " + detail::display(cfg) +
                     ": translation_only with a goal rotation different from the start's");
  }
  std::ostringstream out;
  out << "# OMPL.app benchmark config (written by mddual)\n[problem]\n";
  if (!c.name.empty()) line(out, "name", c.name);
  line(out, "robot", c.robot.string());
  line(out, "world", c.world.string());
  pose(out, "start", c.start, planar);
  pose(out, "goal", c.goal, planar);
  if (c.volume) {
    // What the reader refuses (the core's coordinate range), refused here.
    if (!(c.volume->min().cwiseAbs().maxCoeff() <= defaults::kMaxCoordinate &&
          c.volume->max().cwiseAbs().maxCoeff() <= defaults::kMaxCoordinate)) {
      throw SceneError("cannot write " + detail::display(cfg) + ": a volume corner is outside the supported range [-" +
                       detail::formatNumber(defaults::kMaxCoordinate) + ", " +
                       detail::formatNumber(defaults::kMaxCoordinate) + "]");
    }
    const char* axes[] = {"x", "y", "z"};
    const bool z = !planar || c.volume->min().z() != 0.0 || c.volume->max().z() != 0.0;
    for (int i = 0; i < (z ? 3 : 2); ++i) number(out, std::string("volume.min.") + axes[i], c.volume->min()[i]);
    for (int i = 0; i < (z ? 3 : 2); ++i) number(out, std::string("volume.max.") + axes[i], c.volume->max()[i]);
  }
  if (c.threshold) number(out, "threshold", *c.threshold);
  if (!c.objective.empty()) line(out, "objective", c.objective);
  if (c.objective_threshold) number(out, "objective.threshold", *c.objective_threshold);
  if (c.solution_length) number(out, "solution_length", *c.solution_length);
  if (isTranslationOnly(c.space)) line(out, "translation_only", "true");
  if (c.mesh_convex_tolerance) {
    if (!(*c.mesh_convex_tolerance >= 0.0 && *c.mesh_convex_tolerance <= kMaxMeshConvexTolerance)) {
      throw SceneError("cannot write " + detail::display(cfg) + ": mesh_convex_tolerance " +
                       formatNumber(*c.mesh_convex_tolerance) + " is not in [0, " +
                       formatNumber(kMaxMeshConvexTolerance) + "]");
    }
    number(out, "mesh_convex_tolerance", *c.mesh_convex_tolerance);
  }
  for (const auto& [key, value] : c.space_parameters) {
    if (detail::isDeclaredProblemKey(key)) {
      throw SceneError("cannot write the space parameter " + quote(key) + ": the reader takes it for its own key");
    }
    line(out, key, value);
  }

  out << "\n[benchmark]\n";
  number(out, "time_limit", c.time_limit);
  number(out, "mem_limit", c.mem_limit);
  if (c.run_count < 0) throw SceneError("cannot write run_count: negative");
  line(out, "run_count", std::to_string(c.run_count));
  if (!c.output.empty()) line(out, "output", c.output.string());
  line(out, "save_paths",
       c.save_paths == SavePaths::kAll        ? "all"
       : c.save_paths == SavePaths::kShortest ? "shortest"
                                              : "none");
  line(out, "simplify", c.simplify ? "true" : "false");

  out << "\n[planner]\n";
  for (const PlannerSpec& p : c.planners) {
    if (p.name.find('.') != std::string::npos) throw SceneError("cannot write the planner " + quote(p.name));
    line(out, p.name, "");
    for (const auto& [key, value] : p.params) line(out, p.name + "." + key, value);
    for (const auto& [key, value] : p.context) {
      if (key == "objective") throw SceneError("cannot write problem.objective for one planner: it is global");
      line(out, "problem." + key, value);
    }
  }

  std::ofstream file(cfg);
  if (!file) throw SceneError(detail::display(cfg) + ": cannot open the file for writing");
  file << out.str();
  file.close();
  if (!file) throw SceneError(detail::display(cfg) + ": write error");
}

}  // namespace mddual::scene
