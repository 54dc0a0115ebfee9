// mddual_bench_pd: speed and accuracy of mddual::penetrationDepth() (exact,
// shallow, approximate with delta 0.1 and 0.01) against FCL's and Bullet's
// penetration (peers.h) and the brute force, on three sets of overlapping
// pairs:
//
//   paper   the MDD-DUAL paper's polytopes and pairs (scene.h): per
//           orientation, the placements of the protocol with a negative
//           signed distance (B placed exactly at penetration depth -delta,
//           an independent reference);
//   random  hulls of random points on ellipsoids, 10 to 5000 vertices each,
//           random orientations and offsets, kept when they overlap;
//   hard    what EPA is reported to fail on: triangles piercing boxes, thin
//           slabs, needles, a small body deep inside a large one, exactly
//           touching boxes (PD 0).
//
//   mddual_bench_pd [--quick] [--sets paper,random,hard] [--orientations N]
//                   [--sizes 10,30,...] [--pairs-per-size N] [--placements N]
//                   [--hard-queries N] [--passes N] [--brute-queries N]
//                   [--label TEXT] [--json FILE]
//
// The reference of every query is our exact method, itself checked against an
// independent answer: the placement's depth (paper set) or the brute force
// (the first --brute-queries queries of each group whose |V(A)| |V(B)| is at
// most 250,000). Timing as in measure.h: each query timed alone, the fastest
// of --passes passes over the whole set, the timer's overhead subtracted.
// Errors are |answer - PD| / PD (penetrating queries) and |answer| / scale
// (touching: PD = 0, scale = the larger radius).
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "mddual/brute_force.h"
#include "mddual/defaults.h"
#include "mddual/generators.h"
#include "mddual/penetration.h"
#include "measure.h"
#include "peers.h"
#include "scene.h"

namespace {

using mddual::ConvexPolytope;
using mddual::PenetrationMethod;
using mddual::generators::Points;
using mddual::generators::Rng;
using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// Agreement required of an exact answer, relative to PD (or to the scale when PD = 0).
constexpr double kExactRel = 1e-9;
/// An answer off by more than this (relative) is a failure ("wrong").
constexpr double kWrongRel = 1e-2;

struct Options {
  std::vector<std::string> sets = {"paper", "random", "hard"};
  int orientations = 40;
  std::vector<int> sizes = {10, 30, 100, 300, 1000, 3000, 5000};
  int pairs_per_size = 10;
  int placements = 10;
  int hard_queries = 200;
  int passes = 3;
  int brute_queries = 10;
  std::string label;
  std::string json;
};

/// One posed pair of a group.
struct PdQuery {
  Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  double independent = kNaN;  ///< an independent PD (paper: the placement's depth), or NaN
  double reference = kNaN;    ///< PD by our exact method
};

/// A set of queries on pairs of polytopes (one pair for the paper set, several otherwise).
struct Group {
  std::string set;
  std::string name;
  std::vector<std::unique_ptr<ConvexPolytope>> polytopes;
  std::vector<std::pair<int, int>> pair_of;  ///< per query: indices of A and B in polytopes
  std::vector<PdQuery> queries;
  double scale = 1.0;  ///< largest radius (for errors when PD = 0)
  int vertices_a = 0, vertices_b = 0;
};

// ---- Options --------------------------------------------------------------------------

[[noreturn]] void usage(const std::string& error) {
  std::cerr << "mddual_bench_pd: " << error << "\n"
            << "usage: mddual_bench_pd [--quick] [--sets paper,random,hard] [--orientations N] [--sizes 10,30,...]\n"
            << "       [--pairs-per-size N] [--placements N] [--hard-queries N] [--passes N] [--brute-queries N]\n"
            << "       [--label TEXT] [--json FILE]\n";
  std::exit(2);
}

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

Options parse(int argc, char** argv) {
  Options o;
  auto value = [&](int& i) -> std::string {
    if (i + 1 >= argc) usage(std::string(argv[i]) + " needs a value");
    return argv[++i];
  };
  auto number = [&](int& i) {
    const std::string v = value(i);
    try {
      return std::stoi(v);
    } catch (const std::exception&) {
      usage("bad number '" + v + "'");
    }
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      o.orientations = 4;
      o.sizes = {10, 100, 1000, 5000};
      o.pairs_per_size = 3;
      o.placements = 5;
      o.hard_queries = 20;
      o.brute_queries = 3;
    } else if (a == "--sets") {
      o.sets = splitList(value(i));
    } else if (a == "--orientations") {
      o.orientations = number(i);
    } else if (a == "--sizes") {
      o.sizes.clear();
      for (const std::string& s : splitList(value(i))) o.sizes.push_back(std::stoi(s));
    } else if (a == "--pairs-per-size") {
      o.pairs_per_size = number(i);
    } else if (a == "--placements") {
      o.placements = number(i);
    } else if (a == "--hard-queries") {
      o.hard_queries = number(i);
    } else if (a == "--passes") {
      o.passes = number(i);
    } else if (a == "--brute-queries") {
      o.brute_queries = number(i);
    } else if (a == "--label") {
      o.label = value(i);
    } else if (a == "--json") {
      o.json = value(i);
    } else {
      usage(a == "--help" || a == "-h" ? "help" : "unknown argument '" + a + "'");
    }
  }
  if (o.orientations < 1 || o.pairs_per_size < 1 || o.placements < 1 || o.passes < 1) usage("counts must be positive");
  return o;
}

