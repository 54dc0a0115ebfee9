// The arm benchmark behind `mddual bench PROBLEM_DIR --robot URDF --srdf
// SRDF`: every problem of a MotionBenchMaker directory with each checker and
// planner in ompl::tools::Benchmark, one OMPL log per (problem, checker),
// every solution verified.
//
// Checkers: the entries of armCheckers() (checker_registry.h):
//   mdd       ArmStateValidityChecker + ArmMotionValidator (exact states,
//             certified edges);
//   fcl       FclArmStateValidityChecker + OMPL's DiscreteMotionValidator at
//             OMPL's default resolution (what MoveIt runs);
//   fcl-fine  the same with a segment of at most ArmBenchOptions::
//             fine_resolution radians (joint-space distance).
// All three check the same pairs on the same pieces: every link against the
// world and the link pairs the SRDF and the scene's matrix keep.
//
// Logs: "<dir>-<NNNN>-<checker>.log" (experiment "<dir>-<checker>", experiment
// parameters config = the directory's name, checker, problem = NNNN, shard),
// so that the report merges the problems of a directory into one config.
// Run properties, as runBench's: run index, state checks, motion checks,
// checking time, verified, invalid solution, invalid by mdd, invalid by fcl,
// verification time.
//
// Verification of an exact solution: (a) each edge with ArmScene::checkEdge
// at a tenth of the checker's contact distance (certified; a path within
// that of contact counts as invalid, and every path the mdd checker accepts
// keeps ten times more) and (b)
// each edge densely with FCL, states at most ArmBenchOptions::
// verify_resolution radians apart in every joint. Invalid when either finds
// a contact.
//
// Paths: with ArmBenchOptions::paths_dir, every exact solution is also
// written there as a trajectory (scene::saveMbmTrajectory, the group's
// joints, continuous ones unwrapped along the path):
// "<dir>-<NNNN>-<checker>-<planner>-<run>.yaml" (the planner's name with
// characters other than letters, digits, '-', '_', '.' as '_'), with
// "-invalid" before ".yaml" when the verification found a contact. A path
// that cannot be written ends the benchmark with its SceneError once the
// problem's runs are done.
//
// Sharding: problem k of the directory (in number order) belongs to shard k
// mod N.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "mddual/planning/arm_problem.h"
#include "mddual/planning/bench_runner.h"
#include "mddual/planning/checker_registry.h"

namespace mddual::planning {

/// The OMPL planner name of a MotionBenchMaker (MoveIt) planner_id:
/// "RRTConnectkConfigDefault" -> "rrtconnect", "BKPIECEGood" -> "bkpiece";
/// a plain OMPL name is itself. Empty when no planner matches.
std::string plannerFromPlannerId(const std::string& planner_id);

/// The name a problem directory gives its config, logs and output folder:
/// its last component ("problems/cage/" and "problems/cage/." are "cage").
std::string problemDirName(const std::filesystem::path& problem_dir);

/// Options of runArmBench.
struct ArmBenchOptions {
  /// Names of armCheckers() entries; by default all of them, in the table's order.
  std::vector<std::string> checkers = armCheckerNames();
  /// Planner names or planner_ids; empty: each request's planner_id.
  std::vector<std::string> planners;
  int runs = 10;
  /// Seconds; <= 0: each request's allowed_planning_time (10 s when absent).
  double time_limit = 0.0;
  double mem_limit = 4096.0;  ///< MB
  /// At most this many problems (the first by number); 0: all.
  int problems = 0;
  BenchShard shard;
  /// fcl-fine's longest valid segment (joint-space distance, radians).
  double fine_resolution = kDefaultFineResolution;
  /// The dense FCL verification's largest step per joint (radians).
  double verify_resolution = 1e-3;
  std::filesystem::path output_dir;
  /// Where the solution paths go (see the file comment); empty: nowhere.
  std::filesystem::path paths_dir;
  ArmProblemOptions problem;
};

/// Progress callbacks (any may be empty).
struct ArmBenchObserver {
  std::function<void(const std::string& problem, int index, int count)> problem_started;
  std::function<void(const std::string& checker, const std::string& planner, bool solved, bool verified, bool invalid)>
      run_finished;
};

/// What runArmBench wrote for one (problem, checker).
struct ArmBenchLog {
  std::string problem;
  std::string checker;
  std::filesystem::path file;
  int solved = 0;    ///< exact solutions
  int verified = 0;  ///< of them, verified collision-free
  int invalid = 0;   ///< of them, found in collision
};

/// Runs the benchmark (see the file comment). Throws InvalidInputError for
/// bad options, SceneError for a problem that does not load (naming the file
/// and field), and InvalidInputError for a log that cannot be written.
std::vector<ArmBenchLog> runArmBench(const ArmRobot& robot, const std::filesystem::path& problem_dir,
                                     const ArmBenchOptions& options, const ArmBenchObserver& observer = {});

}  // namespace mddual::planning
