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
// two builds. The file names its config and state size, checked on --load; the
// states are raw doubles (not portable across machines).
//
// Output: one Markdown table; per (config, planner): the checks recorded
// (those asking for lastValid), how many each checker finds invalid and on how
// many they disagree (each way: "FCL valid, MDD invalid" is a contact between
// the discrete check's samples or one of MDD's rotating false alarms; "MDD
// valid, FCL invalid" would be a contact MDD missed), the mean time per check
// of each (all, valid only, invalid only; per-check times read from the clock
// around each call), the mean fraction lastValid keeps over the lastValid
// checks both find invalid, and MDD's pair queries and rotating-search
// triples (robot node, world node, interval) bounded per check.
//
// The MDD validator is told the planner's discarded lastValid fraction, as
// `mddual bench` tells it (discardedLastValidFraction: KPIECE1's
// min_valid_path_fraction, 0 for RRT-Connect and RRT): on a rotating edge whose
// state at that fraction collides it answers lastValid = (s1, 0) without the
// first-contact search, so with KPIECE MDD's mean kept fraction counts those
// checks as 0 (KPIECE drops them whatever their fraction). With --load the
// fraction is that of --planner's planner: the file does not name the planner
// that recorded it, so name the same one.
//
// Before timing, MDD's enlarged robot pieces (built on first use by a planning
// run) are all built, so that no pass times their one-time construction.
#include <ompl/base/MotionValidator.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bench_support.h"
#include "mddual/planning/planner_factory.h"
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

/// First bytes of a recording file (then the config's name, the number of
/// reals per state, the number of checks, and the checks).
constexpr char kMagic[8] = {'M', 'D', 'D', 'R', 'E', 'C', '0', '1'};

std::FILE* openFile(const std::string& path, const char* mode) {
  std::FILE* f = std::fopen(path.c_str(), mode);
  if (f == nullptr) throw std::runtime_error("cannot open " + path + ": " + std::strerror(errno));
  return f;
}

void save(const Recording& rec, const std::string& name, const std::string& path) {
  std::FILE* f = openFile(path, "wb");
  const ob::StateSpacePtr& space = rec.si->getStateSpace();
  const std::uint64_t name_size = name.size(), reals = space->getValueLocations().size(), count = rec.checks.size();
  bool ok = std::fwrite(kMagic, 1, sizeof kMagic, f) == sizeof kMagic && std::fwrite(&name_size, 8, 1, f) == 1 &&
            std::fwrite(name.data(), 1, name.size(), f) == name.size() && std::fwrite(&reals, 8, 1, f) == 1 &&
            std::fwrite(&count, 8, 1, f) == 1;
  std::vector<double> values;
  for (const Recording::Check& c : rec.checks) {
    const char lv = c.last_valid ? 1 : 0;
    ok = ok && std::fwrite(&lv, 1, 1, f) == 1;
    for (const ob::State* s : {c.s1, c.s2}) {
      space->copyToReals(values, s);
      ok = ok && std::fwrite(values.data(), sizeof(double), values.size(), f) == values.size();
    }
  }
  if (std::fclose(f) != 0 || !ok) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
}

void load(Recording* rec, const std::string& name, const std::string& path) {
  std::FILE* f = openFile(path, "rb");
  const auto fail = [&](const std::string& what) {
    std::fclose(f);
    throw std::runtime_error(path + ": " + what);
  };
  const ob::StateSpacePtr& space = rec->si->getStateSpace();
  char magic[sizeof kMagic] = {};
  std::uint64_t name_size = 0, reals = 0, count = 0;
  if (std::fread(magic, 1, sizeof magic, f) != sizeof magic || std::memcmp(magic, kMagic, sizeof magic) != 0 ||
      std::fread(&name_size, 8, 1, f) != 1 || name_size > 4096) {
    fail("not a recording of mddual_bench_replay (--save)");
  }
  std::string recorded(name_size, '\0');
  if (std::fread(&recorded[0], 1, recorded.size(), f) != recorded.size() || std::fread(&reals, 8, 1, f) != 1 ||
      std::fread(&count, 8, 1, f) != 1) {
    fail("truncated header");
  }
  if (recorded != name) fail("recorded on config '" + recorded + "', not '" + name + "'");
  if (reals != space->getValueLocations().size())
    fail("states of " + std::to_string(reals) + " values, not this space's");
  std::vector<double> values(reals);
  for (std::uint64_t k = 0; k < count; ++k) {
    char lv = 0;
    Recording::Check c{rec->si->allocState(), rec->si->allocState(), false};
    rec->checks.push_back(c);  // owned from here on (freed by ~Recording)
    bool ok = std::fread(&lv, 1, 1, f) == 1;
    for (ob::State* s : {c.s1, c.s2}) {
      ok = ok && std::fread(values.data(), sizeof(double), values.size(), f) == values.size();
      if (ok) space->copyFromReals(s, values);
    }
    if (!ok) fail("truncated at check " + std::to_string(k) + " of " + std::to_string(count));
    rec->checks.back().last_valid = lv != 0;
  }
  std::fclose(f);
}

