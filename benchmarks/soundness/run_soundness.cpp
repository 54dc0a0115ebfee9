// The soundness suite's runner: every case family (cases.h) with every
// checker, against the ground truth; writes one Markdown table row per
// (family, checker). scripts/run-soundness.sh runs it and files the table.
//
//   mddual_soundness [--edges N] [--seed S] [--out FILE] [--family NAME]...
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cases.h"
#include "fcl_bvh.h"

namespace {

using namespace mddual::soundness;

struct Tally {
  int edges = 0;
  int colliding = 0;
  int missed = 0;
  int false_alarms = 0;
  std::vector<double> seconds;
};

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  int edges = 200;
  std::uint64_t seed = 1;
  std::string out_path;
  std::vector<std::string> families;
  CLI::App app("The soundness suite: every case family with every checker against its ground truth");
  app.add_option("--edges", edges, "edges per family (default 200)")->check(CLI::Range(1, 1000000));
  app.add_option("--seed", seed, "the families' seed (default 1)");
  app.add_option("--out", out_path, "also write the Markdown table to FILE")->option_text("FILE");
  app.add_option("--family", families, "only these families (repeatable; default: all)")
      ->check(CLI::IsMember(familyNames()))
      ->option_text("NAME");
  CLI11_PARSE(app, argc, argv);
  if (families.empty()) families = familyNames();

  std::ostringstream table;
  table << "| case | checker | edges | colliding edges | missed | false alarms | median time per edge (us) |\n"
        << "|---|---|---|---|---|---|---|\n";
  for (const std::string& family : families) {
    const std::uint64_t warnings_before = fclBvhWarnings();
    const std::vector<Case> cases = makeFamily(family, seed, edges);
    std::map<std::string, Tally> tallies;
    for (const Case& c : cases) {
      const Scene scene = buildScene(c);
      std::vector<Truth> truths;
      for (int e = 0; e < c.numEdges(); ++e) truths.push_back(groundTruth(c, scene, e));
      for (const std::string& checker : checkerNames(family)) {
        const CheckerRun run = runChecker(*makeChecker(checker, scene), c, scene);
        Tally& t = tallies[checker];
        for (std::size_t e = 0; e < truths.size(); ++e) {
          ++t.edges;
          t.colliding += truths[e].collides;
          t.missed += truths[e].collides && run.valid[e];
          t.false_alarms += !truths[e].collides && !run.valid[e];
          t.seconds.push_back(run.seconds[e]);
        }
      }
    }
    for (const std::string& checker : checkerNames(family)) {
      const Tally& t = tallies[checker];
      char time[32];
      std::snprintf(time, sizeof time, "%.3g", median(t.seconds) * 1e6);
      table << "| " << family << " | " << checker << " | " << t.edges << " | " << t.colliding << " | " << t.missed
            << " | " << t.false_alarms << " | " << time << " |\n";
    }
    std::cerr << "mddual_soundness: " << family << " done";
    // What FCL printed in the casts of fcl-continuous-obb and -rss (fcl_bvh.h).
    if (fclBvhWarnings() > warnings_before)
      std::cerr << " (FCL warned " << fclBvhWarnings() - warnings_before << " times)";
    std::cerr << "\n";
  }
  std::cout << table.str();
  if (!out_path.empty()) {
    std::ofstream out(out_path);
    out << table.str();
    if (!out) {
      std::cerr << "mddual_soundness: cannot write " << out_path << "\n";
      return 1;
    }
  }
  return 0;
}
