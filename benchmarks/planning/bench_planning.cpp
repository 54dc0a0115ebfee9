// Planning-layer benchmark: per scene, the time of a state check and of a
// motion check with the MDD checkers against FCL over the same pieces: FCL's
// state checker with OMPL's DiscreteMotionValidator at the space's default
// resolution (what OMPL.app users run), and FCL's continuous collision
// (naive and conservative advancement), with the narrow-phase queries per
// check. Prints Markdown tables.
//
//   mddual_bench_planning [--quick] [--states N] [--edges N] [--passes P] [--seed S] [--scene NAME] [--cpu]
//                         [--config FILE.cfg ...] [--no-ccd] [--mdd-only]
//
// Scenes: the built-in example scenes, or (--config, repeatable) the SE(2)
// and SE(3) scenes of benchmark configs, loaded as `mddual bench` loads them.
// --no-ccd leaves out FCL's continuous validators (minutes per row on the
// large mesh configs). --mdd-only times the MDD checkers alone (one line per
// edge kind, for comparing two builds; no peer, so no ratio).
//
// Timing: each checker runs the same list of states (or edges) `passes` times
// in one thread, after MDD's one-time set-up (its enlarged robot pieces, all
// built first and timed on a line of their own); a row reports the fastest
// pass's mean time per check (the checkers' own timers are off: they would
// add two clock reads per call to both sides). Wall-clock time by default;
// --cpu measures the thread's CPU time instead (steadier on a shared, loaded
// machine). Edges: s1 valid; s2 at a distance uniform up to, or equal to,
// the "range" = 20% of the bounds' diagonal (OMPL's default range for RRT-like
// planners is 20% of the space's extent); rotating edges turn by up to pi.
#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/Console.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_support.h"
#include "mddual/constants.h"
#include "mddual/generators.h"
#include "mddual/planning/example_scenes.h"
#include "mddual/planning/fcl_checkers.h"
#include "mddual/planning/mdd_checkers.h"
#include "mddual/planning/problem_setup.h"

