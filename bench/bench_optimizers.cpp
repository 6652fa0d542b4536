// The optimizers' own cost per candidate (ask + tell, 1 thread), on an objective that costs next to nothing:
// the shifted sphere Σ (x_j − 0.3)² over [0, 1]^dim (optimum 0 at x = 0.3). This is the serial work a fit adds on
// top of the model's evaluation (it is what keeps the `ga` fit on the fvd record below DE's rate).
// Population 50 and 100 generations as the fvd paper; dim 4 as fvd.gv_linear_elastic, 8 as a Spencer-sized model.
// items_per_second is candidates per second (1e9 / it = ns per candidate). Run: ./build/bench/bench_optimizers
#include <benchmark/benchmark.h>

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "engine/model/batch.hpp"
#include "optimizers/registry.hpp"

namespace {

using namespace dampbench;

constexpr int kPopulation = 50, kGenerations = 100;

void BM_AskTell(benchmark::State& state, const std::string& optimizer) {
  const int dim = static_cast<int>(state.range(0));
  const OptimizerFactory make = make_optimizer_factory({optimizer, kPopulation, kGenerations, {}});
  const Bounds bounds{std::vector<double>(dim, 0.0), std::vector<double>(dim, 1.0)};
  CandidateBatch batch(dim, kPopulation);
  std::vector<double> values(kPopulation);
  std::uint64_t run = 0;
  long long candidates = 0;
  double best = 0;
  for (auto _ : state) {
    const auto opt = make(bounds, ++run);
    while (!opt->finished()) {
      opt->ask(batch, 0);
      for (int i = 0; i < kPopulation; ++i) {
        double s = 0;
        for (int j = 0; j < dim; ++j) s += (batch.at(i, j) - 0.3) * (batch.at(i, j) - 0.3);
        values[i] = s;
      }
      opt->tell(values);
      candidates += kPopulation;
    }
    best += opt->best_value();
  }
  benchmark::DoNotOptimize(best);
  state.SetItemsProcessed(candidates);
}

/// The same with state.range(1) runs in lockstep, as a fit runs them (engine/identification): every run asks, then
/// every run is told, so a run's state leaves the caches between its generations when the runs' states together
/// are larger than them.
void BM_AskTellLockstep(benchmark::State& state, const std::string& optimizer) {
  const int dim = static_cast<int>(state.range(0)), runs = static_cast<int>(state.range(1));
  const OptimizerFactory make = make_optimizer_factory({optimizer, kPopulation, kGenerations, {}});
  const Bounds bounds{std::vector<double>(dim, 0.0), std::vector<double>(dim, 1.0)};
  CandidateBatch batch(dim, kPopulation * runs);
  std::vector<double> values(static_cast<std::size_t>(kPopulation) * runs);
  std::uint64_t run = 0;
  long long candidates = 0;
  double best = 0;
  for (auto _ : state) {
    std::vector<std::unique_ptr<Optimizer>> opts;
    for (int r = 0; r < runs; ++r) opts.push_back(make(bounds, ++run));
    while (!opts[0]->finished()) {
      for (int r = 0; r < runs; ++r) opts[r]->ask(batch, r * kPopulation);
      for (int i = 0; i < kPopulation * runs; ++i) {
        double s = 0;
        for (int j = 0; j < dim; ++j) s += (batch.at(i, j) - 0.3) * (batch.at(i, j) - 0.3);
        values[i] = s;
      }
      for (int r = 0; r < runs; ++r)
        opts[r]->tell(std::span(values).subspan(static_cast<std::size_t>(r) * kPopulation, kPopulation));
      candidates += static_cast<long long>(kPopulation) * runs;
    }
    for (const auto& o : opts) best += o->best_value();
  }
  benchmark::DoNotOptimize(best);
  state.SetItemsProcessed(candidates);
}

}  // namespace

BENCHMARK_CAPTURE(BM_AskTellLockstep, ga, std::string("ga"))->Args({4, 50})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AskTellLockstep, de, std::string("de"))->Args({4, 50})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AskTell, ga, std::string("ga"))->Arg(4)->Arg(8)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AskTell, aga, std::string("aga"))->Arg(4)->Arg(8)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AskTell, de, std::string("de"))->Arg(4)->Arg(8)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AskTell, pso, std::string("pso"))->Arg(4)->Arg(8)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
