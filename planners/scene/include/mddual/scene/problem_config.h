// OMPL.app benchmark configs (.cfg, INI): the problem, the benchmark limits
// and the planners, as a struct with a reader and a writer, and the scene the
// problem describes.
//
// Format (OMPL.app's ompl_benchmark; keys are "name = value", one per line;
// comments are lines starting with '#' or ';', and anything after a '#'):
//
//   [problem]
//   name = maze                 experiment name
//   robot = car.dae             robot: URDF or mesh, relative to the cfg's folder
//   world = maze.urdf           world: URDF or mesh, relative to the cfg's folder
//   start.x, start.y, start.theta             SE(2): no z and no axis anywhere
//   start.z, start.axis.x/y/z                 SE(3): all of them, for start and goal
//   goal.x, goal.y, goal.theta (goal.z, goal.axis.x/y/z)
//                               a pose is the translation and the rotation of
//                               theta radians about the axis (SE(2): about z;
//                               the pose lies at z = 0)
//   volume.min.x/y(/z), volume.max.x/y(/z)    position bounds; when absent,
//                               the world's bounding box widened to hold start
//                               and goal (loadProblemScene)
//   threshold = 1e-6            goal tolerance (OMPL.app's default 1e-6)
//   objective = length          length | max_min_clearance | mechanical_work
//   objective.threshold = 0     cost threshold of the objective
//   solution_length = ...       kept (OMPL.app reads it and does not use it)
//   translation_only = true     OURS: plan translations only, the orientation
//                               fixed at the start's; the state space is R^3
//                               (R^2 for an SE(2)-style problem) with the same
//                               position bounds; the goal's rotation must equal
//                               the start's
//   mesh_convex_tolerance = 1e-4
//                               OURS: a mesh loads as one convex piece (its
//                               hull) when the hull differs from it by at most
//                               this fraction of its size (LoadOptions::
//                               mesh_convex_tolerance; default 1e-4, in
//                               [0, 1e-2])
//   <any other key> = value     a parameter of OMPL's space information, e.g.
//                               longest_valid_segment_fraction = 0.01, sampler
//
//   [benchmark]
//   time_limit = 5              seconds per run (OMPL's default 5)
//   mem_limit = 4096            MB per run (OMPL's default 4096)
//   run_count = 100             runs per planner (OMPL's default 100; 0: as many
//                               as fit in time_limit)
//   output = results            folder of the log, relative to the cfg's folder
//                               (default: the cfg's folder; the log is named
//                               after the cfg, <cfg stem>.log)
//   save_paths = none           none | all | shortest (OMPL.app; "best" = shortest)
//   simplify = true             simplify solutions (OMPL's default true)
//
//   [planner]
//   rrtconnect =                a new instance of a planner (OMPL.app's names)
//   rrtconnect.range = 50       a parameter of the last instance of that
//                               planner (creates one if there is none)
//   problem.KEY = value         a space-information parameter for the planner
//                               declared last (or, before any, the next one)
//
// Keys of [planner] and unknown [problem] keys are lower-cased, as OMPL.app
// does. Unknown sections, [benchmark] keys, planner names, duplicate keys, bad
// numbers and mixes of SE(2) and SE(3) keys are errors naming the file and
// the line ("maze.cfg:14: start.x: 'abc' is not a number").
#pragma once

#include <Eigen/Geometry>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "mddual/scene/loaders.h"
#include "mddual/scene/scene.h"

namespace mddual::scene {

/// The state space: SE(2)/SE(3) (OMPL.app's rigid bodies) or translation
/// only (translation_only = true: R^2 / R^3, orientation fixed at the start's).
enum class SpaceKind { kSE2, kSE3, kR2, kR3 };

/// True for kSE2 and kR2 (poses in the plane z = 0, rotations about z).
bool isPlanar(SpaceKind kind);
/// True for kR2 and kR3.
bool isTranslationOnly(SpaceKind kind);
/// "se2", "se3", "r2", "r3".
const char* toString(SpaceKind kind);

/// A pose as the cfg writes it: position, and a rotation of theta radians
/// about axis (not necessarily unit; a zero axis is the identity, as in
/// OMPL's SO3 setAxisAngle). Planar spaces use position.z = 0 and axis = z.
struct PoseSpec {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double theta = 0.0;
  bool operator==(const PoseSpec& o) const { return position == o.position && axis == o.axis && theta == o.theta; }
};

/// The pose X_WR of the robot frame R that `pose` describes, in the world
/// frame W (planar kinds: at z = 0, rotated by theta about z).
Eigen::Isometry3d toIsometry(const PoseSpec& pose, SpaceKind kind);

/// One planner instance of [planner].
struct PlannerSpec {
  std::string name;  ///< OMPL.app's name ("rrtconnect") or one of the caller's extra names
  std::vector<std::pair<std::string, std::string>> params;   ///< "range" = "50", in order
  std::vector<std::pair<std::string, std::string>> context;  ///< its problem.KEY overrides
  int line = 0;                                              ///< line of the cfg that created it (0 when built in code)
  /// Compares name, params and context (not line).
  bool operator==(const PlannerSpec& o) const { return name == o.name && params == o.params && context == o.context; }
};

/// save_paths of [benchmark].
enum class SavePaths { kNone, kAll, kShortest };

/// OMPL.app's goal threshold when the cfg gives none.
constexpr double kDefaultGoalThreshold = 1e-6;

/// An OMPL.app benchmark config.
struct ProblemConfig {
  std::filesystem::path file;  ///< the cfg itself; relative paths below are relative to its folder
  std::string name;
  std::filesystem::path robot;  ///< as written in the cfg (see resolvePath)
  std::filesystem::path world;
  SpaceKind space = SpaceKind::kSE3;
  PoseSpec start;
  PoseSpec goal;
  /// Position bounds (planar kinds: x and y used; z is [0, 0] unless given).
  std::optional<Eigen::AlignedBox3d> volume;
  std::string objective;  ///< empty: none
  std::optional<double> objective_threshold;
  std::optional<double> threshold;  ///< goal threshold (absent: kDefaultGoalThreshold)
  std::optional<double> solution_length;
  /// mesh_convex_tolerance (ours): overrides LoadOptions::mesh_convex_tolerance
  /// in loadProblemScene.
  std::optional<double> mesh_convex_tolerance;
  /// Other [problem] keys, in order: parameters of OMPL's space information.
  std::vector<std::pair<std::string, std::string>> space_parameters;
  // [benchmark]
  double time_limit = 5.0;    ///< seconds
  double mem_limit = 4096.0;  ///< MB
  int run_count = 100;
  std::filesystem::path output;  ///< folder for the log (empty: the cfg's folder)
  SavePaths save_paths = SavePaths::kNone;
  bool simplify = true;
  std::vector<PlannerSpec> planners;

