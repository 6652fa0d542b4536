// Batch evaluation throughput: model × candidates × samples, reported as candidate-samples per second
// (items_per_second). Threads: oneTBB's default (all cores); pin with --benchmark_filter and taskset.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "engine/batch_evaluator.hpp"
#include "engine/bounds.hpp"
#include "engine/random.hpp"
#include "models/registry.hpp"

namespace {

using namespace dampbench;

Signals sine_record(int samples) {
  Dataset d;
  d.name = "bench";
  const double X = 0.02, w = 2 * std::numbers::pi * 2.0;
  for (int k = 0; k < samples; ++k) {
    const double t = 3.0 * k / samples / 2.0;  // three cycles at 2 Hz
    d.t_s.push_back(t);
    d.x_m.push_back(X * std::sin(w * t));
    d.v_m_s.push_back(X * w * std::cos(w * t));
    d.a_m_s2.push_back(-X * w * w * std::sin(w * t));
    d.F_N.push_back(5e5 * std::cos(w * t) + 1e5 * std::sin(w * t));
  }
  return prepare_signals(d);
}

void BM_Evaluate(benchmark::State& state, const std::string& model_id) {
  const Model& model = find_model(model_id);
  const int candidates = static_cast<int>(state.range(0)), samples = static_cast<int>(state.range(1));
  const Signals data = sine_record(samples);
  const Bounds b = default_bounds(model);
  CandidateBatch batch(model.dim(), candidates);
  RandomStream rng(hash_key({1}));
  for (int i = 0; i < candidates; ++i)
    for (int j = 0; j < model.dim(); ++j) batch.at(i, j) = rng.uniform(b.lower[j], b.upper[j]);
  const BatchEvaluator evaluator(model, data);
  std::vector<double> out(candidates);
  for (auto _ : state) {
    evaluator.evaluate(batch, Metric::of_abs, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(candidates) * samples);
}

void register_all() {
  for (const Model* m : all_models()) {
    auto* b = benchmark::RegisterBenchmark(("evaluate/" + std::string(m->id())).c_str(), BM_Evaluate, std::string(m->id()));
    for (int candidates : {64, 1024, 16384, 65536})
      for (int samples : {256, 2048, 16384})
        if (static_cast<long>(candidates) * samples <= 1L << 28) b->Args({candidates, samples});
    b->ArgNames({"candidates", "samples"})->UseRealTime()->Unit(benchmark::kMillisecond);
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
