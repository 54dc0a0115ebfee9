// The benchmark runner behind `mddual bench`: a cfg's problem with each
// checker, ompl::tools::Benchmark over the cfg's planners, one OMPL benchmark
// log per checker (and shard), every solution verified (PathVerifier).
//
// Per checker: a ProblemSetup, the cfg's planners (makePlanner, in cfg order,
// named as in the cfg), ompl::tools::Benchmark with the cfg's time and memory
// limits and run count (options override them), experiment name
// "<config>-<checker>", experiment parameters config, checker and shard
// ("I/N"; "0/1" unsharded). Each planner runs with the space parameters plus
// its own context (planner-switch event). OMPL's own output is off while it
// runs; the observer sees the progress.
//
// Extra properties of every run (post-run event; the counters are reset in
// the pre-run event):
//   run index INTEGER          the run's index r among the cfg's runs (shards
//                              hold disjoint sets of r)
//   state checks INTEGER, motion checks INTEGER, pair queries INTEGER,
//                              sub edges INTEGER, checking time REAL
//                              the checkers' work during the planner's solve()
//                              (ProblemSetup::stats() read the moment it returns,
//                              before OMPL checks the solution path)
//   verified BOOLEAN           an exact solution that PathVerifier found valid
//   invalid solution BOOLEAN   an exact solution that it found in collision
//   invalid by mdd BOOLEAN, invalid by fcl BOOLEAN, invalid by bounds BOOLEAN
//                              which of its checks did (exact solutions; all 0
//                              when the verification failed with an error)
//   invalid raw solution BOOLEAN  the path before simplification was invalid
//   verification time REAL     seconds spent verifying (both paths)
//   verification mdd time REAL / verification fcl time REAL: of which check
//                              (a) / check (b) of PathVerifier
//   verification error STRING  what went wrong if the verifier threw (the run
//                              then counts as neither verified nor invalid)
// Approximate solutions are not solutions: verified and invalid are 0. The
// solution is simplified here (not by Benchmark) after the counters are read,
// when the cfg says simplify = true, with OMPL's property names (simplified
// solution length REAL, ..., simplification time REAL); the path verified is
// the one the run returns (simplified when simplification is on).
//
// Sharding: run r of every (checker, planner) belongs to shard r mod N; shard
// I of N runs those r in increasing order. The caller seeds OMPL's RNG with
// shardSeed(seed, shard) before building anything, so a shard is
// reproducible. The N shards together hold the same run indices as one
// unsharded run, each exactly once, but not bit-identical runs: OMPL draws a
// process's random streams one after another, so run r of a shard does not
// see the stream run r of an unsharded process sees (the results are
// statistically equivalent samples).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "mddual/planning/path_verifier.h"
#include "mddual/planning/problem_setup.h"

