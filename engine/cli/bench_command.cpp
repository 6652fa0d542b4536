// The `dampbench bench` workload (docs/performance.md):
//   record     engine/evaluation/bench_workload.hpp at 1 Hz, 2 cycles of 1024 samples (2049 samples)
//   candidates 4096 from bench_candidates (the central half of the model's bench box); masked_share is the
//              share of them that blow up (+inf), 0 for every model by the choice of the bench boxes
//   metric     of_abs through BatchEvaluator (the same path as identification), in float64 lanes or, with
//              `--lanes float32`, in the single-precision lanes of `--precision mixed` (models without them: float64)
//   1 thread / 2 threads   tbb::task_arena of that size, repeated until min_time_s
//   scalar     Model::evaluate_scalar (the same law, one candidate at a time, no lanes), 1 thread, 256 candidates
//   limit      a vector-exp probe: exp over a 4096-element array (libmvec lanes), 1 thread, elements/s
// Every rate is the best of `trials` measurements, taken in turns (1 thread, 2 threads, scalar, then again),
// so that a burst of load on the shared machine does not land in one column only.
// Ratios: scalar_ratio = 1-thread lanes / scalar; limit_ratio = 1-thread candidate-samples/s ÷ exp/s
// (a model with one exp per candidate-sample and nothing else would reach 1).
#include "engine/cli/bench_command.hpp"
#include "engine/cli/bench_rate.hpp"
#include "engine/cli/bench_real_records.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <thread>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/task_arena.h>

#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/evaluation/bench_workload.hpp"
#include "engine/evaluation/lane_blocks.hpp"
#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"
#include "engine/common/table.hpp"
#include "engine/common/vector_math.hpp"
#include "engine/kernels/isa.hpp"
#include "models/registry.hpp"