/// One replay pass of a checker over the recording.
struct Pass {
  double seconds = 0.0, valid_seconds = 0.0, invalid_seconds = 0.0;
  int invalid = 0;
  std::vector<char> verdicts;  ///< per check, 1: valid
  std::vector<double> kept;    ///< per check, lastValid.second (invalid lastValid checks; else 0)
  mp::CheckStats stats;        ///< the checkers' counts over the pass
};

Pass replay(const Recording& rec, const ob::SpaceInformationPtr& si, const ob::MotionValidatorPtr& validator) {
  Pass out;
  out.verdicts.reserve(rec.checks.size());
  out.kept.reserve(rec.checks.size());
  ob::State* last = si->allocState();
  for (const Recording::Check& c : rec.checks) {
    std::pair<ob::State*, double> lv(last, 0.0);
    const double start = nowSeconds();
    const bool valid = c.last_valid ? validator->checkMotion(c.s1, c.s2, lv) : validator->checkMotion(c.s1, c.s2);
    const double s = nowSeconds() - start;
    out.seconds += s;
    (valid ? out.valid_seconds : out.invalid_seconds) += s;
    out.verdicts.push_back(valid ? 1 : 0);
    out.kept.push_back(!valid && c.last_valid ? lv.second : 0.0);
    if (!valid) ++out.invalid;
  }
  si->freeState(last);
  return out;
}

std::string us(double seconds) {
  return mddual::bench::micros(seconds);
}