// ---- Scenes ---------------------------------------------------------------------------

Eigen::Isometry3d pose(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}

double uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

int addPolytope(Group* g, const Points& points) {
  g->polytopes.push_back(std::make_unique<ConvexPolytope>(ConvexPolytope::fromPoints(points)));
  g->scale = std::max(g->scale, g->polytopes.back()->radius());
  return static_cast<int>(g->polytopes.size()) - 1;
}

double exactPd(const Group& g, size_t q) {
  const auto [ia, ib] = g.pair_of[q];
  const PdQuery& x = g.queries[q];
  return mddual::penetrationDepth(
             {g.polytopes[static_cast<size_t>(ia)].get(), x.X_WA, g.polytopes[static_cast<size_t>(ib)].get(), x.X_WB})
      .depth;
}

/// Paper set: the protocol's overlapping placements (signed distance < 0).
Group paperGroup(const mddual::bench::PairSpec& spec, int index, const Options& opt) {
  mddual::bench::Protocol protocol;
  protocol.orientations = opt.orientations;
  protocol.directions = 1;
  protocol.verify = false;
  const mddual::bench::PairScene scene = mddual::bench::buildScene(spec, protocol, index);
  Group g;
  g.set = "paper";
  g.name = spec.name();
  g.scale = 0.0;
  g.polytopes.push_back(std::make_unique<ConvexPolytope>(scene.a));
  g.polytopes.push_back(std::make_unique<ConvexPolytope>(scene.b));
  g.scale = std::max(scene.a.radius(), scene.b.radius());
  for (const mddual::bench::Query& q : scene.cold) {
    const double delta = scene.deltas[static_cast<size_t>(q.placement)];
    if (delta >= 0.0) continue;
    g.queries.push_back({q.X_WA, q.X_WB, -delta});
    g.pair_of.emplace_back(0, 1);
  }
  return g;
}

/// Random set: pairs of n-vertex hulls, random orientations and overlapping offsets.
Group randomGroup(int n, const Options& opt, Rng& rng) {
  Group g;
  g.set = "random";
  g.name = std::to_string(n) + " vertices";
  g.scale = 0.0;
  for (int p = 0; p < opt.pairs_per_size; ++p) {
    const Eigen::Vector3d axes_a =
        mddual::generators::drawVector(std::uniform_real_distribution<double>(1.0, 2.0), rng);
    const Eigen::Vector3d axes_b =
        mddual::generators::drawVector(std::uniform_real_distribution<double>(1.0, 2.0), rng);
    const int ia = addPolytope(&g, mddual::generators::blob(n, axes_a, rng));
    const int ib = addPolytope(&g, mddual::generators::blob(n, axes_b, rng));
    const double reach = axes_a.minCoeff() + axes_b.minCoeff();
    for (int k = 0; k < opt.placements;) {
      PdQuery q;
      q.X_WA = pose(mddual::generators::randomRotation(rng), Eigen::Vector3d::Zero());
      // B's offset length, its direction, then its rotation: the order GCC
      // evaluated them in one call (C++ leaves it unspecified), kept so the
      // seeded queries stay as they were.
      const double length = uniform(rng, 0.0, 0.9 * reach);
      const Eigen::Vector3d direction = mddual::generators::randomUnitVector(rng);
      const Eigen::Matrix3d R_WB = mddual::generators::randomRotation(rng);
      q.X_WB = pose(R_WB, direction * length);
      g.queries.push_back(q);
      g.pair_of.emplace_back(ia, ib);
      if (exactPd(g, g.queries.size() - 1) > 0.0) {
        ++k;
      } else {
        g.queries.pop_back();
        g.pair_of.pop_back();
      }
    }
  }
  g.vertices_a = g.vertices_b = n;
  return g;
}

