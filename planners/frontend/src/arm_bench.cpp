// The arm benchmark (arm_bench.h).
#include "mddual/planning/arm_bench.h"

#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/tools/benchmark/Benchmark.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <set>

#include "mddual/error.h"
#include "mddual/planning/arm_checkers.h"
#include "mddual/planning/planner_factory.h"
#include "metered_planner.h"
#include "run_text.h"

namespace mddual::planning {
namespace {

using detail::flag;
using detail::MeteredPlanner;
using detail::real;

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace ot = ompl::tools;
using Clock = std::chrono::steady_clock;

/// One problem set up with one checker.
struct ArmSetup {
  ArmSpacePtr space;
  std::shared_ptr<og::SimpleSetup> ss;
  InstalledChecker installed;

  void resetCounts() {
    installed.reset_counts();
    ss->getSpaceInformation()->getMotionValidator()->resetMotionCounter();
  }
  /// State checks and the time inside the checkers (the FCL discrete
  /// validator's time is its state checks').
  std::pair<std::uint64_t, double> counts() const {
    const CheckerCounts c = installed.counts();
    return {c.state_checks, c.seconds};
  }
};

ArmSetup makeSetup(const ArmProblem& p, const ArmChecker& checker, const std::shared_ptr<const FclArmScene>& fcl,
                   double fine_resolution) {
  ArmSetup s;
  s.space = ArmSpace::make(p.space->modelPtr(), p.space->variables(), p.start);
  auto si = std::make_shared<ob::SpaceInformation>(s.space->stateSpace());
  s.installed = checker.install({si, s.space, p.scene, fcl, fine_resolution});
  s.ss = std::make_shared<og::SimpleSetup>(si);
  ob::ScopedState<> start(si), goal(si);
  s.space->setState(start.get(), p.start.data());
  s.space->setState(goal.get(), p.goal.data());
  s.ss->setStartAndGoalStates(start, goal);
  s.ss->setup();
  return s;
}

/// Verification of a path: (a) certified edges, (b) dense FCL states.
struct Verdict {
  bool invalid_mdd = false;
  bool invalid_fcl = false;
  double seconds = 0.0;
};

Verdict verify(const ArmProblem& p, const ArmScene& exact, const FclArmScene& fcl, const ArmSpace& space,
               const og::PathGeometric& path, double step) {
  const auto t0 = Clock::now();
  Verdict v;
  const std::size_t n = p.start.size();
  std::vector<double> q0(n), q1(n), q(n);
  for (unsigned int i = 0; i + 1 < path.getStateCount(); ++i) {
    space.edge(path.getState(i), path.getState(i + 1), q0.data(), q1.data());
    if (!v.invalid_mdd && exact.checkEdge(q0.data(), q1.data(), EdgeQuery::kValidity).collides) {
      v.invalid_mdd = true;
    }
    double largest = 0.0;
    for (std::size_t k = 0; k < n; ++k) largest = std::max(largest, std::abs(q1[k] - q0[k]));
    const int steps = std::max(1, static_cast<int>(std::ceil(largest / step)));
    for (int s = 0; s <= steps && !v.invalid_fcl; ++s) {
      const double t = static_cast<double>(s) / steps;
      for (std::size_t k = 0; k < n; ++k) q[k] = q0[k] + t * (q1[k] - q0[k]);
      v.invalid_fcl = fcl.collides(q.data());
    }
  }
  v.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return v;
}

/// Writes a solution path as a trajectory of p's group (continuous joints
/// unwrapped along it: ArmSpace::pathConfigurations).
void savePath(const ArmProblem& p, const ArmSpace& space, const og::PathGeometric& path,
              const std::filesystem::path& file, const std::vector<std::string>& comment) {
  std::vector<const ob::State*> states;
  for (unsigned int i = 0; i < path.getStateCount(); ++i) states.push_back(path.getState(i));
  scene::saveMbmTrajectory(file, armTrajectory(p, space.pathConfigurations(states)), comment);
}

/// A name as a file name part: characters other than letters, digits, '-',
/// '_' and '.' become '_'.
std::string fileNamePart(std::string name) {
  for (char& c : name) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.')) c = '_';
  }
  return name;
}

}  // namespace

