// Arm edge benchmark: the cost of one motion check and one state check of
// an arm, mdd's certified check against OMPL's DiscreteMotionValidator with
// FCL at the space's default resolution (what MoveIt runs) and with segments
// of at most 1/32 rad (fcl-fine), installed as `mddual bench` installs them
// (the checker table), on the same links, self pairs and world, in the same
// run.
//
//   mddual_bench_arm_edges PROBLEM_DIR --robot URDF --srdf SRDF [--problems N] [--edges M] [--seed S]
//                          [--range R] [--passes P]
//
// Edges are drawn as RRT-Connect draws them: from a valid state (uniform,
// rejected until valid) toward a uniform sample, cut at --range times the
// space's maximum extent (default 0.2, RRT-Connect's default range). Each
// pass checks every edge with each checker (alternating), on the calling
// thread's CPU clock; the fastest pass counts.
//
// Output: one Markdown row per problem and a total: edges, the share mdd
// finds colliding, FCL-valid edges mdd refuses (a contact between FCL's
// samples or a false alarm) and mdd-valid edges fcl or fcl-fine refuses
// (must be 0), microseconds per edge of each and per state, and the ratios
// to mdd (above 1: mdd is faster).
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "bench_support.h"
#include "mddual/planning/arm_checkers.h"
#include "mddual/planning/arm_problem.h"
#include "mddual/planning/checker_registry.h"

namespace ob = ompl::base;
namespace mp = mddual::planning;
using mddual::bench::nowSeconds;

namespace {

struct Edge {
  std::vector<double> q0, q1;  // group coordinates, in the state's order
};

struct Totals {
  int edges = 0;
  int mdd_colliding = 0;
  int fcl_colliding = 0;
  int mdd_only = 0;  // FCL valid, mdd invalid
  int fcl_only = 0;  // mdd valid, fcl or fcl-fine invalid
  double mdd_edge_s = 0.0;
  double fcl_edge_s = 0.0;
  double fine_edge_s = 0.0;
  int states = 0;
  double mdd_state_s = 0.0;
  double fcl_state_s = 0.0;
  long queries = 0;     // mdd's pair bound queries
  long fcl_states = 0;  // FCL's state checks in its motion checks