/// Hard set: one group per kind of input EPA is reported to fail on.
std::vector<Group> hardGroups(const Options& opt, Rng& rng) {
  std::vector<Group> out;
  auto make = [&](const std::string& name, const Points& a, const Points& b, auto&& place) {
    Group g;
    g.set = "hard";
    g.name = name;
    g.scale = 0.0;
    const int ia = addPolytope(&g, a);
    const int ib = addPolytope(&g, b);
    for (int k = 0; k < opt.hard_queries; ++k) {
      g.queries.push_back(place());
      g.pair_of.emplace_back(ia, ib);
    }
    g.vertices_a = g.polytopes[0]->numVertices();
    g.vertices_b = g.polytopes[1]->numVertices();
    out.push_back(std::move(g));
  };
  using mddual::generators::box;
  using mddual::generators::randomRotation;
  using mddual::generators::randomUnitVector;
  const Points triangle = mddual::generators::triangle({-2.0, -1.5, 0.0}, {2.0, -1.5, 0.0}, {0.0, 2.0, 0.0});
  // The draws below are in the order GCC evaluated the call arguments they
  // were once written in, last argument first (C++ leaves the order
  // unspecified), so the seeded queries and shapes stay as they were.
  make("triangle through box", box({1.0, 0.8, 0.6}), triangle, [&] {
    // The triangle's plane through the box's interior, tilted at random.
    PdQuery q;
    const Eigen::Vector3d p = 0.4 * randomUnitVector(rng);
    const Eigen::Matrix3d R = randomRotation(rng);
    q.X_WB = pose(R, p);
    return q;
  });
  make("slab / slab 1:100", box({1.0, 1.0, 0.01}), box({1.0, 1.0, 0.01}), [&] {
    PdQuery q;
    q.X_WA = pose(randomRotation(rng), Eigen::Vector3d::Zero());
    const Eigen::Vector3d p = 0.3 * randomUnitVector(rng);
    const Eigen::Matrix3d R = randomRotation(rng);
    q.X_WB = pose(R, p);
    return q;
  });
  make("needle / box 1:100", box({0.8, 0.6, 0.7}), box({0.01, 0.01, 1.5}), [&] {
    PdQuery q;
    const Eigen::Vector3d p = 0.5 * randomUnitVector(rng);
    const Eigen::Matrix3d R = randomRotation(rng);
    q.X_WB = pose(R, p);
    return q;
  });
  const Points small_blob = mddual::generators::blob(40, {0.2, 0.15, 0.25}, rng);
  const Points large_blob = mddual::generators::blob(60, {2.0, 1.6, 1.8}, rng);
  make("deep: small blob in large", large_blob, small_blob, [&] {
    PdQuery q;
    q.X_WA = pose(randomRotation(rng), Eigen::Vector3d::Zero());
    const Eigen::Vector3d p = 0.2 * randomUnitVector(rng);
    const Eigen::Matrix3d R = randomRotation(rng);
    q.X_WB = pose(R, p);
    return q;
  });
  make("touching boxes (PD 0)", box({0.5, 0.5, 0.5}), box({0.5, 0.5, 0.5}), [&] {
    // Face, edge or corner contact at exact offsets, in a random common orientation.
    const Eigen::Matrix3d R = randomRotation(rng);
    const double p_z = std::uniform_int_distribution<int>(0, 1)(rng) * 1.0;
    const double p_y = std::uniform_int_distribution<int>(-2, 2)(rng) * 0.25;
    Eigen::Vector3d p(1.0, p_y, p_z);
    PdQuery q;
    q.X_WA = pose(R, Eigen::Vector3d::Zero());
    q.X_WB = pose(R, R * p);
    return q;
  });
  return out;
}

