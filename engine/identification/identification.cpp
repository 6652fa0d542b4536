#include "engine/identification/identification.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include <tbb/parallel_for.h>
#include <string>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/random.hpp"

namespace dampbench {

std::uint64_t task_key(std::string_view model_id, std::string_view dataset_name, std::string_view optimizer) {
  return hash_key({hash_name(model_id), hash_name(dataset_name), hash_name(optimizer)});
}

std::optional<Precision> search_precision_of(std::string_view text) {
  if (text == "double") return Precision::float64;
  if (text == "mixed") return Precision::float32;
  return std::nullopt;
}

Precision parse_search_precision(std::string_view text, std::string_view where) {
  if (const auto p = search_precision_of(text)) return *p;
  throw InputError(fmt::format("{}: expected double or mixed, got '{}'", where, text));
}

std::string_view search_precision_name(Precision p) { return p == Precision::float32 ? "mixed" : "double"; }

int Identification::best_run() const {
  int best = 0;
  for (int r = 1; r < static_cast<int>(runs.size()); ++r)
    if (runs[r].best_value < runs[best].best_value) best = r;
  return best;
}

Identification identify(const Model& model, const Signals& data, const Bounds& bounds,
                        const OptimizerFactory& make_optimizer, const IdentificationSettings& settings) {
  return identify(model, std::vector<const Signals*>{&data}, bounds, make_optimizer, settings);
}

std::vector<std::vector<double>> scaled_residuals(const Model& model, std::span<const Signals* const> data,
                                                  std::span<const std::vector<double>> candidates) {
  const int count = static_cast<int>(candidates.size());
  CandidateBatch batch(model.dim(), count);
  for (int i = 0; i < count; ++i) batch.set_candidate(i, candidates[static_cast<std::size_t>(i)]);
  std::size_t total = 0;
  for (const Signals* d : data) total += d->size();
  std::vector<std::vector<double>> r(static_cast<std::size_t>(count), std::vector<double>(total));
  const int blocks = (count + kLanes - 1) / kLanes;
  tbb::parallel_for(0, blocks, [&](int b) {
    const int first = b * kLanes, n = std::min(kLanes, count - first);
    std::vector<double> force;
    std::size_t offset = 0;
    for (const Signals* d : data) {
      force.resize(static_cast<std::size_t>(n) * d->size());
      model.simulate_block(batch, first, n, *d, force.data());
      const double scale = 1.0 / (std::sqrt(static_cast<double>(d->size())) * d->measured_max_abs);
      for (int i = 0; i < n; ++i) {
        const double* F = force.data() + static_cast<std::size_t>(i) * d->size();
        double* out = r[static_cast<std::size_t>(first + i)].data() + offset;
        for (std::size_t k = 0; k < d->size(); ++k) out[k] = (F[k] - d->measured()[k]) * scale;
      }
      offset += d->size();
    }
  });
  return r;
}

std::vector<double> scaled_residuals(const Model& model, std::span<const Signals* const> data,
                                     std::span<const double> params) {
  const std::vector<double> one(params.begin(), params.end());
  return std::move(scaled_residuals(model, data, std::span<const std::vector<double>>(&one, 1)).front());
}

namespace {

/// The budget rule that stops a run now, or "" to go on.
std::string budget_stop(const Budget& b, const RunResult& run, int stalled, double elapsed_s) {
  if (b.max_evaluations > 0 && run.evaluations >= b.max_evaluations) return "max_evaluations";
  if (!run.trace.empty() && run.trace.back() <= b.target) return "target";
  if (b.stall_iterations > 0 && stalled >= b.stall_iterations) return "stall";
  if (b.max_wall_time_s > 0 && elapsed_s >= b.max_wall_time_s) return "wall_time";
  return "";
}

/// Interrupted once the caller's stop flag is set.
void check_stop(const std::atomic<bool>* stop) {
  if (stop && stop->load(std::memory_order_relaxed)) throw Interrupted("interrupted");
}

/// The problem one run's refinement sees: batch metric through the evaluator, residuals through simulate.
class RunProblem final : public LocalProblem {
 public:
  RunProblem(const BatchEvaluator& evaluator, Metric metric, const Bounds& bounds, const std::atomic<bool>* stop)
      : evaluator_(evaluator), metric_(metric), bounds_(bounds), stop_(stop) {}
  void evaluate(const CandidateBatch& batch, std::span<double> values) const override {
    check_stop(stop_);
    evaluator_.evaluate(batch, metric_, values);
    evaluations_ += batch.count();
  }
  [[nodiscard]] std::vector<double> residuals(std::span<const double> params) const override {
    check_stop(stop_);
    ++evaluations_;
    return scaled_residuals(evaluator_.model(), evaluator_.datasets(), params);
  }
  [[nodiscard]] std::vector<std::vector<double>> residuals_batch(std::span<const std::vector<double>> candidates) const override {
    check_stop(stop_);
    evaluations_ += static_cast<long long>(candidates.size());
    return scaled_residuals(evaluator_.model(), evaluator_.datasets(), candidates);
  }
  /// Within one lane block (kLanes candidates) the points beside the trial take no extra block.
  [[nodiscard]] std::vector<std::vector<double>> residuals_ahead(std::span<const std::vector<double>> points) const override {
    if (points.empty() || points.size() > static_cast<std::size_t>(kLanes)) return {};
    check_stop(stop_);
    ++evaluations_;
    return scaled_residuals(evaluator_.model(), evaluator_.datasets(), points);
  }
  void count_evaluations(long long n) const override { evaluations_ += n; }
  [[nodiscard]] const Bounds& bounds() const override { return bounds_; }
  [[nodiscard]] long long evaluations() const { return evaluations_; }

