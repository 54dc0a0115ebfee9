#include "mddual/planning/bench_runner.h"

#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/Exception.h>

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <system_error>

#include "mddual/error.h"
#include "mddual/planning/planner_factory.h"
#include "metered_planner.h"
#include "run_text.h"

namespace mddual::planning {

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace ot = ompl::tools;

namespace {

using detail::flag;
using detail::MeteredPlanner;
using detail::real;
using detail::setUpPlanner;

int parseInt(const std::string& text, const std::string& what) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos || text.size() > 9) {
    throw InvalidInputError(what);
  }
  return std::stoi(text);
}

/// The planner of a cfg entry with its problem context applied and the MDD
/// validator's discarded fraction tried (*discarded): a bad value in either
/// is refused with the entry's place.
ob::PlannerPtr checkedPlanner(ProblemSetup& setup, const scene::PlannerSpec& spec, double* discarded) {
  ob::PlannerPtr p = setup.makePlanner(spec);
  setup.applyPlannerContext(spec);
  *discarded = discardedLastValidFraction(*p);
  try {
    setup.setDiscardedLastValidFraction(*discarded);
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(setup.plannerWhere(spec) + "min_valid_path_fraction: " + e.what());
  }
  return p;
}

/// Throws unless a file can be written in `dir`: found before the runs, not
/// when their log is written at the end (a read-only folder was reported
/// after every run had finished, without the reason).
void checkWritable(const std::filesystem::path& dir) {
  const std::filesystem::path probe = dir / (".mddual-write-test-" + std::to_string(::getpid()));
  errno = 0;
  std::ofstream out(probe);
  const bool ok = out && (out << "x" << std::flush);
  const int error = errno;
  out.close();
  std::error_code ignored;
  std::filesystem::remove(probe, ignored);
  if (!ok) {
    throw InvalidInputError("cannot write in the output folder " + dir.string() +
                            (error != 0 ? ": " + std::string(std::strerror(error)) : ""));
  }
}

/// Writes a path as OMPL's printAsMatrix does (one state per line).
void savePath(const og::PathGeometric& path, const std::filesystem::path& file) {
  std::ofstream out(file);
  path.printAsMatrix(out);
  if (!out) throw InvalidInputError("cannot write the path file " + file.string());
}

}  // namespace

BenchShard parseShard(const std::string& text) {
  const std::string what = "--shard '" + clipForMessage(text) + "': expected I/N with 0 <= I < N (e.g. 0/4)";
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos) throw InvalidInputError(what);
  BenchShard s;
  s.index = parseInt(text.substr(0, slash), what);
  s.count = parseInt(text.substr(slash + 1), what);
  if (s.count < 1 || s.index >= s.count) throw InvalidInputError(what);
  return s;
}

std::string toString(const BenchShard& shard) {
  return std::to_string(shard.index) + "/" + std::to_string(shard.count);
}

std::vector<int> shardRuns(int runs, const BenchShard& shard) {
  std::vector<int> out;
  for (int r = shard.index; r < runs; r += shard.count) out.push_back(r);
  return out;
}