// ---- Measurement ----------------------------------------------------------------------

struct Answer {
  double depth = kNaN;
  bool collide = false;
  bool error = false;
  std::string message;
};

struct Run {
  std::string name;
  std::vector<double> ns;
  std::vector<Answer> answers;
  int measured = 0;  ///< queries run (the brute force runs on a prefix)
};

/// Times `call(q)` on the first `count` queries, fastest of `passes` passes.
template <class Call>
Run timeMethod(const std::string& name, size_t count, int passes, double overhead_ns, Call&& call) {
  Run run;
  run.name = name;
  run.ns.assign(count, kNaN);
  run.answers.resize(count);
  run.measured = static_cast<int>(count);
  for (int pass = 0; pass < passes; ++pass) {
    for (size_t q = 0; q < count; ++q) {
      try {
        const Clock::time_point t0 = Clock::now();
        const Answer a = call(q);
        const Clock::time_point t1 = Clock::now();
        const double ns = std::max(0.0, std::chrono::duration<double, std::nano>(t1 - t0).count() - overhead_ns);
        if (pass == 0) run.answers[q] = a;
        if (!(run.ns[q] <= ns)) run.ns[q] = ns;
      } catch (const std::exception& e) {
        if (pass == 0) {
          run.answers[q].error = true;
          run.answers[q].message = e.what();
        }
      }
    }
  }
  return run;
}

/// timeMethod() for code that may abort the process (FCL's libccd EPA
/// asserts on some touching pairs, and Debian builds FCL with assertions):
/// the passes run in a child process that streams one record per query
/// through a pipe. When the child dies, the query it was on is recorded as a
/// crash (an exception "process aborted by signal N") and a new child goes on
/// with the next query; crashed queries are skipped by later passes.
template <class Call>
Run timeIsolated(const std::string& name, size_t count, int passes, double overhead_ns, Call&& call) {
  struct Record {
    std::int32_t index;
    std::int32_t kind;  // 0: started, 1: answered, 2: threw
    double ns;
    double depth;
    std::int32_t collide;
    std::int32_t pass;
  };
  Run run;
  run.name = name;
  run.ns.assign(count, kNaN);
  run.answers.resize(count);
  run.measured = static_cast<int>(count);
  std::vector<char> crashed(count, 0);
  for (int pass = 0; pass < passes; ++pass) {
    size_t next = 0;
    while (next < count) {
      int fd[2];
      if (pipe(fd) != 0) throw std::runtime_error("pipe failed");
      std::cout.flush();
      const pid_t pid = fork();
      if (pid < 0) throw std::runtime_error("fork failed");
      if (pid == 0) {
        close(fd[0]);
        for (size_t q = next; q < count; ++q) {
          if (crashed[q] != 0) continue;
          Record r{static_cast<std::int32_t>(q), 0, 0.0, 0.0, 0, pass};
          if (write(fd[1], &r, sizeof r) != static_cast<ssize_t>(sizeof r)) _exit(3);
          try {
            const Clock::time_point t0 = Clock::now();
            const Answer a = call(q);
            const Clock::time_point t1 = Clock::now();
            r.kind = 1;
            r.ns = std::max(0.0, std::chrono::duration<double, std::nano>(t1 - t0).count() - overhead_ns);
            r.depth = a.depth;
            r.collide = a.collide ? 1 : 0;
          } catch (const std::exception&) {
            r.kind = 2;
          }
          if (write(fd[1], &r, sizeof r) != static_cast<ssize_t>(sizeof r)) _exit(3);
        }
        _exit(0);
      }
      close(fd[1]);
      Record r{};
      long started = -1;
      while (read(fd[0], &r, sizeof r) == static_cast<ssize_t>(sizeof r)) {
        const size_t q = static_cast<size_t>(r.index);
        if (r.kind == 0) {
          started = r.index;
          continue;
        }
        started = -1;
        if (r.kind == 2) {
          if (pass == 0) {
            run.answers[q].error = true;
            run.answers[q].message = "exception";
          }
          continue;
        }
        if (pass == 0) {
          run.answers[q].depth = r.depth;
          run.answers[q].collide = r.collide != 0;
        }
        if (!(run.ns[q] <= r.ns)) run.ns[q] = r.ns;
      }
      close(fd[0]);
      int status = 0;
      waitpid(pid, &status, 0);
      if (started < 0) break;  // the child finished the pass
      const size_t q = static_cast<size_t>(started);
      crashed[q] = 1;
      run.answers[q] = Answer();
      run.answers[q].error = true;
      run.answers[q].message =
          "process aborted by signal " + std::to_string(WIFSIGNALED(status) ? WTERMSIG(status) : 0);
      run.ns[q] = kNaN;
      next = q + 1;
    }
  }
  return run;
}