namespace dampbench::cli {
namespace {

constexpr int kCandidates = 4096, kScalarCandidates = 256, kSamplesPerCycle = 1024;
constexpr std::uint64_t kBenchSeed = 2024;

/// The vector-exp probe: elements of exp per second on one thread, the best of `trials` measurements (a
/// single one varied by ±15 % between runs on the shared machine, and every limit ratio divides by it).
/// exp over an array in one `omp simd` loop (libmvec's variant of the active vector level).
struct VectorExp {
  static void run(double* __restrict out, const double* __restrict in, std::size_t n) {
#pragma omp simd
    for (std::size_t i = 0; i < n; ++i) out[i] = std::exp(in[i]);
  }
};

double exp_rate(double min_time_s, int trials) {
  std::vector<double> in(4096), out(4096);
  for (std::size_t i = 0; i < in.size(); ++i) in[i] = -5.0 + 10.0 * static_cast<double>(i) / in.size();
  double best = 0;
  for (int trial = 0; trial < trials; ++trial)
    best = std::max(best, rate(static_cast<double>(in.size()), min_time_s, [&] {
      IsaClones<VectorExp>::call(out.data(), in.data(), in.size());
      asm volatile("" : : "r"(out.data()) : "memory");
    }));
  return best;
}

std::vector<std::string> supported_isa_names() {
  std::vector<std::string> names;
  for (Isa i : supported_isas()) names.emplace_back(isa_name(i));
  return names;
}

struct ModelRates {
  double one = 0, two = 0, scalar = 0, masked_share = 0;
};

ModelRates measure(const Model& model, double min_time_s, int trials, Precision precision) {
  const Signals data = bench_record(model, 2 * kSamplesPerCycle + 1, 1.0, kSamplesPerCycle);
  const CandidateBatch batch = bench_candidates(model, kCandidates, kBenchSeed);
  const CandidateBatch few = bench_candidates(model, kScalarCandidates, kBenchSeed);
  const BatchEvaluator evaluator(model, data, 1, precision);
  std::vector<double> out(kCandidates);
  std::vector<MetricSums> sums(kScalarCandidates);
  const double n = static_cast<double>(data.size());
  tbb::task_arena one_thread(1), two_threads(2);
  auto lanes_rate = [&](tbb::task_arena& arena) {
    return arena.execute(
        [&] { return rate(kCandidates * n, min_time_s, [&] { evaluator.evaluate(batch, Metric::of_abs, out); }); });
  };
  ModelRates r;
  for (int trial = 0; trial < trials; ++trial) {
    r.one = std::max(r.one, lanes_rate(one_thread));
    r.two = std::max(r.two, lanes_rate(two_threads));
    r.scalar = std::max(r.scalar, rate(kScalarCandidates * n, min_time_s, [&] {
      model.evaluate_scalar(few, 0, kScalarCandidates, data, sum_set_of(Metric::of_abs), sums.data());
    }));
  }
  r.masked_share = static_cast<double>(std::count_if(out.begin(), out.end(), [](double m) { return !std::isfinite(m); })) /
                   kCandidates;
  return r;
}

}  // namespace

void add_bench_options(CLI::App* cmd, BenchOptions& o) {
  cmd->add_option("--format", o.format, "md (default) or json");
  cmd->add_option("--models", o.models, "comma-separated model ids (default: every model)");
  cmd->add_option("--min-time", o.min_time_s, "seconds per measurement (default 0.3)")->check(CLI::PositiveNumber);
  cmd->add_option("--trials", o.trials, "measurements per rate, best kept (default 3)")->check(CLI::Range(1, 100));
  cmd->add_option("--lanes", o.lanes,
                  "float64 (default) or float32: the single-precision lanes the global search of --precision mixed uses "
                  "(models without them run float64; the table says which)");
  cmd->add_option("--workload", o.workload,
                  "sine (default): every model on a synthetic record; real-records: the hysteretic MR models on two "
                  "measured UTFSM records, candidates from the whole fit box (docs/performance.md)");
  cmd->add_option("--data-dir", o.data_dir,
                  "real-records: folder of the UTFSM records (default: $DAMPBENCH_SHARED_DATA_DIR/utfsm-mr-damper)");
}

int bench_command(const BenchOptions& o) {
  if (o.format != "md" && o.format != "json") throw InputError(fmt::format("--format: expected md or json, got '{}'", o.format));
  if (o.lanes != "float64" && o.lanes != "float32")
    throw InputError(fmt::format("--lanes: expected float64 or float32, got '{}'", o.lanes));
  if (o.workload == "real-records") return bench_real_records(o);
  if (o.workload != "sine") throw InputError(fmt::format("--workload: expected sine or real-records, got '{}'", o.workload));
  const Precision precision = o.lanes == "float32" ? Precision::float32 : Precision::float64;
  std::vector<const Model*> models;
  if (o.models.empty()) models.assign(all_models().begin(), all_models().end());
  else for (const auto& id : split_list(o.models, "--models")) models.push_back(&find_model(id));

  const double exp_per_s = exp_rate(o.min_time_s, o.trials);
  nlohmann::ordered_json j;
  Table t{"bench", "Candidate-samples per second (dampbench bench workload, docs/performance.md)",
          {"model", "lanes", "1 thread", "2 threads", "2t/1t", "scalar loop", "lanes/scalar", "limit ratio", "masked"}, {}};
  for (const Model* m : models) {
    const ModelRates r = measure(*m, o.min_time_s, o.trials, precision);
    const char* lanes = precision == Precision::float32 && m->has_float32_lanes() ? "float32" : "float64";
    j["models"][std::string(m->id())] = {{"lanes", lanes},
                                         {"cand_samples_per_s_1t", r.one},
                                         {"cand_samples_per_s_2t", r.two},
                                         {"scalar_ratio", r.one / r.scalar},
                                         {"limit_ratio", r.one / exp_per_s},
                                         {"cand_samples_per_s_scalar", r.scalar},
                                         {"masked_share", r.masked_share}};
    t.rows.push_back({std::string(m->id()), lanes, fmt::format("{:.3g}", r.one), fmt::format("{:.3g}", r.two),
                      fmt::format("{:.2f}", r.two / r.one), fmt::format("{:.3g}", r.scalar),
                      fmt::format("{:.2f}", r.one / r.scalar), fmt::format("{:.3f}", r.one / exp_per_s),
                      fmt::format("{:.0f} %", 100 * r.masked_share)});
    if (o.format == "md") std::cerr << fmt::format("  {} done\n", m->id());
  }
  j["machine"] = {{"hardware_threads", std::thread::hardware_concurrency()},
                  {"vector_isa", std::string(isa_name(active_isa()))},
                  {"vector_isas_supported", supported_isa_names()},
                  {"lanes_per_block", kLanes},
                  {"wider_blocks_lanes", {kWideLanes, kWidestLanes}},
                  {"block_times", block_times()},
                  {"exp_per_s_1t", exp_per_s},
                  {"build", DAMPBENCH_BUILD_FLAGS},
                  {"version", DAMPBENCH_VERSION}};
  if (o.format == "json") {
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << t.to_markdown() << fmt::format("\nvector-exp probe: {:.3g} exp/s on 1 thread; build {}; vector kernels {}\n",
                                                exp_per_s, DAMPBENCH_BUILD_FLAGS, isa_summary());
  }
  return 0;
}

}  // namespace dampbench::cli