std::uint32_t shardSeed(long seed, const BenchShard& shard) {
  if (!shard.sharded()) return static_cast<std::uint32_t>(seed);
  // splitmix64 (Steele, Lea, Flood 2014) over the three numbers in turn.
  const auto mix = [](std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  std::uint64_t h = mix(static_cast<std::uint64_t>(seed));
  h = mix(h ^ static_cast<std::uint64_t>(shard.index));
  h = mix(h ^ (static_cast<std::uint64_t>(shard.count) << 32));
  return static_cast<std::uint32_t>(1 + h % 0xfffffffeULL);
}

namespace {

/// "<stem>.shard<I>of<N>.log" (as logFileName writes it) -> stem, I, N.
bool parseShardLogName(const std::string& name, std::string* stem, int* index, int* count) {
  const std::string suffix = ".log";
  const std::size_t at = name.rfind(".shard");
  if (at == std::string::npos || name.size() < suffix.size() ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) {
    return false;
  }
  const std::string middle = name.substr(at + 6, name.size() - suffix.size() - at - 6);  // "<I>of<N>"
  const std::size_t of = middle.find("of");
  const auto digits = [](const std::string& t) {
    return !t.empty() && t.size() < 10 && t.find_first_not_of("0123456789") == std::string::npos;
  };
  if (of == std::string::npos || !digits(middle.substr(0, of)) || !digits(middle.substr(of + 2))) return false;
  *stem = name.substr(0, at);
  *index = std::stoi(middle.substr(0, of));
  *count = std::stoi(middle.substr(of + 2));
  return true;
}

}  // namespace

void checkShardSets(const std::vector<std::filesystem::path>& logs) {
  // Per "<config>-<checker>": unsharded logs, and shard index sets per N.
  struct Group {
    int unsharded = 0;
    std::map<int, std::set<int>> shards;
  };
  std::map<std::string, Group> groups;
  for (const auto& path : logs) {
    std::string stem;
    int index = 0;
    int count = 0;
    if (parseShardLogName(path.filename().string(), &stem, &index, &count)) {
      groups[stem].shards[count].insert(index);
    } else {
      ++groups[path.stem().string()].unsharded;
    }
  }
  for (const auto& [stem, g] : groups) {
    if (g.unsharded > 0 && !g.shards.empty()) {
      throw InvalidInputError(stem +
                              ": both an unsharded log and shard logs in the same folder (their runs would "
                              "be counted twice); keep one kind");
    }
    if (g.shards.size() > 1) {
      std::string counts;
      for (const auto& [n, ignored] : g.shards) counts += (counts.empty() ? "" : ", ") + std::to_string(n);
      throw InvalidInputError(stem + ": shard logs of different shard counts (" + counts +
                              ") in the same folder; keep those of one count");
    }
    if (g.shards.empty()) continue;
    const auto& [n, have] = *g.shards.begin();
    std::string missing;
    for (int i = 0; i < n; ++i) {
      if (have.count(i) == 0) missing += (missing.empty() ? "" : ", ") + std::to_string(i) + "/" + std::to_string(n);
    }
    if (!missing.empty()) throw InvalidInputError(stem + ": shard logs missing: " + missing);
  }
}

std::string logFileName(const std::string& config, const std::string& checker, const BenchShard& shard) {
  std::string name = config + "-" + checker;
  if (shard.sharded()) name += ".shard" + std::to_string(shard.index) + "of" + std::to_string(shard.count);
  return name + ".log";
}

std::vector<scene::PlannerSpec> selectPlanners(const Problem& problem, const std::vector<std::string>& names) {
  return selectPlannerSpecs(problem.config.planners, names, problem.cfgName());
}

std::vector<std::string> checkBenchProblem(const Problem& problem, bool allow_invalid_endpoints) {
  if (problem.name.size() > kMaxProblemNameBytes) {
    throw InvalidInputError(problem.cfgName() + ": the problem name '" + clipForMessage(problem.name) +
                            "' is too long: it names the experiment and the log files; at most " +
                            std::to_string(kMaxProblemNameBytes) + " bytes");
  }
  if (allow_invalid_endpoints) return endpointCollisions(problem);
  checkStartAndGoal(problem);  // OMPL would only report every run unsolved
  return {};
}

std::vector<BenchLog> runBench(const Problem& problem, const BenchOptions& options, const BenchObserver& observer) {
  const scene::ProblemConfig& cfg = problem.config;
  if (options.checkers.empty()) throw InvalidInputError("no checker to run");
  for (const std::string& name : options.checkers) findRigidChecker(name);  // an unknown name fails now
  const int runs = options.runs.value_or(cfg.run_count);
  if (options.runs && runs < 1) throw InvalidInputError("--runs must be at least 1 (got " + std::to_string(runs) + ")");
  if (runs < 1) {
    throw InvalidInputError(problem.cfgName() + ": run_count = " + std::to_string(runs) +
                            " (as many runs as fit in the time limit) is not supported: give the number of runs");
  }
  const double time_limit = options.time_limit.value_or(cfg.time_limit);
  if (!(time_limit > 0.0) || !(time_limit <= kMaxTimeLimit)) {
    throw InvalidInputError("the time limit must be a positive number of seconds, at most " + real(kMaxTimeLimit) +
                            " (got " + real(time_limit) + ")");
  }
  const double mem_limit = options.mem_limit.value_or(cfg.mem_limit);
  if (!(mem_limit > 0.0) || !(mem_limit <= kMaxMemLimit)) {
    throw InvalidInputError("the memory limit must be a positive number of MB, at most " + real(kMaxMemLimit) +
                            " (got " + real(mem_limit) + ")");
  }
  const BenchShard shard = options.shard;
  if (shard.count < 1 || shard.index < 0 || shard.index >= shard.count) {
    throw InvalidInputError("shard " + toString(shard) + ": expected 0 <= I < N");
  }
  if (shard.count > runs) {
    throw InvalidInputError("--shard " + toString(shard) + ": only " + std::to_string(runs) +
                            " runs per planner, so at most " + std::to_string(runs) + " shards");
  }
  const std::vector<scene::PlannerSpec> specs = selectPlanners(problem, options.planners);
  checkBenchProblem(problem, options.setup.allow_invalid_endpoints);
  const std::vector<int> run_indices = shardRuns(runs, shard);
  const int n = static_cast<int>(run_indices.size());

  std::error_code ec;
  std::filesystem::create_directories(options.output_dir, ec);
  if (ec || !std::filesystem::is_directory(options.output_dir)) {
    throw InvalidInputError("cannot create the output folder " + options.output_dir.string() +
                            (ec ? ": " + ec.message() : ""));
  }
  checkWritable(options.output_dir);
  const std::filesystem::path paths_dir = options.output_dir / "paths";
  if (cfg.save_paths != scene::SavePaths::kNone) {
    std::filesystem::create_directories(paths_dir, ec);
    if (ec) throw InvalidInputError("cannot create the paths folder " + paths_dir.string() + ": " + ec.message());
  }

  const PathVerifier verifier(problem.robot(), problem.world(), problem.scene->bounds, options.verifier);
  // Every checker's setup once before any run: ProblemSetup refuses a start
  // or goal its checker finds in collision, which must stop the command
  // before the first checker's runs, not after them.
  for (std::size_t ci = 1; ci < options.checkers.size(); ++ci) {
    const ProblemSetup check(problem, options.checkers[ci], options.setup);
  }
  std::vector<BenchLog> logs;
  for (std::size_t ci = 0; ci < options.checkers.size(); ++ci) {
    const std::string& checker = options.checkers[ci];
    if (observer.checker_started)
      observer.checker_started(checker, static_cast<int>(ci), static_cast<int>(options.checkers.size()));
    ProblemSetup setup(problem, checker, options.setup);
    const std::string experiment = problem.name + "-" + checker;

    // Planners in cfg order, named as in the cfg (repeats numbered); every
    // context tried once now, so that a bad value fails here and not inside
    // OMPL's benchmark (which would only log it).
    // Each planner is metered: the checkers' counters are read when its
    // solve() returns (solve_stats), before OMPL checks the path.
    std::vector<ob::PlannerPtr> planners;
    std::vector<double> discarded_fraction;  // per spec: discardedLastValidFraction
    std::map<const ob::Planner*, std::size_t> spec_of;
    std::map<std::string, int> seen;
    CheckStats solve_stats;
    double solve_seconds = 0.0;  // the planner's own solve(), see MeteredPlanner
    if (ci == 0) {
      // The cfg's planners that --planners leaves out are checked too, set up
      // on a copy of the problem (a set-up may add an objective to it): a bad
      // value in the cfg is refused whichever planners run (it passed). The
      // ones that run are checked below and set up by the benchmark.
      for (const scene::PlannerSpec& listed : problem.config.planners) {
        const bool selected = std::any_of(specs.begin(), specs.end(), [&](const scene::PlannerSpec& spec) {
          return spec.line == listed.line && spec == listed;
        });
        if (selected) continue;
        double discarded = 0.0;
        const ob::PlannerPtr p = checkedPlanner(setup, listed, &discarded);
        p->setProblemDefinition(setup.simpleSetup().getProblemDefinition()->clone());
        setUpPlanner(*p, setup.plannerWhere(listed));
      }
    }
    for (std::size_t i = 0; i < specs.size(); ++i) {
      discarded_fraction.push_back(0.0);
      ob::PlannerPtr p = checkedPlanner(setup, specs[i], &discarded_fraction.back());  // tried once now
      const int count = ++seen[p->getName()];
      if (count > 1) p->setName(p->getName() + "_" + std::to_string(count));
      p = std::make_shared<MeteredPlanner>(
          p,
          [&setup, &solve_stats, &solve_seconds](double seconds) {
            solve_stats = setup.stats();
            solve_seconds = seconds;
          },
          setup.plannerWhere(specs[i]));
      spec_of[p.get()] = i;
      planners.push_back(p);
    }

    ot::Benchmark bench(setup.simpleSetup(), experiment);
    bench.addExperimentParameter("config", "STRING", problem.name);
    bench.addExperimentParameter("checker", "STRING", checker);
    bench.addExperimentParameter("shard", "STRING", toString(shard));
    for (const ob::PlannerPtr& p : planners) bench.addPlanner(p);

    BenchLog log;
    log.checker = checker;
    log.file = options.output_dir / logFileName(problem.name, checker, shard);
    log.planners = static_cast<int>(planners.size());
    log.runs_per_planner = n;
    std::exception_ptr failure;
    std::size_t current = 0;
    std::map<std::string, std::pair<double, og::PathGeometric>> shortest;

    bench.setPlannerSwitchEvent([&](const ob::PlannerPtr& planner) {
      try {
        current = spec_of.at(planner.get());
        setup.setDiscardedLastValidFraction(discarded_fraction[current]);
        setup.applyPlannerContext(specs[current]);
      } catch (...) {
        if (!failure) failure = std::current_exception();
      }
      if (observer.planner_started) {
        observer.planner_started(checker, planner->getName(), static_cast<int>(current),
                                 static_cast<int>(planners.size()), n);
      }
    });
    bench.setPreRunEvent([&](const ob::PlannerPtr& planner) {
      setup.resetStats();
      solve_stats = CheckStats();
      solve_seconds = 0.0;
      const int k = static_cast<int>(bench.getStatus().activeRun);
      if (observer.run_started && k < n) {
        observer.run_started(checker, planner->getName(), k, n, run_indices[static_cast<std::size_t>(k)]);
      }
    });
    bench.setPostRunEvent([&](const ob::PlannerPtr& planner, ot::Benchmark::RunProperties& run) {
      // Never throws: every run is kept, whatever happens here.
      const CheckStats st = solve_stats;
      const int k = static_cast<int>(bench.getStatus().activeRun);
      const int r = k < n ? run_indices[static_cast<std::size_t>(k)] : -1;
      run["run index INTEGER"] = std::to_string(r);
      run["state checks INTEGER"] = std::to_string(st.state_checks);
      run["motion checks INTEGER"] = std::to_string(st.motion_checks);
      run["pair queries INTEGER"] = std::to_string(st.pair_queries);
      run["sub edges INTEGER"] = std::to_string(st.sub_edges);
      run["checking time REAL"] = real(st.seconds);
      run["solve time REAL"] = real(solve_seconds);
      bool exact = false;
      bool verified = false;
      bool invalid = false;
      bool invalid_mdd = false;
      bool invalid_fcl = false;
      bool invalid_raw = false;
      bool out_of_bounds = false;
      double verify_seconds = 0.0;
      double verify_mdd_seconds = 0.0;
      double verify_fcl_seconds = 0.0;
      std::string error;
      try {
        og::SimpleSetup& ss = setup.simpleSetup();
        const bool solved = ss.haveSolutionPath();
        exact = solved && !ss.getProblemDefinition()->hasApproximateSolution();
        if (solved) {
          const og::PathGeometric raw = ss.getSolutionPath();
          if (cfg.simplify) {
            const auto t0 = std::chrono::steady_clock::now();
            ss.simplifySolution();
            const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            og::PathGeometric& path = ss.getSolutionPath();
            run["simplification time REAL"] = real(dt);
            run["simplified solution length REAL"] = real(path.length());
            run["simplified solution smoothness REAL"] = real(path.smoothness());
            run["simplified solution clearance REAL"] = real(path.clearance());
            run["simplified solution segments INTEGER"] = std::to_string(path.getStateCount() - 1);
            run["simplified correct solution BOOLEAN"] = flag(path.check());
            const unsigned factor = ss.getStateSpace()->getValidSegmentCountFactor();
            ss.getStateSpace()->setValidSegmentCountFactor(factor * 4);
            run["simplified correct solution strict BOOLEAN"] = flag(path.check());
            ss.getStateSpace()->setValidSegmentCountFactor(factor);
          }
          if (exact) {
            const og::PathGeometric& path = ss.getSolutionPath();
            const VerifyResult v = verifier.verify(*setup.planningSpace(), path);
            verify_seconds += v.seconds;
            verify_mdd_seconds += v.mdd_seconds;
            verify_fcl_seconds += v.fcl_seconds;
            verified = v.valid;
            invalid = !v.valid;
            invalid_mdd = v.mdd_collision;
            invalid_fcl = v.fcl_collision;
            out_of_bounds = v.out_of_bounds;
            invalid_raw = invalid;
            if (cfg.simplify) {
              const VerifyResult vr = verifier.verify(*setup.planningSpace(), raw);
              verify_seconds += vr.seconds;
              verify_mdd_seconds += vr.mdd_seconds;
              verify_fcl_seconds += vr.fcl_seconds;
              invalid_raw = !vr.valid;
            }
            const std::string stem = experiment + "-" + planner->getName();
            if (cfg.save_paths == scene::SavePaths::kAll) {
              std::string name = stem + "-run" + std::to_string(r);
              if (shard.sharded()) name += ".shard" + std::to_string(shard.index) + "of" + std::to_string(shard.count);
              savePath(path, paths_dir / (name + ".path"));
            } else if (cfg.save_paths == scene::SavePaths::kShortest) {
              auto it = shortest.find(stem);
              if (it == shortest.end() || path.length() < it->second.first) {
                shortest.insert_or_assign(stem, std::make_pair(path.length(), path));
              }
            }
          }
        }
      } catch (const std::exception& e) {
        error = e.what();
      } catch (...) {
        error = "unknown exception";
      }
      if (!error.empty()) {  // neither verified nor invalid, and no half of the check counted
        verified = false;
        invalid = invalid_mdd = invalid_fcl = out_of_bounds = invalid_raw = false;
        for (char& c : error) {
          if (c == '\n' || c == ';') c = ' ';
        }
        run["verification error STRING"] = error;
      }
      run["verified BOOLEAN"] = flag(verified);
      run["invalid solution BOOLEAN"] = flag(invalid);
      run["invalid by mdd BOOLEAN"] = flag(exact && invalid_mdd);
      run["invalid by fcl BOOLEAN"] = flag(exact && invalid_fcl);
      run["invalid by bounds BOOLEAN"] = flag(exact && out_of_bounds);
      if (cfg.simplify) run["invalid raw solution BOOLEAN"] = flag(exact && invalid_raw);
      run["verification time REAL"] = real(verify_seconds);
      run["verification mdd time REAL"] = real(verify_mdd_seconds);
      run["verification fcl time REAL"] = real(verify_fcl_seconds);
      log.solved += exact ? 1 : 0;
      log.verified += verified ? 1 : 0;
      log.invalid += invalid ? 1 : 0;
      if (observer.run_finished) observer.run_finished(checker, planner->getName(), k, exact, verified, invalid);
    });

    ot::Benchmark::Request request(time_limit, mem_limit, static_cast<unsigned>(n), 0.05,
                                   /*displayProgress=*/false, /*saveConsoleOutput=*/false, /*simplify=*/false);
    bench.benchmark(request);
    if (failure) std::rethrow_exception(failure);

    errno = 0;
    std::ofstream out(log.file);
    if (!out) {
      throw InvalidInputError("cannot write the benchmark log " + log.file.string() +
                              (errno != 0 ? ": " + std::string(std::strerror(errno)) : ""));
    }
    if (!bench.saveResultsToStream(out) || !(out << std::flush)) {
      throw InvalidInputError("cannot write the benchmark log " + log.file.string());
    }
    for (const auto& [stem, best] : shortest) {
      std::string name = stem + "-shortest";
      if (shard.sharded()) name += ".shard" + std::to_string(shard.index) + "of" + std::to_string(shard.count);
      savePath(best.second, paths_dir / (name + ".path"));
    }
    logs.push_back(log);
  }
  return logs;
}

}  // namespace mddual::planning
