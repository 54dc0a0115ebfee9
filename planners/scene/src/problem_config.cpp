// Reading OMPL.app benchmark configs (.cfg).
#include "mddual/scene/problem_config.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>

#include "mddual/defaults.h"
#include "problem_config_detail.h"
#include "scene_detail.h"

namespace mddual::scene {
namespace {

using detail::quote;

/// One "key = value" line.
struct Entry {
  std::string key;
  std::string value;
  int line = 0;
};

std::string trim(const std::string& s) {
  const std::size_t first = s.find_first_not_of(" \t\r\f\v");
  if (first == std::string::npos) return "";
  const std::size_t last = s.find_last_not_of(" \t\r\f\v");
  return s.substr(first, last - first + 1);
}

/// Reads the cfg into its three sections; throws on syntax errors.
class Reader {
 public:
  explicit Reader(const std::filesystem::path& file) : file_(file), name_(file.filename().string()) {}

  [[noreturn]] void fail(int line, const std::string& what) const {
    throw SceneError(name_ + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + what);
  }

  void read(std::map<std::string, std::vector<Entry>>* sections) const {
    detail::requireFile(file_);
    std::ifstream in(file_);
    if (!in) throw SceneError(detail::display(file_) + ": cannot open the file");
    std::string raw;
    std::string section;
    int number = 0;
    while (std::getline(in, raw)) {
      ++number;
      // A UTF-8 byte-order mark (some Windows editors write one) is no text.
      if (number == 1 && raw.rfind("\xEF\xBB\xBF", 0) == 0) raw.erase(0, 3);
      std::string text = raw.substr(0, raw.find('#'));  // '#' starts a comment anywhere (as boost's parser)
      text = trim(text);
      if (text.empty() || text[0] == ';') continue;
      if (text.front() == '[') {
        if (text.back() != ']') fail(number, "malformed section header " + quote(text));
        section = detail::lowerCase(trim(text.substr(1, text.size() - 2)));
        if (section != "problem" && section != "benchmark" && section != "planner") {
          fail(number, "unknown section [" + section + "] (expected [problem], [benchmark] or [planner])");
        }
        (*sections)[section];
        continue;
      }
      const std::size_t eq = text.find('=');
      if (eq == std::string::npos) fail(number, "expected 'key = value', got " + quote(text));
      Entry e{detail::lowerCase(trim(text.substr(0, eq))), trim(text.substr(eq + 1)), number};
      if (e.key.empty()) fail(number, "empty key");
      if (section.empty()) fail(number, quote(e.key) + " comes before any section");
      (*sections)[section].push_back(std::move(e));
    }
    if (in.bad()) throw SceneError(detail::display(file_) + ": read error");
  }

  double number(const Entry& e) const {
    const std::optional<double> v = detail::parseNumber(e.value);
    if (!v) fail(e.line, e.key + ": " + quote(e.value) + " is not a number");
    return *v;
  }

  bool boolean(const Entry& e) const {
    const std::string v = detail::lowerCase(e.value);
    if (v == "true" || v == "1" || v == "yes" || v == "on") return true;
    if (v == "false" || v == "0" || v == "no" || v == "off") return false;
    fail(e.line, e.key + ": " + quote(e.value) + " is not true or false");
  }

  int integer(const Entry& e) const {
    long long v = 0;
    const char* first = e.value.data();
    const char* last = first + e.value.size();
    if (first != last && *first == '+') ++first;
    const auto [ptr, ec] = std::from_chars(first, last, v);
    if (ec != std::errc() || ptr != last || first == last || v < 0 || v > std::numeric_limits<int>::max()) {
      fail(e.line, e.key + ": " + quote(e.value) + " is not an integer in [0, " +
                       std::to_string(std::numeric_limits<int>::max()) + "]");
    }
    return static_cast<int>(v);
  }

  const std::string& name() const { return name_; }