 private:
  const BatchEvaluator& evaluator_;
  Metric metric_;
  const Bounds& bounds_;
  const std::atomic<bool>* stop_;
  mutable long long evaluations_ = 0;
};

}  // namespace

namespace {

using Clock = std::chrono::steady_clock;
using Runs = std::vector<std::unique_ptr<Optimizer>>;

/// The population phase in lockstep: every unfinished run asks, one batch is evaluated, every run is told its
/// slice, until each run's optimizer or budget stops it. Returns the evaluations spent.
long long lockstep(const Model& model, const BatchEvaluator& evaluator, Runs& runs, Identification& result,
                   const IdentificationSettings& settings, Clock::time_point start) {
  const int R = settings.runs;
  int capacity = 0;
  for (const auto& run : runs) capacity += run->batch_size();
  CandidateBatch batch(model.dim(), capacity);
  std::vector<double> values(capacity);
  std::vector<int> active, first_row;  // unfinished runs and the first row of each one's candidates
  std::vector<int> stalled(R, 0);
  long long evaluations = 0;
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  for (;;) {
    check_stop(settings.stop);
    active.clear();
    first_row.clear();
    int rows = 0;
    for (int r = 0; r < R; ++r) {
      RunResult& run = result.runs[r];
      if (!run.stop_reason.empty()) continue;
      if (runs[r]->finished()) run.stop_reason = "iterations";
      else run.stop_reason = budget_stop(settings.budget, run, stalled[r], elapsed());
      if (!run.stop_reason.empty()) continue;
      active.push_back(r);
      first_row.push_back(rows);
      rows += runs[r]->batch_size();
    }
    if (active.empty()) return evaluations;
    if (rows != batch.count()) batch.resize(model.dim(), rows);
    // Each run's ask and tell touch only that run's state and rows, so the runs go across cores (the
    // serial share of a generation); a run's arithmetic is the same on any thread: same bits.
    const int A = static_cast<int>(active.size());
    tbb::parallel_for(0, A, [&](int i) { runs[active[i]]->ask(batch, first_row[i]); });
    evaluator.evaluate(batch, settings.metric, std::span(values.data(), rows));
    evaluations += rows;
    tbb::parallel_for(0, A, [&](int i) {
      const int r = active[i];
      RunResult& run = result.runs[r];
      const int n = runs[r]->batch_size();
      runs[r]->tell(std::span<const double>(values.data() + first_row[i], n));
      run.evaluations += n;
      stalled[r] = (!run.trace.empty() && !(runs[r]->best_value() < run.trace.back())) ? stalled[r] + 1 : 0;
      run.trace.push_back(runs[r]->best_value());
      run.trace_evaluations.push_back(run.evaluations);
    });
  }
}

}  // namespace

Identification identify(const Model& model, const std::vector<const Signals*>& data, const Bounds& bounds,
                        const OptimizerFactory& make_optimizer, const IdentificationSettings& settings) {
  if (settings.runs < 1) throw InputError(fmt::format("runs must be at least 1, got {}", settings.runs));
  if (data.empty()) throw InputError("identification needs at least one dataset");
  for (const Signals* d : data)
    if (!d->has_measured())
      throw InputError(fmt::format("dataset '{}' has no measured output (force F, or displacement y)", d->name));
  validate_bounds(bounds, model);
  const auto start = Clock::now();

  const int R = settings.runs;
  Runs runs;
  for (int r = 0; r < R; ++r)
    runs.push_back(make_optimizer(bounds, hash_key({settings.seed, settings.task_key, static_cast<std::uint64_t>(r)})));

  Identification result;
  result.runs.resize(R);
  const BatchEvaluator evaluator(model, data, settings.grain_blocks);
  const long long evaluations =
      lockstep(model, BatchEvaluator(model, data, settings.grain_blocks, settings.search_precision), runs, result,
               settings, start);

  // Local refinement of each run (hybrids), runs side by side; each run's refinement is deterministic.
  tbb::parallel_for(0, R, [&](int r) {
    RunProblem problem(evaluator, settings.metric, bounds, settings.stop);
    runs[r]->refine(problem);
    result.runs[r].evaluations += problem.evaluations();
    result.runs[r].at_local_optimum = runs[r]->at_local_optimum();
  });

  // Every metric at each run's best parameters, as one more batch.
  CandidateBatch best(model.dim(), R);
  for (int r = 0; r < R; ++r) best.set_candidate(r, runs[r]->best_position());
  std::vector<MetricRow> metrics(R);
  evaluator.evaluate_all(best, metrics);

  result.wall_time_s = std::chrono::duration<double>(Clock::now() - start).count();
  result.candidate_samples = static_cast<double>(evaluations) * evaluator.samples();
  const int metric_index = static_cast<int>(settings.metric);
  for (int r = 0; r < R; ++r) {
    RunResult& run = result.runs[r];
    run.best_params = best.candidate(r);
    run.best_metrics = metrics[r];
    run.best_value = metrics[r][metric_index];
    run.wall_time_s = result.wall_time_s / R;
  }
  return result;
}

}  // namespace dampbench
