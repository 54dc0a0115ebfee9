// mddual_bench_core: speed and accuracy of mddual::mdd() / mddual::toi()
// against the brute force and against Bullet's and FCL's convex casts, on the
// MDD-DUAL paper's protocol (docs/algorithms.md section 5; scene.h, measure.h).
//
//   mddual_bench_core [--quick] [--pairs P1-P2,P3-P3 | --pair P1-P2]
//                     [--orientations N] [--placements N] [--directions N]
//                     [--seed S] [--peers bullet_gjk,... | --peers none]
//                     [--cast-length L] [--no-verify] [--passes N]
//                     [--examples N] [--label TEXT] [--json FILE]
//
// Defaults are the paper's counts (40 orientations x 21 placements x 40
// directions = 33,600 queries per pair); --quick is 4 x 21 x 10. --passes
// (default 3): each query's time is its fastest of that many passes over the
// whole query set (measure.h). --label: free text stored in the JSON (the run
// script puts the git revision there).
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "measure.h"
#include "peers.h"
#include "scene.h"

namespace {

using mddual::bench::MethodRun;
using mddual::bench::PairScene;
using mddual::bench::PairSpec;
using mddual::bench::Summary;
using Json = nlohmann::ordered_json;

struct Options {
  mddual::bench::Protocol protocol;
  std::vector<std::string> pairs;  ///< empty: all ten
  std::vector<std::string> peers;  ///< empty: all
  bool no_peers = false;
  double cast_length = 25.0;
  int examples = 3;
  int passes = 3;
  std::string json;
  std::string label;
};

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

[[noreturn]] void usage(const std::string& error) {
  std::cerr << "mddual_bench_core: " << error << "\n"
            << "usage: mddual_bench_core [--quick] [--pairs P1-P2,P1-P3,... | --pair P1-P2] [--orientations N]\n"
            << "       [--placements N] [--directions N] [--seed S] [--peers LIST|none] [--cast-length L]\n"
            << "       [--no-verify] [--passes N] [--examples N] [--label TEXT] [--json FILE]\n";
  std::exit(2);
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
      return std::stol(v);
    } catch (const std::exception&) {
      usage("bad number '" + v + "'");
    }
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      o.protocol.orientations = 4;
      o.protocol.placements = 21;
      o.protocol.directions = 10;
    } else if (a == "--pairs" || a == "--pair") {
      for (const std::string& p : splitList(value(i))) o.pairs.push_back(p);
    } else if (a == "--orientations") {
      o.protocol.orientations = static_cast<int>(number(i));
    } else if (a == "--placements") {
      o.protocol.placements = static_cast<int>(number(i));
    } else if (a == "--directions") {
      o.protocol.directions = static_cast<int>(number(i));
    } else if (a == "--seed") {
      o.protocol.seed = static_cast<std::uint64_t>(number(i));
    } else if (a == "--peers") {
      const std::string v = value(i);
      o.no_peers = v == "none";
      if (!o.no_peers) o.peers = splitList(v);
    } else if (a == "--cast-length") {
      o.cast_length = std::stod(value(i));
    } else if (a == "--no-verify") {
      o.protocol.verify = false;
    } else if (a == "--passes") {
      o.passes = static_cast<int>(number(i));
    } else if (a == "--label") {
      o.label = value(i);
    } else if (a == "--examples") {
      o.examples = static_cast<int>(number(i));
    } else if (a == "--json") {
      o.json = value(i);
    } else if (a == "--help" || a == "-h") {
      usage("help");
    } else {
      usage("unknown argument '" + a + "'");
    }
  }
  if (o.protocol.orientations < 1 || o.protocol.placements < 1 || o.protocol.directions < 1 || o.passes < 1) {
    usage("counts must be positive");
  }
  return o;
}

std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

std::string cpuModel() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown";
}