namespace {

namespace ob = ompl::base;
namespace mp = mddual::planning;
using Rng = std::mt19937_64;
using mddual::kPi;

struct Options {
  int states = 20000;
  int edges = 2000;
  int passes = 3;
  std::uint64_t seed = 1;
  std::string only;                  ///< run only the scene of this name
  bool cpu = false;                  ///< time with the thread's CPU clock
  std::vector<std::string> configs;  ///< benchmark configs to load instead of the example scenes
  bool ccd = true;                   ///< time FCL's continuous validators too
  bool mdd_only = false;             ///< time the MDD checkers only (profiling; no peer, no ratio)
};

/// Set from --cpu: timePerItem reads the thread's CPU clock.
bool g_cpu_time = false;

double nowSeconds() {
  return mddual::bench::nowSeconds(g_cpu_time);
}

void randomState(const mp::PlanningSpace& space, Rng& rng, ob::State* state) {
  const Eigen::AlignedBox3d& b = space.bounds();
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  for (int k = 0; k < 3; ++k) X.translation()[k] = std::uniform_real_distribution<double>(b.min()[k], b.max()[k])(rng);
  switch (space.kind()) {
    case mp::SpaceKind::kSE2:
      X.translation().z() = 0.0;
      X.linear() = Eigen::AngleAxisd(std::uniform_real_distribution<double>(-kPi, kPi)(rng), Eigen::Vector3d::UnitZ())
                       .toRotationMatrix();
      break;
    case mp::SpaceKind::kSE3: X.linear() = mddual::generators::randomRotation(rng); break;
    case mp::SpaceKind::kR2: X.translation().z() = space.fixedZ(); [[fallthrough]];
    case mp::SpaceKind::kR3: X.linear() = space.fixedOrientation().toRotationMatrix(); break;
  }
  space.setPose(X, state);
}

/// s2 at a random distance (up to max_length, or exactly max_length) from s1
/// (within the bounds when it can be); rotated when asked.
void edgeEnd(const mp::PlanningSpace& space, const ob::State* s1, double max_length, bool exact_length, bool rotate,
             Rng& rng, ob::State* s2) {
  Eigen::Isometry3d X = space.pose(s1);
  Eigen::Vector3d d = mddual::generators::randomUnitVector(rng);
  if (space.kind() == mp::SpaceKind::kSE2 || space.kind() == mp::SpaceKind::kR2) d.z() = 0.0;
  d.normalize();
  const double length = exact_length ? max_length : std::uniform_real_distribution<double>(0.0, max_length)(rng);
  for (int attempt = 0; attempt < 20 && !space.positionInBounds(X.translation() + length * d); ++attempt) {
    d = mddual::generators::randomUnitVector(rng);
    if (space.kind() == mp::SpaceKind::kSE2 || space.kind() == mp::SpaceKind::kR2) d.z() = 0.0;
    d.normalize();
  }
  X.translation() += length * d;
  if (rotate) {
    const Eigen::Vector3d axis =
        space.kind() == mp::SpaceKind::kSE2 ? Eigen::Vector3d::UnitZ() : mddual::generators::randomUnitVector(rng);
    X.linear() =
        Eigen::AngleAxisd(std::uniform_real_distribution<double>(-kPi, kPi)(rng), axis).toRotationMatrix() * X.linear();
  }
  space.stateSpace()->copyState(s2, s1);
  space.setPose(X, s2);
}

/// Fastest pass's mean seconds per item.
double timePerItem(int items, int passes, const std::function<void()>& pass) {
  double best = 1e300;
  for (int p = 0; p < passes; ++p) {
    const double start = nowSeconds();
    pass();
    const double s = nowSeconds() - start;
    best = std::min(best, s);
  }
  return best / std::max(1, items);
}

std::string us(double seconds) {
  return mddual::bench::micros(seconds);
}

struct Setup {
  mddual::planning::examples::ExampleScene scene;
  mp::PlanningSpacePtr space;
  std::shared_ptr<mp::MddScene> mdd;
  std::shared_ptr<mp::FclScene> fcl;
  ob::SpaceInformationPtr si, fcl_si, mdd_discrete_si;
  mp::MddStateValidityCheckerPtr mdd_checker, mdd_checker_discrete;
  mp::MddMotionValidatorPtr mdd_motion;
  mp::FclStateValidityCheckerPtr fcl_checker;
};

Setup makeSetup(const mddual::planning::examples::ExampleScene& scene) {
  Setup s;
  s.scene = scene;
  s.space = mddual::planning::examples::makeSpace(scene);
  s.mdd = std::make_shared<mp::MddScene>(scene.robot, scene.world);
  s.fcl = std::make_shared<mp::FclScene>(scene.robot, scene.world);
  s.si = std::make_shared<ob::SpaceInformation>(s.space->stateSpace());
  s.mdd_checker = std::make_shared<mp::MddStateValidityChecker>(s.si, s.space, s.mdd);
  s.mdd_motion = std::make_shared<mp::MddMotionValidator>(s.si, s.space, s.mdd);
  s.si->setStateValidityChecker(s.mdd_checker);
  s.si->setMotionValidator(s.mdd_motion);
  s.si->setup();
  s.mdd_checker->setTiming(false);
  s.mdd_motion->setTiming(false);
  s.fcl_si = std::make_shared<ob::SpaceInformation>(s.space->stateSpace());
  s.fcl_checker = std::make_shared<mp::FclStateValidityChecker>(s.fcl_si, s.space, s.fcl);
  s.fcl_checker->setTiming(false);
  s.fcl_si->setStateValidityChecker(s.fcl_checker);
  s.fcl_si->setMotionValidator(std::make_shared<ob::DiscreteMotionValidator>(s.fcl_si));
  s.fcl_si->setup();
  // OMPL's discrete validator on the MDD state checker, for reference.
  s.mdd_discrete_si = std::make_shared<ob::SpaceInformation>(s.space->stateSpace());
  s.mdd_checker_discrete = std::make_shared<mp::MddStateValidityChecker>(s.mdd_discrete_si, s.space, s.mdd);
  s.mdd_checker_discrete->setTiming(false);
  s.mdd_discrete_si->setStateValidityChecker(s.mdd_checker_discrete);
  s.mdd_discrete_si->setMotionValidator(std::make_shared<ob::DiscreteMotionValidator>(s.mdd_discrete_si));
  s.mdd_discrete_si->setup();
  return s;
}

void benchScene(const mddual::planning::examples::ExampleScene& scene, const Options& opt) {
  Setup s = makeSetup(scene);
  Rng rng(opt.seed);
  const auto& ss = s.space->stateSpace();
  std::printf(
      "\n### %s (%s): robot %zu pieces (radius %.2f), world %zu pieces; FCL objects: robot %d, world %d; "
      "resolution %.3g\n\n",
      scene.name.c_str(), mp::toString(s.space->kind()), scene.robot->pieces().size(), scene.robot->radius(),
      scene.world->pieces().size(), s.fcl->robotObjectCount(), s.fcl->worldObjectCount(),
      s.si->getStateValidityCheckingResolution() * ss->getMaximumExtent());
  // The enlarged robot pieces of rotating edges are built on first use: a
  // planning run pays for them once, in its first rotating checks. Built
  // here, all of them, and timed apart, so that no row below times a build
  // (with one pass, the lastValid rows did: 287 against 172 us per bugtrap
  // edge with a second pass).
  const double setup_start = nowSeconds();
  mddual::bench::buildEnlargedPieces(*s.mdd);
  const int pieces = static_cast<int>(scene.robot->pieces().size());
  std::printf("MDD one-time set-up: enlarged robot pieces (%d levels x %d pieces) %.1f ms (%s)\n\n",
              s.mdd->refinementLevels() + 1, pieces, 1e3 * (nowSeconds() - setup_start),
              opt.cpu ? "thread CPU time" : "wall-clock time");

  // ---- States.
  std::vector<ob::ScopedState<>> states;
  for (int i = 0; i < opt.states; ++i) {
    states.emplace_back(ss);
    randomState(*s.space, rng, states.back().get());
  }
  int invalid = 0;
  for (const auto& st : states) invalid += !s.mdd_checker->isValid(st.get());
  s.mdd_checker->resetCounts();
  s.fcl_checker->resetCounts();
  int sink = 0;
  const double t_mdd = timePerItem(opt.states, opt.passes, [&] {
    for (const auto& st : states) sink += s.mdd_checker->isValid(st.get());
  });
  const double t_fcl = opt.mdd_only ? 0.0 : timePerItem(opt.states, opt.passes, [&] {
    for (const auto& st : states) sink += s.fcl_checker->isValid(st.get());
  });
  const double q_mdd = static_cast<double>(s.mdd_checker->counts().pair_queries) /
                       static_cast<double>(s.mdd_checker->counts().state_checks);
  const double q_fcl = static_cast<double>(s.fcl_checker->counts().pair_queries) /
                       static_cast<double>(s.fcl_checker->counts().state_checks);
  if (opt.mdd_only) {
    std::printf("State checks (%d random states, %.0f%% invalid): MDD %s us (%.2f pair queries)\n\n", opt.states,
                100.0 * invalid / opt.states, us(t_mdd).c_str(), q_mdd);
  } else {
    std::printf(
        "State checks (%d random states, %.0f%% invalid): MDD %s us (%.2f pair queries), FCL %s us (%.2f object "
        "pairs); FCL / MDD = %.2fx\n\n",
        opt.states, 100.0 * invalid / opt.states, us(t_mdd).c_str(), q_mdd, us(t_fcl).c_str(), q_fcl, t_fcl / t_mdd);
  }

  // ---- Edges.
  const double range = 0.2 * (s.space->bounds().max() - s.space->bounds().min()).norm();
  const bool can_rotate = s.space->kind() == mp::SpaceKind::kSE2 || s.space->kind() == mp::SpaceKind::kSE3;
  mp::FclCcdOptions naive_opt;
  naive_opt.solver = mp::FclCcdSolver::kNaive;
  mp::FclContinuousMotionValidator naive(s.fcl_si, s.space, s.fcl, naive_opt);
  mp::FclContinuousMotionValidator ca(s.fcl_si, s.space, s.fcl);
  naive.setTiming(false);
  ca.setTiming(false);
  if (!opt.mdd_only) {
    std::printf(
        "| edges | valid (MDD) | MDD | pair queries | sub-edges | OMPL discrete + FCL | states | **discrete / MDD** | "
        "valid / invalid edges only: discrete / MDD | OMPL discrete + MDD states | FCL CCD naive | FCL CCD CA | CA "
        "answers != MDD |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  }
  using Edges = std::vector<std::pair<ob::ScopedState<>, ob::ScopedState<>>>;
  const auto timeMdd = [&](const Edges& edges) {
    return timePerItem(static_cast<int>(edges.size()), opt.passes, [&] {
      for (const auto& e : edges) sink += s.mdd_motion->checkMotion(e.first.get(), e.second.get());
    });
  };
  const auto timeDiscrete = [&](const Edges& edges) {
    return timePerItem(static_cast<int>(edges.size()), opt.passes, [&] {
      for (const auto& e : edges) sink += s.fcl_si->checkMotion(e.first.get(), e.second.get());
    });
  };
  // checkMotion with lastValid (what KPIECE and the exact RRT-Connect call):
  // the first contact, not only whether there is one.
  ob::ScopedState<> last_state(ss);
  const auto timeLastValid = [&](const Edges& edges, const ob::MotionValidator& v) {
    return timePerItem(static_cast<int>(edges.size()), opt.passes, [&] {
      for (const auto& e : edges) {
        std::pair<ob::State*, double> last_valid(last_state.get(), 0.0);
        sink += v.checkMotion(e.first.get(), e.second.get(), last_valid);
      }
    });
  };
  std::vector<std::string> last_valid_rows;
  for (bool rotate : {false, true}) {
    if (rotate && !can_rotate) continue;
    for (bool full_range : {false, true}) {
      Edges edges, valid_edges, invalid_edges;
      for (int i = 0; i < opt.edges; ++i) {
        ob::ScopedState<> a(ss), b(ss);
        do {
          randomState(*s.space, rng, a.get());
        } while (!s.si->isValid(a.get()));
        edgeEnd(*s.space, a.get(), range, full_range, rotate, rng, b.get());
        edges.emplace_back(a, b);
      }
      int ca_differs = 0;
      for (const auto& e : edges) {
        const bool v = s.mdd_motion->checkMotion(e.first.get(), e.second.get());
        (v ? valid_edges : invalid_edges).push_back(e);
        if (opt.ccd) ca_differs += v != ca.checkMotion(e.first.get(), e.second.get());
      }
      s.mdd_motion->resetCounts();
      s.fcl_checker->resetCounts();
      const int n = opt.edges;
      const double m_mdd = timeMdd(edges);
      if (opt.mdd_only) {
        std::printf("| %s, %s | %.0f%% | checkMotion %s us | with lastValid %s us |\n",
                    rotate ? "rotating" : "translation", full_range ? "length = range" : "length <= range",
                    100.0 * static_cast<double>(valid_edges.size()) / n, us(m_mdd).c_str(),
                    us(timeLastValid(edges, *s.mdd_motion)).c_str());
        continue;
      }
      const double m_disc = timeDiscrete(edges);
      const mp::CheckerCounts c = s.mdd_motion->counts();
      const double states_per_edge =
          static_cast<double>(s.fcl_checker->counts().state_checks) / (opt.passes * static_cast<double>(n));
      const double v_ratio = valid_edges.empty() ? 0.0 : timeDiscrete(valid_edges) / timeMdd(valid_edges);
      const double i_ratio = invalid_edges.empty() ? 0.0 : timeDiscrete(invalid_edges) / timeMdd(invalid_edges);
      const double m_disc_mdd = timePerItem(n, opt.passes, [&] {
        for (const auto& e : edges) sink += s.mdd_discrete_si->checkMotion(e.first.get(), e.second.get());
      });
      const double m_naive = !opt.ccd ? 0.0 : timePerItem(n, opt.passes, [&] {
        for (const auto& e : edges) sink += naive.checkMotion(e.first.get(), e.second.get());
      });
      const double m_ca = !opt.ccd ? 0.0 : timePerItem(n, opt.passes, [&] {
        for (const auto& e : edges) sink += ca.checkMotion(e.first.get(), e.second.get());
      });
      s.mdd_motion->resetCounts();
      const double l_mdd = timeLastValid(edges, *s.mdd_motion);
      const double l_sub = static_cast<double>(s.mdd_motion->counts().sub_edges) /
                           static_cast<double>(s.mdd_motion->counts().motion_checks);
      const double l_disc = timeLastValid(edges, *s.fcl_si->getMotionValidator());
      // How much of the invalid edges each keeps: the mean lastValid fraction.
      const auto meanLastValid = [&](const ob::MotionValidator& v) {
        double sum = 0.0;
        for (const auto& e : invalid_edges) {
          std::pair<ob::State*, double> last_valid(last_state.get(), 0.0);
          v.checkMotion(e.first.get(), e.second.get(), last_valid);
          sum += last_valid.second;
        }
        return invalid_edges.empty() ? 0.0 : sum / static_cast<double>(invalid_edges.size());
      };
      const double kept_mdd = meanLastValid(*s.mdd_motion);
      const double kept_disc = meanLastValid(*s.fcl_si->getMotionValidator());
      char row[256];
      std::snprintf(row, sizeof row, "| lastValid: %s, %s | %s us | %.1f | %s us | **%.1fx** | %.3f / %.3f |\n",
                    rotate ? "rotating" : "translation", full_range ? "length = range" : "length <= range",
                    us(l_mdd).c_str(), l_sub, us(l_disc).c_str(), l_disc / l_mdd, kept_mdd, kept_disc);
      last_valid_rows.emplace_back(row);
      const double checks = static_cast<double>(c.motion_checks);
      const std::string naive_text = opt.ccd ? us(m_naive) + " us" : "-";
      const std::string ca_text = opt.ccd ? us(m_ca) + " us" : "-";
      const std::string ca_differs_text = opt.ccd ? std::to_string(ca_differs) : "-";
      std::printf(
          "| %s, %s | %.0f%% | %s us | %.1f | %.1f | %s us | %.1f | **%.1fx** | %.1fx / %.1fx | %s us | %s | %s "
          "| %s |\n",
          rotate ? "rotating" : "translation", full_range ? "length = range" : "length <= range",
          100.0 * static_cast<double>(valid_edges.size()) / n, us(m_mdd).c_str(),
          static_cast<double>(c.pair_queries) / checks, static_cast<double>(c.sub_edges) / checks, us(m_disc).c_str(),
          states_per_edge, m_disc / m_mdd, v_ratio, i_ratio, us(m_disc_mdd).c_str(), naive_text.c_str(),
          ca_text.c_str(), ca_differs_text.c_str());
    }
  }
  if (opt.mdd_only) return;
  std::printf(
      "\n| edges, checkMotion with lastValid (first contact) | MDD | sub-edges | OMPL discrete + FCL | **discrete / "
      "MDD** | invalid edges: mean lastValid fraction MDD / discrete |\n|---|---|---|---|---|---|\n");
  for (const std::string& row : last_valid_rows) std::printf("%s", row.c_str());
  if (sink == 42) std::printf(" ");
}

/// The scene of a benchmark config (SE(2) or SE(3): the example scenes carry
/// no fixed orientation for the translation-only kinds).
mddual::planning::examples::ExampleScene configScene(const std::string& cfg) {
  const mp::Problem problem = mp::loadProblem(cfg);
  mddual::planning::examples::ExampleScene scene;
  scene.name = problem.name;
  scene.robot = problem.robot();
  scene.world = problem.world();
  scene.bounds = problem.scene->bounds;
  scene.kind = mp::toPlanningKind(problem.config.space);
  if (scene.kind != mp::SpaceKind::kSE2 && scene.kind != mp::SpaceKind::kSE3) {
    throw std::runtime_error(cfg + ": only SE(2) and SE(3) configs are benchmarked here (the space is " +
                             mp::toString(scene.kind) + ")");
  }
  return scene;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> long {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(2);
      }
      return std::strtol(argv[++i], nullptr, 10);
    };
    if (a == "--quick") {
      opt.states = 2000;
      opt.edges = 200;
      opt.passes = 1;
    } else if (a == "--states") {
      opt.states = static_cast<int>(next());
    } else if (a == "--edges") {
      opt.edges = static_cast<int>(next());
    } else if (a == "--passes") {
      opt.passes = static_cast<int>(std::max(1L, next()));
    } else if (a == "--seed") {
      opt.seed = static_cast<std::uint64_t>(next());
    } else if (a == "--cpu") {
      opt.cpu = true;
    } else if (a == "--scene" && i + 1 < argc) {
      opt.only = argv[++i];
    } else if (a == "--config" && i + 1 < argc) {
      opt.configs.emplace_back(argv[++i]);
    } else if (a == "--no-ccd") {
      opt.ccd = false;
    } else if (a == "--mdd-only") {
      opt.mdd_only = true;
      opt.ccd = false;
    } else {
      std::fprintf(stderr,
                   "usage: %s [--quick] [--states N] [--edges N] [--passes P] [--seed S] [--scene NAME] [--cpu] "
                   "[--config FILE.cfg ...] [--no-ccd] [--mdd-only]\n",
                   argv[0]);
      return 2;
    }
  }
  g_cpu_time = opt.cpu;
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  namespace ex = mddual::planning::examples;
  std::printf("## Planning checkers: MDD vs FCL (seed %llu, %d states, %d edges per kind, fastest of %d passes, %s)\n",
              static_cast<unsigned long long>(opt.seed), opt.states, opt.edges, opt.passes,
              opt.cpu ? "thread CPU time" : "wall-clock time");
  if (!opt.configs.empty()) {
    for (const std::string& cfg : opt.configs) {
      try {
        const ex::ExampleScene scene = configScene(cfg);
        if (opt.only.empty() || opt.only == scene.name) benchScene(scene, opt);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "mddual_bench_planning: %s\n", e.what());
        return 1;
      }
    }
    return 0;
  }
  for (const ex::ExampleScene& scene :
       {ex::primitivesScene(opt.seed), ex::meshScene(opt.seed), ex::planarScene(opt.seed), ex::blobScene(opt.seed),
        ex::thinWallScene(0.05), ex::trapScene()}) {
    if (opt.only.empty() || opt.only == scene.name) benchScene(scene, opt);
  }
  return 0;
}