namespace mddual::planning {

/// Largest time limit accepted, seconds (about 115 days): OMPL adds the limit
/// to the current time, which overflows for limits near 1e18 s and then ends
/// every run at once.
inline constexpr double kMaxTimeLimit = 1e7;
/// Largest memory limit accepted, MB (1 PB): OMPL converts it to bytes in a
/// 64-bit integer, which overflows for limits near 1.8e13 MB.
inline constexpr double kMaxMemLimit = 1e9;

/// Longest problem name runBench accepts, bytes. The name starts the file
/// names of the logs ("<name>-fcl-continuous.shard<I>of<N>.log") and of the
/// saved paths ("<name>-<checker>-<planner>-run<r>....path"), which file
/// systems limit to 255 bytes.
inline constexpr std::size_t kMaxProblemNameBytes = 128;

/// Slice I of N of the runs.
struct BenchShard {
  int index = 0;
  int count = 1;
  bool sharded() const { return count > 1 || index != 0; }
};

/// Parses "I/N" (0 <= I < N); throws InvalidInputError naming what is wrong.
BenchShard parseShard(const std::string& text);
/// "I/N".
std::string toString(const BenchShard& shard);
/// The run indices r in [0, runs) of shard `shard` (r mod N == I), increasing.
std::vector<int> shardRuns(int runs, const BenchShard& shard);
/// OMPL's random seed for `shard` of a campaign seeded with `seed` (>= 1):
/// `seed` itself when unsharded, else a hash (splitmix64) of (seed, I, N) in
/// [1, 2^32 - 1], so the shards of one campaign and of campaigns with other
/// seeds or shard counts do not share seeds the way seed + I would.
std::uint32_t shardSeed(long seed, const BenchShard& shard);
/// Checks that the benchmark logs in `logs` (file names as logFileName makes
/// them) form complete shard sets: per "<config>-<checker>", either one
/// unsharded log or the logs of shards 0 .. N-1 of a single N, each once.
/// Other *.log names count as unsharded logs of their own. Throws
/// InvalidInputError naming the config-checker and the shards missing or mixed.
void checkShardSets(const std::vector<std::filesystem::path>& logs);

/// Options of runBench; unset optionals take the cfg's values.
struct BenchOptions {
  /// Names of rigidCheckers() entries; by default all of them, in the table's order.
  std::vector<std::string> checkers = rigidCheckerNames();
  /// Planner names as in the cfg ([planner] keys); empty: all of the cfg's.
  std::vector<std::string> planners;
  std::optional<int> runs;
  std::optional<double> time_limit;  ///< seconds
  std::optional<double> mem_limit;   ///< MB
  BenchShard shard;
  /// Where the logs (and saved paths) go; created if missing.
  std::filesystem::path output_dir;
  SetupOptions setup;
  VerifierOptions verifier;
};

/// Progress callbacks (any may be empty), called from the thread that calls
/// runBench.
struct BenchObserver {
  /// A checker's benchmark starts (index among the checkers run).
  std::function<void(const std::string& checker, int index, int count)> checker_started;
  /// A planner's runs start: `runs` runs of this shard.
  std::function<void(const std::string& checker, const std::string& planner, int index, int count, int runs)>
      planner_started;
  /// Run k (0-based, of this shard's `runs`) starts; run_index is its r.
  std::function<void(const std::string& checker, const std::string& planner, int k, int runs, int run_index)>
      run_started;
  /// A run ended: solved exactly, verified, invalid.
  std::function<void(const std::string& checker, const std::string& planner, int k, bool solved, bool verified,
                     bool invalid)>
      run_finished;
};

/// What runBench wrote.
struct BenchLog {
  std::string checker;         ///< its name
  std::filesystem::path file;  ///< the OMPL benchmark log
  int planners = 0;
  int runs_per_planner = 0;
  int solved = 0;    ///< exact solutions
  int verified = 0;  ///< of them, verified collision-free
  int invalid = 0;   ///< of them, found in collision
};

/// "<config>-<checker>.log", or "<config>-<checker>.shard<I>of<N>.log" for a shard.
std::string logFileName(const std::string& config, const std::string& checker, const BenchShard& shard);

/// The planners `names` selects (all the cfg's when empty): see
/// selectPlannerSpecs (a name the cfg does not list runs with OMPL's
/// defaults); throws InvalidInputError for a name no planner has.
std::vector<scene::PlannerSpec> selectPlanners(const Problem& problem, const std::vector<std::string>& names);

/// Checks what runBench needs of a problem before anything runs: a name of
/// at most kMaxProblemNameBytes, and start and goal states within the bounds
/// and free (checkStartAndGoal). Throws InvalidInputError naming the cfg.
/// With allow_invalid_endpoints (SetupOptions), a start or goal in collision
/// is returned as its message (endpointCollisions) instead of thrown.
std::vector<std::string> checkBenchProblem(const Problem& problem, bool allow_invalid_endpoints = false);

/// Runs the benchmark (see the file comment). Throws InvalidInputError for
/// bad options (no checker, runs < 1, time or memory limit <= 0 or above
/// kMaxTimeLimit / kMaxMemLimit, more shards than
/// runs, a cfg with run_count = 0 and no runs option) or a problem that
/// checkBenchProblem refuses, all before anything runs, or a log that cannot
/// be written, and what ProblemSetup / makePlanner throw.
std::vector<BenchLog> runBench(const Problem& problem, const BenchOptions& options,
                               const BenchObserver& observer = BenchObserver());

}  // namespace mddual::planning