struct Summary {
  int queries = 0;
  double median_us = kNaN, p90_us = kNaN, mean_us = kNaN;
  double median_err = kNaN, max_err = kNaN;
  int inexact = 0;     ///< error above kExactRel
  int wrong = 0;       ///< error above kWrongRel
  int exceptions = 0;  ///< threw
  int missed = 0;      ///< reported no collision (or depth 0) where PD > 0
  int failures = 0;    ///< exceptions + missed + wrong
  std::vector<std::string> examples;
};

/// The error above which an answer counts as wrong: the method's own bound
/// for the approximations (1 + delta), kWrongRel for everything else.
double wrongThreshold(const std::string& method) {
  if (method == "approx_0.1") return 0.1;
  if (method == "approx_0.01") return 0.01;
  return kWrongRel;
}

Summary summarize(const Group& g, const Run& run) {
  Summary s;
  s.queries = run.measured;
  std::vector<double> us;
  std::vector<double> errs;
  double sum = 0.0;
  for (size_t q = 0; q < static_cast<size_t>(run.measured); ++q) {
    const Answer& a = run.answers[q];
    if (std::isfinite(run.ns[q])) {
      us.push_back(run.ns[q] / 1000.0);
      sum += run.ns[q] / 1000.0;
    }
    const double pd = g.queries[q].reference;
    std::ostringstream why;
    why.precision(17);
    if (a.error || !std::isfinite(a.depth)) {
      ++s.exceptions;
      why << "exception: " << a.message.substr(0, a.message.find('\n'));
    } else {
      const double err = pd > 0.0 ? std::abs(a.depth - pd) / pd : std::abs(a.depth) / g.scale;
      errs.push_back(err);
      if (err > kExactRel) ++s.inexact;
      if (pd > 0.0 && (!a.collide || a.depth <= 0.0)) {
        ++s.missed;
        why << "no penetration reported, PD " << pd;
      } else if (err > wrongThreshold(run.name) + kExactRel) {
        ++s.wrong;
        why << "depth " << a.depth << " vs PD " << pd;
      }
    }
    if (!why.str().empty() && s.examples.size() < 3) {
      const auto [ia, ib] = g.pair_of[q];
      s.examples.push_back(run.name + " " + g.name + ": " + why.str() + "; pair " +
                           mddual::toJsonLine({g.polytopes[static_cast<size_t>(ia)].get(), g.queries[q].X_WA,
                                               g.polytopes[static_cast<size_t>(ib)].get(), g.queries[q].X_WB}));
    }
  }
  s.failures = s.exceptions + s.missed + s.wrong;
  if (!us.empty()) {
    s.median_us = mddual::bench::percentile(us, 50);
    s.p90_us = mddual::bench::percentile(us, 90);
    s.mean_us = sum / static_cast<double>(us.size());
  }
  if (!errs.empty()) {
    s.median_err = mddual::bench::percentile(errs, 50);
    s.max_err = *std::max_element(errs.begin(), errs.end());
  }
  return s;
}

Json toJson(const Summary& s) {
  auto num = [](double x) { return std::isfinite(x) ? Json(x) : Json(nullptr); };
  Json j;
  j["queries"] = s.queries;
  j["median_us"] = num(s.median_us);
  j["p90_us"] = num(s.p90_us);
  j["mean_us"] = num(s.mean_us);
  j["median_err"] = num(s.median_err);
  j["max_err"] = num(s.max_err);
  j["inexact"] = s.inexact;
  j["wrong"] = s.wrong;
  j["missed"] = s.missed;
  j["exceptions"] = s.exceptions;
  j["failures"] = s.failures;
  Json ex = Json::array();
  for (const std::string& e : s.examples) ex.push_back(e.substr(0, e.find("; pair")));
  j["examples"] = ex;
  return j;
}