  void add(const Totals& o) {
    edges += o.edges;
    mdd_colliding += o.mdd_colliding;
    fcl_colliding += o.fcl_colliding;
    mdd_only += o.mdd_only;
    fcl_only += o.fcl_only;
    mdd_edge_s += o.mdd_edge_s;
    fcl_edge_s += o.fcl_edge_s;
    fine_edge_s += o.fine_edge_s;
    states += o.states;
    mdd_state_s += o.mdd_state_s;
    fcl_state_s += o.fcl_state_s;
    queries += o.queries;
    fcl_states += o.fcl_states;
  }
};

void printRow(const std::string& name, const Totals& t) {
  const double e = std::max(1, t.edges);
  const double s = std::max(1, t.states);
  const double mdd = std::max(1e-12, t.mdd_edge_s);
  std::printf("| %s | %d | %.0f%% | %d | %d | %.1f | %.1f | %s | %s | %.2f | %s | %.1f | %s | %s | %.2f |\n",
              name.c_str(), t.edges, 100.0 * t.mdd_colliding / e, t.mdd_only, t.fcl_only,
              static_cast<double>(t.queries) / e, static_cast<double>(t.fcl_states) / e,
              mddual::bench::micros(t.mdd_edge_s / e).c_str(), mddual::bench::micros(t.fcl_edge_s / e).c_str(),
              t.fcl_edge_s / mdd, mddual::bench::micros(t.fine_edge_s / e).c_str(), t.fine_edge_s / mdd,
              mddual::bench::micros(t.mdd_state_s / s).c_str(), mddual::bench::micros(t.fcl_state_s / s).c_str(),
              t.fcl_state_s / std::max(1e-12, t.mdd_state_s));
}

Totals runProblem(const mp::ArmProblem& p, int edges, double range, int passes) {
  auto space = mp::ArmSpace::make(p.space->modelPtr(), p.space->variables(), p.start);
  auto si_mdd = std::make_shared<ob::SpaceInformation>(space->stateSpace());
  const mp::ArmChecking mdd = mp::useExactChecking(si_mdd, space, p.scene);
  si_mdd->setup();
  // fcl and fcl-fine, as the checker table installs them for `mddual bench`.
  auto fcl_scene = std::make_shared<const mp::FclArmScene>(p.scene);
  struct Peer {
    mp::ArmSpacePtr space;
    ob::SpaceInformationPtr si;
    mp::InstalledChecker installed;
  };
  const auto peer = [&](const std::string& name) {
    Peer out;
    out.space = mp::ArmSpace::make(p.space->modelPtr(), p.space->variables(), p.start);
    out.si = std::make_shared<ob::SpaceInformation>(out.space->stateSpace());
    out.installed = mp::findArmChecker(name).install({out.si, out.space, p.scene, fcl_scene});
    out.si->setup();
    return out;
  };
  const Peer fcl = peer("fcl"), fine = peer("fcl-fine");

  // 1. Draw the edges (on si_mdd; the two spaces are alike).
  const double max_length = range * si_mdd->getMaximumExtent();
  ob::StateSamplerPtr sampler = si_mdd->allocStateSampler();
  ob::ScopedState<> a(si_mdd), b(si_mdd), c(si_mdd);
  std::vector<Edge> drawn;
  const int dim = space->dimension();
  auto coordinates = [&](const ob::State* s) {
    std::vector<double> full = space->configuration(s);
    std::vector<double> out;
    for (int v : space->variables()) out.push_back(full[static_cast<std::size_t>(v)]);
    return out;
  };
  while (static_cast<int>(drawn.size()) < edges) {
    sampler->sampleUniform(a.get());
    if (!si_mdd->isValid(a.get())) continue;
    sampler->sampleUniform(b.get());
    const double d = si_mdd->distance(a.get(), b.get());
    si_mdd->getStateSpace()->interpolate(a.get(), b.get(), d > max_length ? max_length / d : 1.0, c.get());
    drawn.push_back({coordinates(a.get()), coordinates(c.get())});
  }
  (void)dim;

  // 2. Time them, alternating checkers per pass; the fastest pass counts.
  Totals best;
  auto setGroup = [&](const mp::ArmSpace& sp, ob::State* s, const std::vector<double>& g) {
    std::vector<double> full = sp.fixedConfiguration();
    for (std::size_t i = 0; i < g.size(); ++i) full[static_cast<std::size_t>(sp.variables()[i])] = g[i];
    sp.setState(s, full.data());
  };
  ob::ScopedState<> m0(si_mdd), m1(si_mdd), f0(fcl.si), f1(fcl.si), g0(fine.si), g1(fine.si);
  for (int pass = 0; pass < passes; ++pass) {
    Totals t;
    for (const Edge& e : drawn) {
      setGroup(*space, m0.get(), e.q0);
      setGroup(*space, m1.get(), e.q1);
      setGroup(*fcl.space, f0.get(), e.q0);
      setGroup(*fcl.space, f1.get(), e.q1);
      setGroup(*fine.space, g0.get(), e.q0);
      setGroup(*fine.space, g1.get(), e.q1);
      double t0 = nowSeconds(true);
      const bool mdd_ok = mdd.motion_validator->checkMotion(m0.get(), m1.get());
      double t1 = nowSeconds(true);
      const auto before = fcl.installed.counts().state_checks;
      const bool fcl_ok = fcl.si->checkMotion(f0.get(), f1.get());
      double t2 = nowSeconds(true);
      const bool fine_ok = fine.si->checkMotion(g0.get(), g1.get());
      const double t3 = nowSeconds(true);
      t.fcl_states += static_cast<long>(fcl.installed.counts().state_checks - before);
      t.queries += mdd.motion_validator->edgeContact(m0.get(), m1.get(), mp::EdgeQuery::kValidity).distance_queries;
      t.mdd_edge_s += t1 - t0;
      t.fcl_edge_s += t2 - t1;
      t.fine_edge_s += t3 - t2;
      ++t.edges;
      t.mdd_colliding += mdd_ok ? 0 : 1;
      t.fcl_colliding += fcl_ok ? 0 : 1;
      t.mdd_only += (!mdd_ok && fcl_ok) ? 1 : 0;
      t.fcl_only += (mdd_ok && !(fcl_ok && fine_ok)) ? 1 : 0;
      t0 = nowSeconds(true);
      (void)si_mdd->isValid(m1.get());
      t1 = nowSeconds(true);
      (void)fcl.si->isValid(f1.get());
      t2 = nowSeconds(true);
      t.mdd_state_s += t1 - t0;
      t.fcl_state_s += t2 - t1;
      ++t.states;
    }
    if (pass == 0) {
      best = t;
    } else {
      best.mdd_edge_s = std::min(best.mdd_edge_s, t.mdd_edge_s);
      best.fcl_edge_s = std::min(best.fcl_edge_s, t.fcl_edge_s);
      best.fine_edge_s = std::min(best.fine_edge_s, t.fine_edge_s);
      best.mdd_state_s = std::min(best.mdd_state_s, t.mdd_state_s);
      best.fcl_state_s = std::min(best.fcl_state_s, t.fcl_state_s);
    }
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mdd's certified arm edges against FCL with OMPL's discrete validator (fcl, fcl-fine), per check"};
  std::string dir, urdf, srdf;
  int problems = 5, edges = 200, passes = 2;
  unsigned seed = 1;
  double range = 0.2;
  app.add_option("problem_dir", dir, "MotionBenchMaker problem directory")->required();
  app.add_option("--robot", urdf, "URDF")->required();
  app.add_option("--srdf", srdf, "SRDF")->required();
  app.add_option("--problems", problems, "first N problems")->check(CLI::PositiveNumber);
  app.add_option("--edges", edges, "edges per problem")->check(CLI::PositiveNumber);
  app.add_option("--passes", passes, "timed passes (fastest counts)")->check(CLI::PositiveNumber);
  app.add_option("--seed", seed, "OMPL's seed");
  app.add_option("--range", range, "edge length, fraction of the maximum extent")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  ompl::RNG::setSeed(seed);
  try {
    const mp::ArmRobot robot = mp::loadArmRobot(urdf, srdf);
    const auto files = mddual::scene::listMbmProblems(dir);
    std::printf(
        "| problem | edges | colliding | mdd only | fcl only | mdd queries | fcl states | mdd us/edge | fcl us/edge | "
        "fcl/mdd | fcl-fine us/edge | fine/mdd | mdd us/state | fcl us/state | fcl/mdd |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    Totals all;
    for (std::size_t i = 0; i < files.size() && static_cast<int>(i) < problems; ++i) {
      // Cold motion checks, as OMPL's discrete validator makes them: no
      // memo of free end states (ArmSceneOptions::remember_free_states).
      mp::ArmProblemOptions options;
      options.scene.remember_free_states = false;
      const mp::ArmProblem p = mp::loadArmProblem(robot, files[i], options);
      const Totals t = runProblem(p, edges, range, passes);
      printRow(p.name, t);
      all.add(t);
    }
    printRow("all", all);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mddual_bench_arm_edges: %s\n", e.what());
    return 2;
  }
  return 0;
}
