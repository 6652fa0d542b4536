// Batch evaluation throughput: model × candidates (64…65 536) × samples (256…16 384) × threads (1, 2),
// reported as candidate-samples per second (items_per_second). Threads: a oneTBB arena of that size.
// bench/cost_growth.py turns the JSON output into the cost-growth tables and plot of docs/performance.md.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/evaluation/bench_workload.hpp"
#include "engine/common/vector_math.hpp"
#include "engine/kernels/isa.hpp"
#include "models/registry.hpp"

namespace {

using namespace dampbench;

/// The bench workload of engine/evaluation/bench_workload.hpp with a 4 Hz sinusoid sampled at 1 024 Hz: `samples` / 256
/// whole cycles. The sampling rate is fixed, so the ODE models take the same RK4 sub-steps per sample at every
/// length and the cost can grow linearly.
constexpr double kFreqHz = 4.0, kSampleRateHz = 1024.0;
constexpr std::uint64_t kSeed = 1;

void BM_Evaluate(benchmark::State& state, const std::string& model_id) {
  const Model& model = find_model(model_id);
  const int candidates = static_cast<int>(state.range(0)), samples = static_cast<int>(state.range(1));
  tbb::task_arena arena(static_cast<int>(state.range(2)));
  const Signals data = bench_record(model, samples, kFreqHz, kSampleRateHz);
  const CandidateBatch batch = bench_candidates(model, candidates, kSeed);
  const BatchEvaluator evaluator(model, data);
  std::vector<double> out(candidates);
  for (auto _ : state) {
    arena.execute([&] { evaluator.evaluate(batch, Metric::of_abs, out); });
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(candidates) * samples);
}

/// F over an array in one `omp simd` loop, compiled per vector level (IsaClones).
template <double (*F)(double)>
struct ApplyVector {
  static void run(double* __restrict out, const double* __restrict in, std::size_t n) {
#pragma omp simd
    for (std::size_t i = 0; i < n; ++i) out[i] = F(in[i]);
  }
};

/// Throughput of one vector function over a 4 096-element array (libmvec or SLEEF lanes at the active vector
/// level, 1 thread): the per-call ceilings of docs/performance.md. Inputs span the range the kernels feed it.
template <double (*F)(double)>
void BM_VectorFunction(benchmark::State& state, double lo, double hi) {
  std::vector<double> in(4096), out(4096);
  for (std::size_t i = 0; i < in.size(); ++i) in[i] = lo + (hi - lo) * static_cast<double>(i) / in.size();
  for (auto _ : state) {
    IsaClones<ApplyVector<F>>::call(out.data(), in.data(), in.size());
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * 4096);
}

/// A dependent |z|^n chain over 64 lanes, z ← 0.5·|z|^n + 0.2 (one vector log and exp per lane and step,
/// each step waiting for the previous one, as RK4 stages do): the per-stage ceiling of the ODE kernels.
struct AbsPowChain {
  static constexpr int W = 64;
  static void run(double* z, const double* n) {
    for (int step = 0; step < 64; ++step) {
#pragma omp simd
      for (int l = 0; l < W; ++l) z[l] = 0.5 * dampbench::abs_pow(z[l], n[l]) + 0.2;
    }
  }
};

void BM_LogExpChain(benchmark::State& state) {
  constexpr int W = AbsPowChain::W;
  alignas(64) double z[W], n[W];
  for (int l = 0; l < W; ++l) z[l] = 0.3 + 0.001 * l, n[l] = 1.2 + 0.01 * l;
  for (auto _ : state) {
    IsaClones<AbsPowChain>::call(&z[0], &n[0]);
    benchmark::DoNotOptimize(z);
  }
  state.SetItemsProcessed(state.iterations() * 64 * W);
}

double vexp(double x) { return std::exp(x); }
double vlog(double x) { return std::log(x); }
double vtanh(double x) { return std::tanh(x); }
double vatan(double x) { return std::atan(x); }
double vsin(double x) { return std::sin(x); }

void register_all() {
  benchmark::RegisterBenchmark("vector/exp", BM_VectorFunction<vexp>, -5.0, 5.0);
  benchmark::RegisterBenchmark("vector/log", BM_VectorFunction<vlog>, 1e-3, 10.0);
  benchmark::RegisterBenchmark("vector/tanh", BM_VectorFunction<vtanh>, -5.0, 5.0);
  benchmark::RegisterBenchmark("vector/atan", BM_VectorFunction<vatan>, -50.0, 50.0);
  benchmark::RegisterBenchmark("vector/sin", BM_VectorFunction<vsin>, -4.0, 4.0);
  benchmark::RegisterBenchmark("vector/abs_pow_chain", BM_LogExpChain);
  for (const Model* m : all_models()) {
    auto* b = benchmark::RegisterBenchmark(("evaluate/" + std::string(m->id())).c_str(), BM_Evaluate, std::string(m->id()));
    for (int candidates : {64, 1024, 16384, 65536})
      for (int samples : {256, 2048, 16384})
        if (static_cast<long>(candidates) * samples <= 1L << 28)
          for (int threads : {1, 2}) b->Args({candidates, samples, threads});
    b->ArgNames({"candidates", "samples", "threads"})->UseRealTime()->Unit(benchmark::kMillisecond);
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (const char* isa = std::getenv("DAMPBENCH_ISA"); isa && *isa) dampbench::select_isa(isa, "DAMPBENCH_ISA");
  benchmark::AddCustomContext("vector_isa", dampbench::isa_summary());
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