Json runGroup(Group& g, const Options& opt, double overhead_ns) {
  const Clock::time_point t0 = Clock::now();
  const size_t n = g.queries.size();
  auto polytope = [&](size_t q, bool b) {
    return g.polytopes[static_cast<size_t>(b ? g.pair_of[q].second : g.pair_of[q].first)].get();
  };
  // Ours. The exact run's answers are the references.
  auto ours = [&](PenetrationMethod method, double delta) {
    return [&, method, delta](size_t q) {
      const mddual::PenetrationResult r = mddual::penetrationDepth(
          {polytope(q, false), g.queries[q].X_WA, polytope(q, true), g.queries[q].X_WB, method, delta});
      Answer a;
      a.depth = r.depth;
      a.collide = r.status == mddual::PenetrationStatus::kPenetrating;
      return a;
    };
  };
  std::vector<Run> runs;
  runs.push_back(timeMethod("exact", n, opt.passes, overhead_ns, ours(PenetrationMethod::kExact, 0.0)));
  int mismatches = 0;
  int independent_checks = 0;
  std::vector<std::string> mismatch_examples;
  for (size_t q = 0; q < n; ++q) g.queries[q].reference = runs[0].answers[q].depth;
  runs.push_back(timeMethod("shallow", n, opt.passes, overhead_ns, ours(PenetrationMethod::kShallow, 0.0)));
  runs.push_back(timeMethod("approx_0.1", n, opt.passes, overhead_ns, ours(PenetrationMethod::kApprox, 0.1)));
  runs.push_back(timeMethod("approx_0.01", n, opt.passes, overhead_ns, ours(PenetrationMethod::kApprox, 0.01)));
  // Peers: one set of peer objects per pair of polytopes.
  for (const std::string& peer_name : mddual::bench::pdPeerNames()) {
    std::vector<std::unique_ptr<mddual::bench::PdPeer>> per_pair(g.polytopes.size() * g.polytopes.size());
    auto peer = [&](size_t q) -> mddual::bench::PdPeer& {
      const size_t key =
          static_cast<size_t>(g.pair_of[q].first) * g.polytopes.size() + static_cast<size_t>(g.pair_of[q].second);
      if (!per_pair[key]) {
        per_pair[key] = std::move(mddual::bench::makePdPeers(*polytope(q, false), *polytope(q, true), {peer_name})[0]);
      }
      return *per_pair[key];
    };
    for (size_t q = 0; q < n; ++q) peer(q);  // build outside the timed calls
    runs.push_back(timeIsolated(peer_name, n, opt.passes, overhead_ns, [&](size_t q) {
      const mddual::bench::PdAnswer a = peer(q).penetration(g.queries[q].X_WA, g.queries[q].X_WB);
      Answer x;
      x.depth = a.depth;
      x.collide = a.collide;
      return x;
    }));
  }
  // Brute force on a prefix (one pass: it takes milliseconds to seconds).
  const bool brute_ok =
      static_cast<long>(polytope(0, false)->numVertices()) * polytope(0, true)->numVertices() <= 250000;
  const size_t brute_n = brute_ok ? std::min(n, static_cast<size_t>(opt.brute_queries)) : 0;
  runs.push_back(timeMethod("brute", brute_n, 1, overhead_ns, ours(PenetrationMethod::kBruteForce, 0.0)));
  // Independent checks of the reference.
  for (size_t q = 0; q < n; ++q) {
    double other = g.queries[q].independent;
    if (q < brute_n && !runs.back().answers[q].error) other = runs.back().answers[q].depth;
    if (!std::isfinite(other)) continue;
    ++independent_checks;
    const double ref = g.queries[q].reference;
    if (std::abs(ref - other) > kExactRel * std::max(other, g.scale)) {
      ++mismatches;
      std::ostringstream m;
      m.precision(17);
      m << g.name << ": exact " << ref << " vs independent " << other;
      mismatch_examples.push_back(m.str());
      std::cerr << "MISMATCH " << m.str() << "\n";
    }
  }

  Json methods;
  std::cout << "\n"
            << g.set << " / " << g.name << ": " << n << " queries, |V| " << polytope(0, false)->numVertices() << " / "
            << polytope(0, true)->numVertices() << "; reference checked on " << independent_checks << " (" << mismatches
            << " mismatches)\n"
            << "  method            med_us   p90_us  med_err  max_err  fails (exc/missed/wrong)\n";
  for (const Run& run : runs) {
    const Summary s = summarize(g, run);
    for (const std::string& e : s.examples) std::cerr << "EXAMPLE " << e << "\n";
    std::cout << "  " << std::left << std::setw(16) << run.name << std::right << std::fixed << std::setprecision(2)
              << std::setw(9) << s.median_us << std::setw(9) << s.p90_us << std::scientific << std::setprecision(1)
              << std::setw(9) << s.median_err << std::setw(9) << s.max_err << std::setw(6) << s.failures << " ("
              << s.exceptions << "/" << s.missed << "/" << s.wrong << ")" << std::defaultfloat << "\n";
    methods[run.name] = toJson(s);
  }
  Json j;
  j["set"] = g.set;
  j["name"] = g.name;
  j["queries"] = n;
  j["a_vertices"] = polytope(0, false)->numVertices();
  j["b_vertices"] = polytope(0, true)->numVertices();
  j["a_faces"] = polytope(0, false)->numFaces();
  j["b_faces"] = polytope(0, true)->numFaces();
  j["scale"] = g.scale;
  j["reference_checks"] = independent_checks;
  j["reference_mismatches"] = mismatches;
  j["mismatch_examples"] = mismatch_examples;
  j["seconds"] = std::chrono::duration<double>(Clock::now() - t0).count();
  j["methods"] = methods;
  return j;
}

