// mddual_gbench_core: the core benchmark's queries under Google Benchmark.
//
// One benchmark per (pair, method): <pair>/<method>, e.g. P4-P6/mdd_cold,
// P4-P6/bullet_gjk. Each runs over a fixed, precomputed query set (the
// --quick preset of mddual_bench_core: 4 orientations x 21 placements x 10
// directions = 840 queries per pair, seed 1), one query per iteration, cycling
// through the set; time per iteration is the mean time per query. The *_warm
// benchmarks walk the warm-start sequences with one WarmStart per benchmark,
// kept across sequences (one in ten queries jumps to a new placement, with a
// stale cache). Use mddual_bench_core for percentiles and accuracy.
//
//   mddual_gbench_core [--benchmark_filter=P4-P6/] [other Google Benchmark flags]
#include <benchmark/benchmark.h>

#include <memory>
#include <string>
#include <vector>

#include "mddual/query.h"
#include "peers.h"
#include "scene.h"

namespace {

using mddual::bench::PairScene;
using mddual::bench::Query;

constexpr double kCastLength = 25.0;

/// Cycles through `queries`, calling f on one per iteration.
template <class F>
void cycle(benchmark::State& state, const std::vector<Query>& queries, F&& f) {
  size_t i = 0;
  for (auto _ : state) {
    f(queries[i]);
    if (++i == queries.size()) i = 0;
  }
  state.SetItemsProcessed(state.iterations());
}

void registerPair(const PairScene* s, const std::vector<std::unique_ptr<mddual::bench::ToiPeer>>* peers) {
  const std::string pair = s->spec.name();
  auto ours = [s](bool mdd, bool warm) {
    return [s, mdd, warm](benchmark::State& state) {
      mddual::WarmStart cache;
      mddual::WarmStart* ws = warm ? &cache : nullptr;
      cycle(state, warm ? s->warm : s->cold, [&](const Query& q) {
        const mddual::DirectionalInput in{&s->a, q.X_WA, &s->b, q.X_WB, q.s_W};
        if (mdd) {
          benchmark::DoNotOptimize(mddual::mdd(in, ws));
        } else {
          benchmark::DoNotOptimize(mddual::toi(in, ws));
        }
      });
    };
  };
  benchmark::RegisterBenchmark((pair + "/mdd_cold").c_str(), ours(true, false));
  benchmark::RegisterBenchmark((pair + "/mdd_warm").c_str(), ours(true, true));
  benchmark::RegisterBenchmark((pair + "/toi_cold").c_str(), ours(false, false));
  benchmark::RegisterBenchmark((pair + "/toi_warm").c_str(), ours(false, true));
  for (const auto& peer : *peers) {
    mddual::bench::ToiPeer* p = peer.get();
    benchmark::RegisterBenchmark((pair + "/" + p->name()).c_str(), [s, p](benchmark::State& state) {
      cycle(state, s->cold, [&](const Query& q) {
        try {
          benchmark::DoNotOptimize(p->toi(q));
        } catch (const std::exception&) {
          state.counters["failures"] += 1;
        }
      });
    });
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  mddual::bench::Protocol protocol;
  protocol.orientations = 4;
  protocol.placements = 21;
  protocol.directions = 10;
  protocol.seed = 1;
  protocol.verify = false;
  const std::vector<mddual::bench::PairSpec> pairs = mddual::bench::paperPairs();
  std::vector<std::unique_ptr<PairScene>> scenes;
  std::vector<std::unique_ptr<std::vector<std::unique_ptr<mddual::bench::ToiPeer>>>> peers;
  for (size_t i = 0; i < pairs.size(); ++i) {
    scenes.push_back(std::make_unique<PairScene>(mddual::bench::buildScene(pairs[i], protocol, static_cast<int>(i))));
    peers.push_back(std::make_unique<std::vector<std::unique_ptr<mddual::bench::ToiPeer>>>(
        mddual::bench::makePeers(scenes.back()->a, scenes.back()->b, kCastLength)));
    registerPair(scenes.back().get(), peers.back().get());
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