  /// Compares every field except `file` (and the planners' lines).
  bool operator==(const ProblemConfig& o) const;
  bool operator!=(const ProblemConfig& o) const { return !(*this == o); }
};

/// OMPL.app's planner names (geometric planners of its ompl_benchmark:
/// rrtconnect, lazyrrt, lazyprm, kpiece, bkpiece, lbkpiece, est, biest,
/// projest, sbl, prm, rrt, stride, pdst, rrtstar, prmstar, lazyprmstar,
/// spars, spars2, lbtrrt, trrt, fmt, bfmt, aps, cforest) and OMPL 1.5's
/// informed planners that a cfg may name too (bitstar, abitstar, aitstar,
/// informedrrtstar, sorrtstar, rrtsharp, rrtxstatic).
const std::set<std::string>& knownPlannerNames();

/// Reads a cfg. `extra_planners` are further allowed planner names (e.g. the
/// caller's own "mdd_rrtconnect"). Throws SceneError naming the file and line
/// for anything it cannot read or does not know.
ProblemConfig readProblemConfig(const std::filesystem::path& cfg, const std::set<std::string>& extra_planners = {});

/// Writes `config` as a cfg that readProblemConfig reads back equal (numbers
/// in their shortest exact form; planner names are not checked, the reader
/// checks them against its allowed set); config.file is ignored. Throws
/// SceneError when a value cannot be written back unchanged (a line break or
/// '#' in it, leading or trailing blanks, a key that is not lower case or that
/// the reader would take for one of its own, a planar pose off the plane, a
/// translation_only goal rotated from the start) or the file cannot be
/// written.
void writeProblemConfig(const ProblemConfig& config, const std::filesystem::path& cfg);

/// `p` resolved against the folder of config.file (unchanged if absolute).
std::filesystem::path resolvePath(const ProblemConfig& config, const std::filesystem::path& p);

/// The scene of a problem.
struct ProblemScene {
  RigidBody robot;  ///< pieces in the robot frame R (the frame the states pose)
  World world;      ///< pieces in the world frame W
  SpaceKind space = SpaceKind::kSE3;
  /// Position bounds of the state space, frame W (planar kinds: x and y).
  Eigen::AlignedBox3d bounds;
  /// X_WR at the start and at the goal (translation-only kinds: both with the
  /// start's rotation, the fixed orientation of the robot).
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d goal = Eigen::Isometry3d::Identity();
  /// A mesh robot's file frame is shifted by -robot_shift to make R (OMPL.app:
  /// the mean vertex, its z zeroed for planar kinds); zero for a URDF robot.
  Eigen::Vector3d robot_shift = Eigen::Vector3d::Zero();
  /// The loaders' warnings for the robot and the world (MeshInfo::warnings:
  /// skipped triangles, a convexity check that fell back to triangles), each
  /// naming its file; the caller shows them.
  std::vector<std::string> warnings;
  /// How the robot's and the world's meshes were loaded (convex pieces,
  /// triangle soups, closed soups).
  MeshCounts robot_meshes;
  MeshCounts world_meshes;
};

/// One line on the scene for the user: the robot's and the world's pieces
/// (convex, triangles) and meshes, and the closed meshes loaded as hollow
/// triangle soups, e.g. "robot 'car': 1 piece (1 convex), 1 mesh (1 convex);
/// world 'maze': 1970 pieces (1970 triangles), 1 mesh (1 triangle soup, 1
/// closed: hollow)".
std::string sceneSummary(const ProblemScene& scene);

/// Loads the robot (URDF: root link frame; mesh: recentred as OMPL.app does)
/// and the world (config.mesh_convex_tolerance, when given, replaces
/// options.mesh_convex_tolerance), and computes the bounds: config.volume, or the world's
/// bounding box widened to hold the start and goal positions (planar kinds:
/// z = [0, 0]). Throws SceneError (prefixed with the cfg's name) from the
/// loaders, for empty bounds, or for a translation-only config whose goal
/// rotation differs from the start's.
ProblemScene loadProblemScene(const ProblemConfig& config, const LoadOptions& options = {});

}  // namespace mddual::scene