std::string cpuModel() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown";
}

std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

}  // namespace

int main(int argc, char** argv) {
  const Options opt = parse(argc, argv);
  const double overhead_ns = mddual::bench::timerOverheadNs();
  const Clock::time_point start = Clock::now();
  std::cout << "mddual_bench_pd: sets";
  for (const std::string& s : opt.sets) std::cout << " " << s;
  std::cout << "; fastest of " << opt.passes << " passes, timer overhead " << overhead_ns << " ns (subtracted), CPU "
            << cpuModel() << ", load " << loadAverage() << "\nerrors: |answer - PD| / PD (PD = 0: |answer| / scale)\n";
  Json out;
  out["benchmark"] = "mddual_bench_pd";
  out["label"] = opt.label;
  out["cpu"] = cpuModel();
  out["passes"] = opt.passes;
  out["timer_overhead_ns"] = overhead_ns;
  out["load_average_start"] = loadAverage();
  out["options"] = {{"orientations", opt.orientations},     {"sizes", opt.sizes},
                    {"pairs_per_size", opt.pairs_per_size}, {"placements", opt.placements},
                    {"hard_queries", opt.hard_queries},     {"brute_queries", opt.brute_queries}};
  out["defaults"] = {{"shallow_delta", mddual::defaults::kShallowPdDelta}};
  Json peers;
  for (const std::string& p : mddual::bench::pdPeerNames()) peers[p] = mddual::bench::pdPeerSettings(p);
  out["peers"] = peers;
  out["groups"] = Json::array();
  auto emit = [&](Group g) {
    out["groups"].push_back(runGroup(g, opt, overhead_ns));
    std::cout.flush();
    if (!opt.json.empty()) {  // rewritten after each group: a partial run leaves a valid file
      std::ofstream f(opt.json);
      f << out.dump(2) << "\n";
    }
  };
  Rng rng(20240505);
  for (const std::string& set : opt.sets) {
    if (set == "paper") {
      const auto pairs = mddual::bench::paperPairs();
      for (size_t i = 0; i < pairs.size(); ++i) emit(paperGroup(pairs[i], static_cast<int>(i), opt));
    } else if (set == "random") {
      for (int n : opt.sizes) emit(randomGroup(n, opt, rng));
    } else if (set == "hard") {
      for (Group& g : hardGroups(opt, rng)) emit(std::move(g));
    } else {
      usage("unknown set '" + set + "'");
    }
  }
  out["seconds"] = std::chrono::duration<double>(Clock::now() - start).count();
  out["load_average_end"] = loadAverage();
  if (!opt.json.empty()) {
    std::ofstream f(opt.json);
    f << out.dump(2) << "\n";
  }
  std::cout << "\nmddual_bench_pd: " << out["seconds"].get<double>() << " s\n";
  return 0;
}