Json toJson(const Summary& s, bool ours) {
  Json j;
  j["queries"] = s.queries;
  j["median_us"] = s.median_us;
  j["p90_us"] = s.p90_us;
  j["p99_us"] = s.p99_us;
  j["mean_us"] = s.mean_us;
  j["max_us"] = s.max_us;
  j["separated_queries"] = s.separated_queries;
  j["separated_median_us"] = s.separated_median_us;
  j["separated_p90_us"] = s.separated_p90_us;
  j["in_contact_median_us"] = s.in_contact_median_us;
  j["in_contact_p90_us"] = s.in_contact_p90_us;
  j["compared"] = s.compared;
  j["max_err"] = s.max_err;
  j["median_err"] = s.median_err;
  j["mean_err"] = s.mean_err;
  j["inexact"] = s.inexact;
  j["large_err"] = s.large_err;
  j["failures"] = s.failures;
  j["exceptions"] = s.exceptions;
  j["nans"] = s.nans;
  j["false_never"] = s.false_never;
  j["false_hit"] = s.false_hit;
  j["touch_never"] = s.touch_never;
  j["ambiguous_accepted"] = s.ambiguous_accepted;
  if (ours) {
    j["mismatches"] = s.mismatches;
    j["faces_visited_pct"] = s.faces_visited_pct;
    j["ee_faces_visited_pct"] = s.ee_faces_visited_pct;
    j["faces_visited_mean"] = s.faces_visited_mean;
    j["ee_faces_visited_mean"] = s.ee_faces_visited_mean;
    j["centre_iterations_mean"] = s.centre_iterations_mean;
    j["steps_mean"] = s.steps_mean;
    j["rays_mean"] = s.rays_mean;
    j["support_vertices_mean"] = s.support_vertices_mean;
  }
  if (s.overlap_queries > 0) {
    j["overlap_start"] = {{"queries", s.overlap_queries},
                          {"zero", s.overlap_zero},
                          {"positive", s.overlap_positive},
                          {"never", s.overlap_never}};
  }
  // Headlines only: the full queries (all vertices) go to stderr.
  Json examples = Json::array();
  for (const std::string& e : s.examples) examples.push_back(e.substr(0, e.find('\n')));
  j["examples"] = examples;
  return j;
}

void printRow(const std::string& name, const Summary& s, bool ours) {
  std::cout << "  " << std::left << std::setw(18) << name << std::right << std::fixed << std::setprecision(2)
            << std::setw(8) << s.median_us << std::setw(8) << s.p90_us << std::setw(8) << s.separated_median_us
            << std::scientific << std::setprecision(1) << std::setw(9) << s.max_err << std::setw(9) << s.median_err
            << std::setw(7) << s.failures;
  if (ours) {
    std::cout << std::setw(6) << s.mismatches << std::fixed << std::setprecision(1) << std::setw(7)
              << s.faces_visited_pct << std::setw(6) << s.ee_faces_visited_pct;
  } else {
    std::cout << std::setw(6) << "-" << std::setw(13) << "-";
  }
  if (s.overlap_queries > 0) {
    std::cout << "  overlap start: " << s.overlap_zero << " zero, " << s.overlap_positive << " >0, " << s.overlap_never
              << " never; touch start never: " << s.touch_never;
  }
  std::cout << std::defaultfloat << "\n";
}

double mean(const std::vector<mddual::bench::OrientationInfo>& os, int mddual::bench::OrientationInfo::*field) {
  double sum = 0.0;
  for (const auto& o : os) sum += o.*field;
  return os.empty() ? 0.0 : sum / static_cast<double>(os.size());
}

Json runPair(const PairSpec& spec, int pair_index, const Options& opt, double overhead_ns) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point t0 = Clock::now();
  const PairScene scene = mddual::bench::buildScene(spec, opt.protocol, pair_index);
  const double scene_s = std::chrono::duration<double>(Clock::now() - t0).count();
  const auto& checks = scene.checks;
  std::cout << "\n"
            << spec.name() << ": |V| " << scene.a.numVertices() << " / " << scene.b.numVertices() << ", faces of M "
            << std::fixed << std::setprecision(0) << mean(scene.orientations, &mddual::bench::OrientationInfo::faces)
            << " (EE " << mean(scene.orientations, &mddual::bench::OrientationInfo::ee_faces) << "), "
            << scene.cold.size() << " queries; scene " << std::setprecision(1) << scene_s << " s; checks: placements "
            << checks.placements_checked - checks.placements_failed << "/" << checks.placements_checked
            << " ok, references " << checks.references_checked - checks.references_failed << "/"
            << checks.references_checked << " ok, min centre depth " << std::setprecision(2) << checks.centre_depth_min
            << std::defaultfloat << "\n";
  for (const std::string& m : checks.messages) std::cerr << "CHECK: " << m << "\n";
  std::cout << "  method             med_us  p90_us sep_med  max_err  med_err  fails  mism faces%   EE%\n";

  Json methods;
  auto record = [&](const MethodRun& run) {
    const Summary s = mddual::bench::summarize(scene, run, opt.examples);
    printRow(run.name, s, run.ours);
    for (const std::string& e : s.examples) std::cerr << "EXAMPLE " << spec.name() << ": " << e << "\n";
    methods[run.name] = toJson(s, run.ours);
  };
  for (const bool warm : {false, true}) {
    for (const bool is_mdd : {true, false})
      record(mddual::bench::runOurs(scene, is_mdd, warm, opt.passes, overhead_ns));
  }
  if (!opt.no_peers) {
    for (auto& peer : mddual::bench::makePeers(scene.a, scene.b, opt.cast_length, opt.peers)) {
      record(mddual::bench::runPeer(scene, *peer, opt.passes, overhead_ns));
    }
  }
  const double total_s = std::chrono::duration<double>(Clock::now() - t0).count();

  Json j;
  j["pair"] = spec.name();
  j["a"] = spec.a;
  j["b"] = spec.b;
  j["a_vertices"] = scene.a.numVertices();
  j["a_faces"] = scene.a.numFaces();
  j["b_vertices"] = scene.b.numVertices();
  j["b_faces"] = scene.b.numFaces();
  j["m_faces_mean"] = mean(scene.orientations, &mddual::bench::OrientationInfo::faces);
  j["m_ee_faces_mean"] = mean(scene.orientations, &mddual::bench::OrientationInfo::ee_faces);
  j["m_fv_faces_mean"] = mean(scene.orientations, &mddual::bench::OrientationInfo::fv_faces);
  j["m_vf_faces_mean"] = mean(scene.orientations, &mddual::bench::OrientationInfo::vf_faces);
  j["checks"] = {{"placements_checked", checks.placements_checked}, {"placements_failed", checks.placements_failed},
                 {"references_checked", checks.references_checked}, {"references_failed", checks.references_failed},
                 {"centre_depth_min", checks.centre_depth_min},     {"messages", checks.messages}};
  j["scene_seconds"] = scene_s;
  j["total_seconds"] = total_s;
  j["load_average_after"] = loadAverage();
  j["methods"] = methods;
  return j;
}

}  // namespace

