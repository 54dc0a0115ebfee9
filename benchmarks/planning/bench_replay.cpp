// Replay benchmark: the motion checks a real planner makes, replayed with
// each checker. Random edges (mddual_bench_planning) are not the edges a
// planner asks about: KPIECE grows from states near obstacles and asks for
// lastValid, RRT-Connect's CONNECT runs along free space. Here a planner runs
// on a benchmark config with the MDD checkers for a few seconds while every
// motion check it makes is recorded (its two states and whether it asked for
// lastValid); then the recorded checks are replayed, in order, with the MDD
// motion validator and with OMPL's DiscreteMotionValidator + FCL at the
// space's resolution (what OMPL.app users run), alternating, fastest pass.
//
//   mddual_bench_replay --config FILE.cfg [--config ...] [--planner NAME ...] [--seconds S] [--seed N]
//                       [--passes P] [--cpu] [--save FILE] [--load FILE]
//
// --planner (repeatable; default kpiece and rrtconnect): any name `mddual
// bench --planners` accepts, with its default parameters. --seconds: how long
// the recording run plans (default 3; it stops earlier when it solves).
// --save writes the recorded checks of the (single) config and planner to a
// file, --load replays such a file instead of planning: the same checks for
// two builds (the file holds the states' reals; it is not a portable format).
//
// Output: one Markdown table; per (config, planner): the checks recorded
// (those asking for lastValid), how many each checker finds invalid, the
// mean time per check of each (all, valid only, invalid only; per-check
// times read from the clock around each call), the mean fraction lastValid
// keeps of the invalid checks, and MDD's pair queries and rotating sub-edges
// (triples bounded) per check.
#include <ompl/base/MotionValidator.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bench_clock.h"
#include "mddual/planning/problem_setup.h"

namespace {

namespace ob = ompl::base;
namespace mp = mddual::planning;

struct Options {
  std::vector<std::string> configs;
  std::vector<std::string> planners;
  double seconds = 3.0;
  unsigned long seed = 1;
  int passes = 2;
  bool cpu = false;
  std::string save, load;
};

bool g_cpu_time = false;

double nowSeconds() {
  return mddual::bench::nowSeconds(g_cpu_time);
}

/// The recorded motion checks (states owned, allocated by the recording
/// space information; every setup of a config has the same state layout).
struct Recording {
  struct Check {
    ob::State* s1;
    ob::State* s2;
    bool last_valid;
  };
  ob::SpaceInformationPtr si;
  std::vector<Check> checks;
  std::mutex mutex;
  ~Recording() {
    for (const Check& c : checks) {
      si->freeState(c.s1);
      si->freeState(c.s2);
    }
  }
};

/// Passes every check to `inner` and records it.
class RecordingValidator : public ob::MotionValidator {
 public:
  RecordingValidator(const ob::SpaceInformationPtr& si, ob::MotionValidatorPtr inner, Recording* rec)
      : ob::MotionValidator(si), inner_(std::move(inner)), rec_(rec) {}
  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    record(s1, s2, false);
    return inner_->checkMotion(s1, s2);
  }
  bool checkMotion(const ob::State* s1, const ob::State* s2, std::pair<ob::State*, double>& lastValid) const override {
    record(s1, s2, true);
    return inner_->checkMotion(s1, s2, lastValid);
  }

 private:
  void record(const ob::State* s1, const ob::State* s2, bool last_valid) const {
    const std::lock_guard<std::mutex> lock(rec_->mutex);
    rec_->checks.push_back({si_->cloneState(s1), si_->cloneState(s2), last_valid});
  }
  ob::MotionValidatorPtr inner_;
  Recording* rec_;
};

void save(const Recording& rec, const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) throw std::runtime_error("cannot write " + path);
  const ob::StateSpacePtr& space = rec.si->getStateSpace();
  std::vector<double> reals;
  for (const Recording::Check& c : rec.checks) {
    const char lv = c.last_valid ? 1 : 0;
    std::fwrite(&lv, 1, 1, f);
    for (const ob::State* s : {c.s1, c.s2}) {
      space->copyToReals(reals, s);
      std::fwrite(reals.data(), sizeof(double), reals.size(), f);
    }
  }
  std::fclose(f);
}