std::string plannerFromPlannerId(const std::string& planner_id) {
  std::string name = planner_id;
  const std::string config = "kConfigDefault";
  if (name.size() > config.size() && name.compare(name.size() - config.size(), config.size(), config) == 0) {
    name.erase(name.size() - config.size());
  }
  // MoveIt configurations name variants with a trailing word ("BKPIECEGood"):
  // drop capitalised words from the end until a planner matches.
  while (!name.empty()) {
    const std::string canonical = canonicalPlannerName(name);
    if (!canonical.empty()) return canonical;
    std::size_t cut = name.size() - 1;
    while (cut > 0 && !(std::isupper(static_cast<unsigned char>(name[cut])) &&
                        std::islower(static_cast<unsigned char>(name[cut + 1 < name.size() ? cut + 1 : cut])))) {
      --cut;
    }
    if (cut == 0) break;
    name.erase(cut);
  }
  return {};
}

std::string problemDirName(const std::filesystem::path& problem_dir) {
  std::filesystem::path dir = std::filesystem::absolute(problem_dir).lexically_normal();
  if (dir.filename().empty()) dir = dir.parent_path();  // a trailing separator
  return dir.filename().string();
}

std::vector<ArmBenchLog> runArmBench(const ArmRobot& robot, const std::filesystem::path& problem_dir,
                                     const ArmBenchOptions& options, const ArmBenchObserver& observer) {
  if (options.checkers.empty()) throw InvalidInputError("bench: no checker given");
  for (const std::string& name : options.checkers) findArmChecker(name);  // an unknown name fails now
  if (options.runs < 1) throw InvalidInputError("bench: runs must be at least 1");
  if (!(options.mem_limit > 0.0 && options.mem_limit <= kMaxMemLimit)) {
    throw InvalidInputError("bench: the memory limit must be in (0, " + real(kMaxMemLimit) + "] MB");
  }
  if (!(options.time_limit <= kMaxTimeLimit)) {
    throw InvalidInputError("bench: the time limit must be at most " + real(kMaxTimeLimit) + " s");
  }
  if (!(options.fine_resolution > 0.0) || !(options.verify_resolution > 0.0)) {
    throw InvalidInputError("bench: resolutions must be > 0");
  }
  std::vector<scene::MbmProblemFiles> files = scene::listMbmProblems(problem_dir);
  if (options.problems > 0 && static_cast<int>(files.size()) > options.problems) files.resize(options.problems);
  std::vector<scene::MbmProblemFiles> mine;
  for (std::size_t k = 0; k < files.size(); ++k) {
    if (static_cast<int>(k % static_cast<std::size_t>(options.shard.count)) == options.shard.index) {
      mine.push_back(files[k]);
    }
  }
  // Every problem loads before any runs (a bad file fails at once).
  std::vector<ArmProblem> problems;
  for (const scene::MbmProblemFiles& f : mine) problems.push_back(loadArmProblem(robot, f, options.problem));
  for (const ArmProblem& p : problems) {
    for (const std::string& name :
         options.planners.empty() ? std::vector<std::string>{p.request.planner_id} : options.planners) {
      if (plannerFromPlannerId(name).empty()) {
        throw InvalidInputError(p.files.request.string() + ": planner '" + clipForMessage(name) +
                                "' is not an OMPL geometric planner");
      }
    }
  }
  std::filesystem::create_directories(options.output_dir);
  if (!options.paths_dir.empty()) std::filesystem::create_directories(options.paths_dir);
  const std::string config = problemDirName(problem_dir);

  std::vector<ArmBenchLog> logs;
  for (std::size_t i = 0; i < problems.size(); ++i) {
    const ArmProblem& p = problems[i];
    if (observer.problem_started)
      observer.problem_started(p.name, static_cast<int>(i), static_cast<int>(problems.size()));
    const auto fcl = std::make_shared<const FclArmScene>(p.scene);
    // The certified half of the verification keeps a tenth of the checker's
    // clearance: every path the mdd checker accepts keeps all of it.
    ArmSceneOptions verify_options = p.scene->options();
    verify_options.contact_distance /= 10.0;
    const ArmScene verifier(p.space->modelPtr(), p.world, p.scene->filter(), p.scene->baseInWorld(), verify_options);
    const double time_limit = options.time_limit > 0.0
                                  ? options.time_limit
                                  : (p.request.allowed_planning_time > 0.0 ? p.request.allowed_planning_time : 10.0);
    for (const std::string& checker : options.checkers) {
      ArmSetup setup = makeSetup(p, findArmChecker(checker), fcl, options.fine_resolution);
      ArmBenchLog log;
      log.problem = p.name;
      log.checker = checker;
      char number[16];
      std::snprintf(number, sizeof number, "%04d", p.files.number);
      log.file = options.output_dir / (config + "-" + number + "-" + checker + ".log");
      ot::Benchmark bench(*setup.ss, config + "-" + checker);
      bench.addExperimentParameter("config", "STRING", config);
      bench.addExperimentParameter("checker", "STRING", checker);
      bench.addExperimentParameter("problem", "INTEGER", std::to_string(p.files.number));
      bench.addExperimentParameter("shard", "STRING", toString(options.shard));
      // The checkers' work is read the moment solve() returns (MeteredPlanner),
      // before OMPL's benchmark checks the solution with them.
      std::pair<std::uint64_t, double> solve_counts;
      std::uint64_t solve_motions = 0;
      double solve_seconds = 0.0;  // the planner's own solve(), see MeteredPlanner
      const auto on_solved = [&](double seconds) {
        solve_seconds = seconds;
        solve_counts = setup.counts();
        const auto& mv = setup.ss->getSpaceInformation()->getMotionValidator();
        solve_motions = mv->getValidMotionCount() + mv->getInvalidMotionCount();
      };
      for (const std::string& name :
           options.planners.empty() ? std::vector<std::string>{p.request.planner_id} : options.planners) {
        ob::PlannerPtr planner = makePlanner(plannerFromPlannerId(name), setup.ss->getSpaceInformation());
        planner->setName(name);
        const std::string where = p.files.request.string() + ": planner '" + name + "': ";
        bench.addPlanner(std::make_shared<MeteredPlanner>(planner, on_solved, where));
      }
      std::exception_ptr save_error;  // the first --save-paths failure
      bench.setPreRunEvent([&](const ob::PlannerPtr&) {
        setup.resetCounts();
        solve_seconds = 0.0;
      });
      bench.setPostRunEvent([&](const ob::PlannerPtr& planner, ot::Benchmark::RunProperties& run) {
        run["run index INTEGER"] = std::to_string(bench.getStatus().activeRun);
        run["state checks INTEGER"] = std::to_string(solve_counts.first);
        run["motion checks INTEGER"] = std::to_string(solve_motions);
        run["checking time REAL"] = real(solve_counts.second);
        run["solve time REAL"] = real(solve_seconds);
        const bool solved = setup.ss->haveSolutionPath();
        const bool exact = solved && !setup.ss->getProblemDefinition()->hasApproximateSolution();
        Verdict v;
        if (exact) v = verify(p, verifier, *fcl, *setup.space, setup.ss->getSolutionPath(), options.verify_resolution);
        const bool invalid = exact && (v.invalid_mdd || v.invalid_fcl);
        const bool verified = exact && !invalid;
        run["verified BOOLEAN"] = flag(verified);
        run["invalid solution BOOLEAN"] = flag(invalid);
        run["invalid by mdd BOOLEAN"] = flag(exact && v.invalid_mdd);
        run["invalid by fcl BOOLEAN"] = flag(exact && v.invalid_fcl);
        run["verification time REAL"] = real(v.seconds);
        log.solved += exact ? 1 : 0;
        log.verified += verified ? 1 : 0;
        log.invalid += invalid ? 1 : 0;
        // OMPL's benchmark catches what this event throws and goes on: a
        // path that cannot be written is kept and thrown after the runs.
        if (exact && !options.paths_dir.empty() && !save_error) {
          try {
            savePath(
                p, *setup.space, setup.ss->getSolutionPath(),
                options.paths_dir / (config + "-" + number + "-" + checker + "-" + fileNamePart(planner->getName()) +
                                     "-" + run["run index INTEGER"] + (invalid ? "-invalid" : "") + ".yaml"),
                {p.files.request.filename().string() + ": " + planner->getName() + " with " + checker + ", run " +
                 run["run index INTEGER"] + (invalid ? ", invalid" : ", verified")});
          } catch (...) {
            save_error = std::current_exception();
          }
        }
        if (observer.run_finished) observer.run_finished(checker, planner->getName(), exact, verified, invalid);
      });
      ot::Benchmark::Request request(time_limit, options.mem_limit, static_cast<unsigned>(options.runs), 0.05,
                                     /*displayProgress=*/false, /*saveConsoleOutput=*/false, /*simplify=*/false);
      bench.benchmark(request);
      if (save_error) std::rethrow_exception(save_error);
      std::ofstream out(log.file);
      if (!out || !bench.saveResultsToStream(out) || !(out << std::flush)) {
        throw InvalidInputError("cannot write the benchmark log " + log.file.string());
      }
      logs.push_back(log);
    }
  }
  return logs;
}

}  // namespace mddual::planning