int main(int argc, char** argv) {
  const Options opt = parse(argc, argv);
  const std::vector<PairSpec> all = mddual::bench::paperPairs();
  std::vector<int> selected;
  if (opt.pairs.empty()) {
    for (size_t i = 0; i < all.size(); ++i) selected.push_back(static_cast<int>(i));
  }
  for (const std::string& name : opt.pairs) {
    size_t i = 0;
    while (i < all.size() && all[i].name() != name) ++i;
    if (i == all.size()) usage("unknown pair '" + name + "' (the paper's pairs are P1-P2, P1-P3, P4-P5, P4-P6, Pi-Pi)");
    selected.push_back(static_cast<int>(i));
  }
  for (const std::string& p : opt.peers) {
    const auto names = mddual::bench::peerNames();
    if (std::find(names.begin(), names.end(), p) == names.end()) usage("unknown peer '" + p + "'");
  }

  const double overhead_ns = mddual::bench::timerOverheadNs();
  const auto& pr = opt.protocol;
  std::cout << "mddual_bench_core: " << pr.orientations << " orientations x " << pr.placements << " placements x "
            << pr.directions << " directions per pair, seed " << pr.seed << ", timer overhead " << overhead_ns
            << " ns (subtracted), fastest of " << opt.passes << " passes, CPU " << cpuModel() << ", load "
            << loadAverage() << "\n"
            << "times in us per query; sep_med = median over queries starting separated; errors are |answer - "
               "exact| / 10;\nfaces% = faces of M evaluated / faces of M (mean over queries whose line meets M)\n";

  Json out;
  out["benchmark"] = "mddual_bench_core";
  out["label"] = opt.label;
  out["protocol"] = {{"orientations", pr.orientations},
                     {"placements", pr.placements},
                     {"directions", pr.directions},
                     {"queries_per_pair", pr.orientations * pr.placements * pr.directions},
                     {"min_delta", pr.min_delta},
                     {"max_delta", pr.max_delta},
                     {"seed", pr.seed},
                     {"warm_step", pr.warm_step},
                     {"warm_turn_deg", pr.warm_turn_deg},
                     {"verify", pr.verify}};
  out["cast_length"] = opt.cast_length;
  out["scene_scale"] = mddual::bench::kSceneScale;
  out["exact_rel_tol"] = mddual::bench::kExactRelTol;
  out["timer_overhead_ns"] = overhead_ns;
  out["cpu"] = cpuModel();
  out["passes"] = opt.passes;
  out["load_average_start"] = loadAverage();
  out["targets"] = {{"paper_us", 350.0}, {"cold_us", 3.5}, {"warm_us", 1.0}};
  Json peers;
  if (!opt.no_peers) {
    for (const std::string& p : mddual::bench::peerNames()) {
      if (opt.peers.empty() || std::find(opt.peers.begin(), opt.peers.end(), p) != opt.peers.end()) {
        peers[p] = mddual::bench::peerSettings(p);
      }
    }
  }
  out["peers"] = peers;
  out["pairs"] = Json::array();
  for (int i : selected) {
    out["pairs"].push_back(runPair(all[static_cast<size_t>(i)], i, opt, overhead_ns));
    std::cout.flush();
    if (!opt.json.empty()) {  // rewritten after each pair: a partial run still leaves a valid file
      std::ofstream f(opt.json);
      if (!f) {
        std::cerr << "mddual_bench_core: cannot write " << opt.json << "\n";
        return 1;
      }
      f << out.dump(2) << "\n";
    }
  }
  return 0;
}