 private:
  std::filesystem::path file_;
  std::string name_;
};

/// [problem] keys OMPL.app declares, and ours (everything else is a space
/// parameter).
const std::vector<std::string>& declaredProblemKeys() {
  static const std::vector<std::string> keys = {"name",
                                                "robot",
                                                "world",
                                                "objective",
                                                "objective.threshold",
                                                "threshold",
                                                "solution_length",
                                                "start.x",
                                                "start.y",
                                                "start.z",
                                                "start.axis.x",
                                                "start.axis.y",
                                                "start.axis.z",
                                                "start.theta",
                                                "goal.x",
                                                "goal.y",
                                                "goal.z",
                                                "goal.axis.x",
                                                "goal.axis.y",
                                                "goal.axis.z",
                                                "goal.theta",
                                                "volume.min.x",
                                                "volume.min.y",
                                                "volume.min.z",
                                                "volume.max.x",
                                                "volume.max.y",
                                                "volume.max.z",
                                                "translation_only",
                                                "mesh_convex_tolerance"};
  return keys;
}

void readProblem(const Reader& r, const std::vector<Entry>& entries, ProblemConfig* c) {
  std::map<std::string, const Entry*> known;
  std::map<std::string, int> parameter_lines;
  const auto& declared = declaredProblemKeys();
  for (const Entry& e : entries) {
    if (e.key == "control") r.fail(e.line, "control-based problems (control = ...) are not supported");
    if (std::find(declared.begin(), declared.end(), e.key) != declared.end()) {
      const auto [it, inserted] = known.emplace(e.key, &e);
      if (!inserted) r.fail(e.line, e.key + " given twice (first at line " + std::to_string(it->second->line) + ")");
      continue;
    }
    const auto [it, inserted] = parameter_lines.emplace(e.key, e.line);
    if (!inserted) r.fail(e.line, e.key + " given twice (first at line " + std::to_string(it->second) + ")");
    c->space_parameters.emplace_back(e.key, e.value);
  }
  const auto has = [&](const std::string& k) { return known.count(k) != 0; };
  const auto text = [&](const std::string& k) { return known.at(k)->value; };
  const auto num = [&](const std::string& k) { return r.number(*known.at(k)); };
  const auto require = [&](const std::string& k) {
    if (!has(k)) r.fail(0, "[problem]: " + k + " is missing");
  };

  if (has("name")) c->name = text("name");
  for (const char* k : {"robot", "world"}) {
    require(k);
    if (text(k).empty()) r.fail(known.at(k)->line, std::string(k) + ": empty path");
  }
  c->robot = text("robot");
  c->world = text("world");

  // SE(3) as soon as any z or axis key appears; then all of them are needed.
  const std::vector<std::string> se3_only = {"start.z", "start.axis.x", "start.axis.y", "start.axis.z",
                                             "goal.z",  "goal.axis.x",  "goal.axis.y",  "goal.axis.z"};
  const bool se3 = std::any_of(se3_only.begin(), se3_only.end(), has);
  for (const char* k : {"start.x", "start.y", "start.theta", "goal.x", "goal.y", "goal.theta"}) require(k);
  if (se3) {
    for (const std::string& k : se3_only) {
      if (!has(k)) {
        r.fail(0, "[problem]: " + k + " is missing (a z or an axis is given, so the problem is SE(3) and needs " +
                      "start.z, start.axis.x/y/z, goal.z and goal.axis.x/y/z)");
      }
    }
  }
  for (const auto& [prefix, pose] :
       {std::make_pair(std::string("start."), &c->start), std::make_pair(std::string("goal."), &c->goal)}) {
    pose->position = Eigen::Vector3d(num(prefix + "x"), num(prefix + "y"), se3 ? num(prefix + "z") : 0.0);
    pose->axis = se3 ? Eigen::Vector3d(num(prefix + "axis.x"), num(prefix + "axis.y"), num(prefix + "axis.z"))
                     : Eigen::Vector3d::UnitZ();
    pose->theta = num(prefix + "theta");
  }
  c->space = se3 ? SpaceKind::kSE3 : SpaceKind::kSE2;

  // Volume: all of it or none of it (z optional in the plane).
  const std::vector<std::string> vol = {"volume.min.x", "volume.min.y", "volume.min.z",
                                        "volume.max.x", "volume.max.y", "volume.max.z"};
  if (std::any_of(vol.begin(), vol.end(), has)) {
    const bool z_given = has("volume.min.z") || has("volume.max.z");
    for (const std::string& k : vol) {
      const bool is_z = k.back() == 'z';
      if (!has(k) && (!is_z || se3 || z_given)) r.fail(0, "[problem]: " + k + " is missing (volume given in part)");
    }
    Eigen::Vector3d lo(num("volume.min.x"), num("volume.min.y"), has("volume.min.z") ? num("volume.min.z") : 0.0);
    Eigen::Vector3d hi(num("volume.max.x"), num("volume.max.y"), has("volume.max.z") ? num("volume.max.z") : 0.0);
    for (int i = 0; i < 3; ++i) {
      const std::string axis(1, "xyz"[i]);
      for (const auto& [key, v] :
           {std::make_pair("volume.min." + axis, lo[i]), std::make_pair("volume.max." + axis, hi[i])}) {
        // The state space's positions reach the volume's corners, and the
        // core's queries accept coordinates up to kMaxCoordinate.
        if (has(key) && !(std::abs(v) <= defaults::kMaxCoordinate)) {
          r.fail(known.at(key)->line, key + ": " + detail::formatNumber(v) + " is outside the supported range [-" +
                                          detail::formatNumber(defaults::kMaxCoordinate) + ", " +
                                          detail::formatNumber(defaults::kMaxCoordinate) + "]");
        }
      }
      if (lo[i] > hi[i]) {
        r.fail(known.at("volume.max." + axis)->line,
               "volume.max." + axis + " is below volume.min." + axis + " (empty volume)");
      }
    }
    c->volume = Eigen::AlignedBox3d(lo, hi);
  }

  if (has("threshold")) {
    c->threshold = num("threshold");
    if (*c->threshold < 0.0) r.fail(known.at("threshold")->line, "threshold: must be >= 0");
  }
  if (has("objective")) {
    c->objective = text("objective");
    if (!detail::isKnownObjective(c->objective)) {
      r.fail(known.at("objective")->line,
             "objective: unknown objective " + quote(c->objective) + " (length, max_min_clearance, mechanical_work)");
    }
  }
  if (has("objective.threshold")) c->objective_threshold = num("objective.threshold");
  if (has("solution_length")) c->solution_length = num("solution_length");
  if (has("mesh_convex_tolerance")) {
    c->mesh_convex_tolerance = num("mesh_convex_tolerance");
    if (!(*c->mesh_convex_tolerance >= 0.0 && *c->mesh_convex_tolerance <= kMaxMeshConvexTolerance)) {
      r.fail(known.at("mesh_convex_tolerance")->line,
             "mesh_convex_tolerance: must be in [0, " + detail::formatNumber(kMaxMeshConvexTolerance) +
                 "] (a fraction of each mesh's size; for a mesh's hull whatever its shape, load it with "
                 "mesh_convex_hull)");
    }
  }
  if (has("translation_only") && r.boolean(*known.at("translation_only"))) {
    c->space = se3 ? SpaceKind::kR3 : SpaceKind::kR2;
    if (!detail::sameRotation(c->start, c->goal, c->space)) {
      r.fail(known.at("translation_only")->line,
             "translation_only: the goal's rotation differs from the start's (the orientation is fixed at the "
             "start's)");
    }
  }
}

void readBenchmark(const Reader& r, const std::vector<Entry>& entries, ProblemConfig* c) {
  std::map<std::string, int> seen;
  for (const Entry& e : entries) {
    const auto [it, inserted] = seen.emplace(e.key, e.line);
    if (!inserted) r.fail(e.line, e.key + " given twice (first at line " + std::to_string(it->second) + ")");
    if (e.key == "time_limit") {
      c->time_limit = r.number(e);
      if (c->time_limit <= 0.0) r.fail(e.line, "time_limit: must be > 0");
    } else if (e.key == "mem_limit") {
      c->mem_limit = r.number(e);
      if (c->mem_limit <= 0.0) r.fail(e.line, "mem_limit: must be > 0");
    } else if (e.key == "run_count") {
      c->run_count = r.integer(e);
    } else if (e.key == "output") {
      c->output = e.value;
    } else if (e.key == "save_paths") {
      const std::string v = detail::lowerCase(e.value);
      if (v == "none") {
        c->save_paths = SavePaths::kNone;
      } else if (v == "all") {
        c->save_paths = SavePaths::kAll;
      } else if (v == "shortest" || v == "best") {
        c->save_paths = SavePaths::kShortest;
      } else {
        r.fail(e.line, "save_paths: " + quote(e.value) + " is not none, all or shortest");
      }
    } else if (e.key == "simplify") {
      c->simplify = r.boolean(e);
    } else {
      r.fail(e.line, "unknown [benchmark] key " + quote(e.key) +
                         " (time_limit, mem_limit, run_count, output, save_paths, simplify)");
    }
  }
}

void setPair(std::vector<std::pair<std::string, std::string>>* list, const std::string& key, const std::string& value) {
  for (auto& kv : *list) {
    if (kv.first == key) {
      kv.second = value;  // the last value wins, as in OMPL.app
      return;
    }
  }
  list->emplace_back(key, value);
}

void readPlanners(const Reader& r, const std::vector<Entry>& entries, const std::set<std::string>& extra,
                  ProblemConfig* c) {
  std::vector<std::pair<std::string, std::string>> pending_context;  // problem.* before any planner
  int pending_line = 0;
  int last = -1;  // the planner instance touched last
  for (const Entry& e : entries) {
    if (e.key.rfind("problem.", 0) == 0) {
      const std::string key = e.key.substr(8);
      if (key.empty()) r.fail(e.line, "empty key after 'problem.'");
      if (key == "objective") {  // one objective for the whole benchmark (OMPL.app)
        if (!detail::isKnownObjective(e.value))
          r.fail(e.line, "problem.objective: unknown objective " + quote(e.value));
        if (c->objective.empty()) {
          c->objective = e.value;
        } else if (c->objective != e.value) {
          r.fail(e.line, "problem.objective: planners cannot have different objectives (the problem's is " +
                             quote(c->objective) + ")");
        }
        continue;
      }
      if (last < 0) {
        setPair(&pending_context, key, e.value);
        pending_line = e.line;
      } else {
        setPair(&c->planners[static_cast<std::size_t>(last)].context, key, e.value);
      }
      continue;
    }
    const std::size_t dot = e.key.find('.');
    const std::string name = e.key.substr(0, dot);
    if (knownPlannerNames().count(name) == 0 && extra.count(name) == 0) {
      r.fail(e.line, "unknown planner " + quote(name));
    }
    const auto create = [&]() {
      PlannerSpec p;
      p.name = name;
      p.line = e.line;
      p.context = std::move(pending_context);
      pending_context.clear();
      c->planners.push_back(std::move(p));
      return static_cast<int>(c->planners.size()) - 1;
    };
    if (dot == std::string::npos) {
      if (!e.value.empty()) {
        r.fail(e.line, quote(name + " = " + e.value) + ": a planner line takes no value (parameters are " + name +
                           ".PARAM = value)");
      }
      last = create();
      continue;
    }
    const std::string param = e.key.substr(dot + 1);
    if (param.empty()) r.fail(e.line, "empty parameter name after " + quote(name + "."));
    int target = -1;
    for (int i = static_cast<int>(c->planners.size()) - 1; i >= 0; --i) {
      if (c->planners[static_cast<std::size_t>(i)].name == name) {
        target = i;
        break;
      }
    }
    if (target < 0) target = create();
    setPair(&c->planners[static_cast<std::size_t>(target)].params, param, e.value);
    last = target;
  }
  if (!pending_context.empty()) {
    r.fail(pending_line, "problem." + pending_context.front().first + " applies to no planner (none follows it)");
  }
}

}  // namespace

namespace detail {

bool isDeclaredProblemKey(const std::string& key) {
  const auto& keys = declaredProblemKeys();
  return key == "control" || std::find(keys.begin(), keys.end(), key) != keys.end();
}

}  // namespace detail

const std::set<std::string>& knownPlannerNames() {
  static const std::set<std::string> names = {
      // OMPL.app's ompl_benchmark (geometric planners)
      "rrtconnect", "lazyrrt", "lazyprm", "kpiece", "bkpiece", "lbkpiece", "est", "biest", "projest", "sbl", "prm",
      "rrt", "stride", "pdst", "rrtstar", "prmstar", "lazyprmstar", "spars", "spars2", "lbtrrt", "trrt", "fmt", "bfmt",
      "aps", "cforest",
      // OMPL 1.5's informed planners
      "bitstar", "abitstar", "aitstar", "informedrrtstar", "sorrtstar", "rrtsharp", "rrtxstatic"};
  return names;
}

ProblemConfig readProblemConfig(const std::filesystem::path& cfg, const std::set<std::string>& extra_planners) {
  const Reader reader(cfg);
  std::map<std::string, std::vector<Entry>> sections;
  reader.read(&sections);
  if (sections.count("problem") == 0) throw SceneError(reader.name() + ": no [problem] section");
  ProblemConfig config;
  config.file = cfg;
  readProblem(reader, sections["problem"], &config);
  readBenchmark(reader, sections["benchmark"], &config);
  readPlanners(reader, sections["planner"], extra_planners, &config);
  return config;
}

}  // namespace mddual::scene
