#include "engine/identification.hpp"

#include <chrono>
#include <string>

#include <fmt/format.h>

#include "engine/error.hpp"
#include "engine/random.hpp"

namespace dampbench {

std::uint64_t task_key(std::string_view model_id, std::string_view dataset_name, std::string_view optimizer) {
  return hash_key({hash_name(model_id), hash_name(dataset_name), hash_name(optimizer)});
}

int Identification::best_run() const {
  int best = 0;
  for (int r = 1; r < static_cast<int>(runs.size()); ++r)
    if (runs[r].best_value < runs[best].best_value) best = r;
  return best;
}

Identification identify(const Model& model, const Signals& data, const Bounds& bounds,
                        const OptimizerFactory& make_optimizer, const IdentificationSettings& settings) {
  if (settings.runs < 1) throw InputError(fmt::format("runs must be at least 1, got {}", settings.runs));
  if (!data.has_force()) throw InputError(fmt::format("dataset '{}' has no force column F", data.name));
  validate_bounds(bounds, model);
  const auto start = std::chrono::steady_clock::now();

  const int R = settings.runs;
  std::vector<std::unique_ptr<Optimizer>> runs;
  std::vector<int> offset(R + 1, 0);
  for (int r = 0; r < R; ++r) {
    runs.push_back(make_optimizer(bounds, hash_key({settings.seed, settings.task_key, static_cast<std::uint64_t>(r)})));
    offset[r + 1] = offset[r] + runs[r]->batch_size();
  }

  Identification result;
  result.runs.resize(R);
  const BatchEvaluator evaluator(model, data, settings.grain_blocks);
  CandidateBatch batch(model.dim(), offset[R]);
  std::vector<double> values(offset[R]);
  std::vector<int> active;
  long long evaluations = 0;

  // Lockstep: every unfinished run asks, one batch is evaluated, every run is told its slice.
  for (;;) {
    active.clear();
    int rows = 0;
    for (int r = 0; r < R; ++r)
      if (!runs[r]->finished()) {
        active.push_back(r);
        rows += runs[r]->batch_size();
      }
    if (active.empty()) break;
    if (rows != batch.count()) batch.resize(model.dim(), rows);
    int row = 0;
    for (int r : active) {
      runs[r]->ask(batch, row);
      row += runs[r]->batch_size();
    }
    evaluator.evaluate(batch, settings.metric, std::span(values.data(), rows));
    evaluations += rows;
    row = 0;
    for (int r : active) {
      const int n = runs[r]->batch_size();
      runs[r]->tell(std::span<const double>(values.data() + row, n));
      result.runs[r].evaluations += n;
      result.runs[r].trace.push_back(runs[r]->best_value());
      row += n;
    }
  }

  // Every metric at each run's best parameters, as one more batch.
  CandidateBatch best(model.dim(), R);
  for (int r = 0; r < R; ++r) best.set_candidate(r, runs[r]->best_position());
  std::vector<MetricSums> sums(R);
  evaluator.evaluate_sums(best, sums);

  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.candidate_samples = static_cast<double>(evaluations) * static_cast<double>(data.size());
  for (int r = 0; r < R; ++r) {
    RunResult& run = result.runs[r];
    run.best_params = best.candidate(r);
    run.best_metrics = finish_all_metrics(sums[r], data);
    run.best_value = finish_metric(settings.metric, sums[r], data);
    run.wall_time_s = result.wall_time_s / R;
  }
  return result;
}

}  // namespace dampbench