std::string num(const char* format, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

void benchConfig(const std::string& cfg, const std::string& planner, const Options& opt) {
  const mp::Problem problem = mp::loadProblem(cfg);
  mp::ProblemSetup mdd(problem, "mdd");
  mp::ProblemSetup fcl(problem, "fcl");
  const ob::SpaceInformationPtr& si = mdd.spaceInformation();
  const ob::MotionValidatorPtr mdd_validator = si->getMotionValidator();
  Recording rec;
  rec.si = si;
  // 1. The planner, and the largest lastValid fraction it drops, told to the
  //    MDD validator as `mddual bench` does (recording and replay alike).
  mddual::scene::PlannerSpec spec;
  spec.name = planner;
  const ob::PlannerPtr planner_ptr = mdd.makePlanner(spec);
  mdd.setDiscardedLastValidFraction(mp::discardedLastValidFraction(*planner_ptr));
  // 2. The recording: the planner on the MDD checkers, or a saved file.
  if (!opt.load.empty()) {
    load(&rec, problem.name, opt.load);
  } else {
    si->setMotionValidator(std::make_shared<RecordingValidator>(si, mdd_validator, &rec));
    si->setup();
    mdd.simpleSetup().setPlanner(planner_ptr);
    mdd.applyPlannerContext(spec);
    mdd.simpleSetup().solve(opt.seconds);
    si->setMotionValidator(mdd_validator);
    si->setup();
  }
  if (!opt.save.empty()) save(rec, problem.name, opt.save);
  if (rec.checks.empty()) throw std::runtime_error(cfg + ": " + planner + ": no motion check recorded");
  // 3. MDD's one-time set-up (see the file comment), then the replay,
  //    alternating the checkers; the fastest pass of each.
  mddual::bench::buildEnlargedPieces(*mdd.mddScene());
  Pass m, f;
  m.seconds = f.seconds = 1e300;
  for (int p = 0; p < opt.passes; ++p) {
    mdd.resetStats();
    Pass pass = replay(rec, si, mdd_validator);
    pass.stats = mdd.stats();
    if (pass.seconds < m.seconds) m = std::move(pass);
    pass = replay(rec, fcl.spaceInformation(), fcl.spaceInformation()->getMotionValidator());
    if (pass.seconds < f.seconds) f = std::move(pass);
  }
  // 4. The row.
  const double n = static_cast<double>(rec.checks.size());
  long last_valid = 0, mdd_only = 0, fcl_only = 0, both_lv = 0;
  double kept_m = 0.0, kept_f = 0.0;
  for (std::size_t k = 0; k < rec.checks.size(); ++k) {
    last_valid += rec.checks[k].last_valid ? 1 : 0;
    mdd_only += m.verdicts[k] == 0 && f.verdicts[k] == 1;
    fcl_only += m.verdicts[k] == 1 && f.verdicts[k] == 0;
    if (rec.checks[k].last_valid && m.verdicts[k] == 0 && f.verdicts[k] == 0) {
      ++both_lv;
      kept_m += m.kept[k];
      kept_f += f.kept[k];
    }
  }
  const auto mean = [](double s, int count) { return count > 0 ? s / count : 0.0; };
  const int valid_m = static_cast<int>(n) - m.invalid, valid_f = static_cast<int>(n) - f.invalid;
  const std::string kept = both_lv > 0 ? num("%.3f", kept_m / static_cast<double>(both_lv)) + " / " +
                                             num("%.3f", kept_f / static_cast<double>(both_lv))
                                       : "- / -";
  std::printf(
      "| %s | %s | %zu (%ld) | %d / %d (%ld / %ld) | %s | %s | **%.1fx** | %s / %s | %s / %s | %s | %.1f / %.0f |\n",
      problem.name.c_str(), planner.c_str(), rec.checks.size(), last_valid, m.invalid, f.invalid, mdd_only, fcl_only,
      us(m.seconds / n).c_str(), us(f.seconds / n).c_str(), f.seconds / m.seconds,
      us(mean(m.valid_seconds, valid_m)).c_str(), us(mean(f.valid_seconds, valid_f)).c_str(),
      us(mean(m.invalid_seconds, m.invalid)).c_str(), us(mean(f.invalid_seconds, f.invalid)).c_str(), kept.c_str(),
      static_cast<double>(m.stats.pair_queries) / n, static_cast<double>(m.stats.sub_edges) / n);
  std::fflush(stdout);
}

[[noreturn]] void usage(const char* argv0) {
  std::fprintf(stderr,
               "usage: %s --config FILE.cfg [--config ...] [--planner NAME ...] [--seconds S] [--seed N] "
               "[--passes P] [--cpu] [--save FILE] [--load FILE]\n",
               argv0);
  std::exit(2);
}

/// `text` as a number of the option `option`; exits with a message naming
/// both when it is not one (or not finite).
double parseNumber(const std::string& option, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno != 0 || !std::isfinite(v)) {
    std::fprintf(stderr, "mddual_bench_replay: %s: '%s' is not a number\n", option.c_str(), text.c_str());
    std::exit(2);
  }
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "mddual_bench_replay: %s needs a value\n", a.c_str());
        usage(argv[0]);
      }
      return argv[++i];
    };
    if (a == "--config") {
      opt.configs.push_back(value());
    } else if (a == "--planner") {
      opt.planners.push_back(value());
    } else if (a == "--seconds") {
      opt.seconds = parseNumber(a, value());
      if (!(opt.seconds > 0.0)) {
        std::fprintf(stderr, "mddual_bench_replay: --seconds must be > 0\n");
        return 2;
      }
    } else if (a == "--seed") {
      opt.seed = static_cast<unsigned long>(parseNumber(a, value()));
    } else if (a == "--passes") {
      opt.passes = std::max(1, static_cast<int>(parseNumber(a, value())));
    } else if (a == "--cpu") {
      opt.cpu = true;
    } else if (a == "--save") {
      opt.save = value();
    } else if (a == "--load") {
      opt.load = value();
    } else {
      std::fprintf(stderr, "mddual_bench_replay: unknown option '%s'\n", a.c_str());
      usage(argv[0]);
    }
  }
  if (opt.configs.empty()) {
    std::fprintf(stderr, "mddual_bench_replay: no --config given\n");
    usage(argv[0]);
  }
  if (opt.planners.empty()) opt.planners = {"kpiece", "rrtconnect"};
  if ((!opt.save.empty() || !opt.load.empty()) && opt.configs.size() * opt.planners.size() != 1) {
    std::fprintf(stderr, "%s: --save and --load take one config and one planner\n", argv[0]);
    return 2;
  }
  g_cpu_time = opt.cpu;
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  ompl::RNG::setSeed(opt.seed);  // before any of OMPL's generators exists
  const std::string source = opt.load.empty()
                                 ? "seed " + std::to_string(opt.seed) + ", " + num("%g", opt.seconds) + " s of planning"
                                 : "loaded from " + opt.load;
  std::printf(
      "Motion checks a planner made with the MDD checkers (%s), replayed with each checker (fastest of %d passes, "
      "%s):\n\n",
      source.c_str(), opt.passes, opt.cpu ? "thread CPU time" : "wall-clock time");
  std::printf(
      "| config | planner | checks (lastValid) | invalid MDD / FCL (only MDD / only FCL) | MDD (us) | OMPL discrete + "
      "FCL (us) | discrete / MDD | valid only MDD / FCL (us) | invalid only MDD / FCL (us) | kept MDD / FCL | MDD "
      "pair queries / triples |\n");
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