void load(Recording* rec, const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) throw std::runtime_error("cannot read " + path);
  const ob::StateSpacePtr& space = rec->si->getStateSpace();
  std::vector<double> reals(space->getValueLocations().size());
  char lv = 0;
  while (std::fread(&lv, 1, 1, f) == 1) {
    Recording::Check c{rec->si->allocState(), rec->si->allocState(), lv != 0};
    for (ob::State* s : {c.s1, c.s2}) {
      if (std::fread(reals.data(), sizeof(double), reals.size(), f) != reals.size()) {
        std::fclose(f);
        throw std::runtime_error(path + ": truncated (not a recording of this config's space?)");
      }
      space->copyFromReals(s, reals);
    }
    rec->checks.push_back(c);
  }
  std::fclose(f);
}

/// One replay pass of a checker over the recording.
struct Pass {
  double seconds = 0.0, valid_seconds = 0.0, invalid_seconds = 0.0;
  int invalid = 0;
  double kept = 0.0;  ///< sum of lastValid.second over the invalid lastValid checks
  int invalid_last_valid = 0;
  std::vector<char> verdicts;  ///< 1: valid
};

Pass replay(const Recording& rec, const ob::SpaceInformationPtr& si, const ob::MotionValidatorPtr& validator) {
  Pass out;
  out.verdicts.reserve(rec.checks.size());
  ob::State* last = si->allocState();
  for (const Recording::Check& c : rec.checks) {
    std::pair<ob::State*, double> lv(last, 0.0);
    const double start = nowSeconds();
    const bool valid = c.last_valid ? validator->checkMotion(c.s1, c.s2, lv) : validator->checkMotion(c.s1, c.s2);
    const double s = nowSeconds() - start;
    out.seconds += s;
    (valid ? out.valid_seconds : out.invalid_seconds) += s;
    out.verdicts.push_back(valid ? 1 : 0);
    if (!valid) {
      ++out.invalid;
      if (c.last_valid) {
        ++out.invalid_last_valid;
        out.kept += lv.second;
      }
    }
  }
  si->freeState(last);
  return out;
}

std::string us(double seconds) {
  char buf[32];
  const double v = seconds * 1e6;
  std::snprintf(buf, sizeof buf, v < 10 ? "%.2f" : (v < 100 ? "%.1f" : "%.0f"), v);
  return buf;
}

std::string num(const char* format, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

void benchConfig(const std::string& cfg, const std::string& planner, const Options& opt) {
  const mp::Problem problem = mp::loadProblem(cfg);
  mp::ProblemSetup mdd(problem, mp::CheckerKind::kMdd);
  mp::ProblemSetup fcl(problem, mp::CheckerKind::kFcl);
  const ob::SpaceInformationPtr& si = mdd.spaceInformation();
  const ob::MotionValidatorPtr mdd_validator = si->getMotionValidator();
  Recording rec;
  rec.si = si;
  // 1. The recording: the planner on the MDD checkers, or a saved file.
  if (!opt.load.empty()) {
    load(&rec, opt.load);
  } else {
    si->setMotionValidator(std::make_shared<RecordingValidator>(si, mdd_validator, &rec));
    si->setup();
    mddual::scene::PlannerSpec spec;
    spec.name = planner;
    mdd.simpleSetup().setPlanner(mdd.makePlanner(spec));
    mdd.applyPlannerContext(spec);
    mdd.simpleSetup().solve(opt.seconds);
    si->setMotionValidator(mdd_validator);
    si->setup();
  }
  if (!opt.save.empty()) save(rec, opt.save);
  if (rec.checks.empty()) throw std::runtime_error(cfg + ": " + planner + " made no motion check");
  // 2. Replay, alternating the checkers; the fastest pass of each.
  Pass best_mdd, best_fcl;
  best_mdd.seconds = best_fcl.seconds = 1e300;
  std::uint64_t pairs = 0, sub_edges = 0;
  for (int p = 0; p < opt.passes; ++p) {
    mdd.resetStats();
    Pass m = replay(rec, si, mdd_validator);
    const mp::CheckStats st = mdd.stats();
    pairs = st.pair_queries;
    sub_edges = st.sub_edges;
    if (m.seconds < best_mdd.seconds) best_mdd = std::move(m);
    Pass f = replay(rec, fcl.spaceInformation(), fcl.spaceInformation()->getMotionValidator());
    if (f.seconds < best_fcl.seconds) best_fcl = std::move(f);
  }
  // 3. The row.
  const double n = static_cast<double>(rec.checks.size());
  const auto lv_count = std::count_if(rec.checks.begin(), rec.checks.end(), [](const auto& c) { return c.last_valid; });
  int fcl_valid_mdd_invalid = 0;
  for (std::size_t k = 0; k < rec.checks.size(); ++k) {
    if (best_mdd.verdicts[k] == 0 && best_fcl.verdicts[k] == 1) ++fcl_valid_mdd_invalid;
  }
  const auto mean = [](double s, int count) { return count > 0 ? s / count : 0.0; };
  const int valid_m = static_cast<int>(n) - best_mdd.invalid, valid_f = static_cast<int>(n) - best_fcl.invalid;
  std::printf(
      "| %s | %s | %zu (%ld) | %d / %d (%d) | %s | %s | **%.1fx** | %s / %s | %s / %s | %s / %s | %.1f / %.0f |\n",
      problem.name.c_str(), planner.c_str(), rec.checks.size(), static_cast<long>(lv_count), best_mdd.invalid,
      best_fcl.invalid, fcl_valid_mdd_invalid, us(best_mdd.seconds / n).c_str(), us(best_fcl.seconds / n).c_str(),
      best_fcl.seconds / best_mdd.seconds, us(mean(best_mdd.valid_seconds, valid_m)).c_str(),
      us(mean(best_fcl.valid_seconds, valid_f)).c_str(), us(mean(best_mdd.invalid_seconds, best_mdd.invalid)).c_str(),
      us(mean(best_fcl.invalid_seconds, best_fcl.invalid)).c_str(),
      best_mdd.invalid_last_valid > 0 ? num("%.3f", best_mdd.kept / best_mdd.invalid_last_valid).c_str() : "-",
      best_fcl.invalid_last_valid > 0 ? num("%.3f", best_fcl.kept / best_fcl.invalid_last_valid).c_str() : "-",
      static_cast<double>(pairs) / n, static_cast<double>(sub_edges) / n);
  std::fflush(stdout);
}

[[noreturn]] void usage(const char* argv0) {
  std::fprintf(stderr,
               "usage: %s --config FILE.cfg [--config ...] [--planner NAME ...] [--seconds S] [--seed N] "
               "[--passes P] [--cpu] [--save FILE] [--load FILE]\n",
               argv0);
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage(argv[0]);
      return argv[++i];
    };
    if (a == "--config") {
      opt.configs.push_back(value());
    } else if (a == "--planner") {
      opt.planners.push_back(value());
    } else if (a == "--seconds") {
      opt.seconds = std::atof(value().c_str());
    } else if (a == "--seed") {
      opt.seed = std::strtoul(value().c_str(), nullptr, 10);
    } else if (a == "--passes") {
      opt.passes = std::max(1, std::atoi(value().c_str()));
    } else if (a == "--cpu") {
      opt.cpu = true;
    } else if (a == "--save") {
      opt.save = value();
    } else if (a == "--load") {
      opt.load = value();
    } else {
      usage(argv[0]);
    }
  }
  if (opt.configs.empty() || !(opt.seconds > 0.0)) usage(argv[0]);
  if (opt.planners.empty()) opt.planners = {"kpiece", "rrtconnect"};
  if ((!opt.save.empty() || !opt.load.empty()) && opt.configs.size() * opt.planners.size() != 1) {
    std::fprintf(stderr, "%s: --save and --load take one config and one planner\n", argv[0]);
    return 2;
  }
  g_cpu_time = opt.cpu;
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  ompl::RNG::setSeed(opt.seed);  // before any of OMPL's generators exists
  std::printf(
      "Motion checks a planner made with the MDD checkers (seed %lu, %g s of planning), replayed with each checker "
      "(fastest of %d passes, %s):\n\n",
      opt.seed, opt.seconds, opt.passes, opt.cpu ? "thread CPU time" : "wall-clock time");
  std::printf(
      "| config | planner | checks (lastValid) | invalid MDD / FCL (FCL valid, MDD invalid) | MDD (us) | OMPL discrete "
      "+ FCL "
      "(us) | discrete / MDD | valid only MDD / FCL (us) | invalid only MDD / FCL (us) | kept MDD / FCL | MDD pair "
      "queries / sub-edges |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& cfg : opt.configs) {
    for (const std::string& planner : opt.planners) {
      try {
        benchConfig(cfg, planner, opt);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "mddual_bench_replay: %s\n", e.what());
        return 1;
      }
    }
  }
  return 0;
}
