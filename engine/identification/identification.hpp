#pragma once
// Repeated identification runs of one (model, dataset): R independent optimizer runs advance in
// lockstep, each iteration's R·N candidates evaluated as one batch across cores (docs/design.md, data flow).
#include <array>
#include <atomic>
#include <string>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/model/bounds.hpp"
#include "engine/model/metrics.hpp"
#include "engine/identification/optimizer.hpp"

namespace dampbench {

/// Stopping rules of a run, on top of the optimizer's own iteration count. A run stops at the end of
/// the first iteration where any rule holds:
///   evaluations ≥ max_evaluations;  best ≤ target;  no improvement of best for stall_iterations
///   iterations;  wall time of the group ≥ max_wall_time_s.
/// Zero (or -inf for target) switches a rule off. The wall-time rule depends on the machine's speed, so a
/// run stopped by it is not reproducible bit for bit; every other rule is.
struct Budget {
  long long max_evaluations = 0;
  double target = -std::numeric_limits<double>::infinity();
  int stall_iterations = 0;
  double max_wall_time_s = 0;
};

struct IdentificationSettings {
  int runs = 50;                ///< independent runs (fvd paper: 50)
  std::uint64_t seed = 1;       ///< sweep seed
  std::uint64_t task_key = 0;   ///< stable key of the task (see task_key()); runs are keyed (seed, task, run)
  Metric metric = Metric::of_abs;
  int grain_blocks = 1;         ///< lane blocks per oneTBB task; results do not depend on it
  Budget budget;
  /// Lanes of the population phase: float64, or float32 (`--precision mixed`: the model's single-precision lanes
  /// where it has them). Local refinements and the reported metrics at each run's best are float64 either way.
  Precision search_precision = Precision::float64;
  /// Checked every generation and every local-stage evaluation: once set, identify throws Interrupted (the
  /// Python module's Ctrl-C). Null: never stops early.
  const std::atomic<bool>* stop = nullptr;
};

/// `--precision` (fit) and a sweep entry's `precision`: "double" → float64 search lanes, "mixed" → float32 search
/// lanes (IdentificationSettings::search_precision); nullopt for any other text.
std::optional<Precision> search_precision_of(std::string_view text);
/// search_precision_of, or InputError naming `where`.
Precision parse_search_precision(std::string_view text, std::string_view where);
/// "double" or "mixed", the name parse_search_precision reads.
std::string_view search_precision_name(Precision p);

/// Stable key of a (model, dataset, optimizer) task, from their names.
std::uint64_t task_key(std::string_view model_id, std::string_view dataset_name, std::string_view optimizer);

struct RunResult {
  std::vector<double> best_params;                ///< SI
  double best_value = 0;                          ///< the optimized metric at best_params (float64 lanes)
  std::array<double, kMetricCount> best_metrics;  ///< every metric at best_params (order of kAllMetrics)
  long long evaluations = 0;
  double wall_time_s = 0;  ///< this run's share of the lockstep group's wall time (group time / runs)
  std::vector<double> trace;  ///< best-so-far metric after each iteration (convergence), in the search's lanes
  std::vector<long long> trace_evaluations;  ///< evaluations spent at each trace point
  std::string stop_reason;    ///< "iterations", "max_evaluations", "target", "stall" or "wall_time"
  bool at_local_optimum = false;  ///< a local refinement ended on its own convergence test (Optimizer::at_local_optimum)
};

struct Identification {
  std::vector<RunResult> runs;
  double wall_time_s = 0;          ///< whole lockstep group
  double candidate_samples = 0;    ///< Σ evaluations × samples (samples summed over the datasets)
  [[nodiscard]] int best_run() const;  ///< index of the run with the lowest best_value (first on ties)
};

/// Residuals F_model − F_measured of one candidate at every sample of every dataset, each dataset's residuals
/// divided by sqrt(N_d)·max|F_d|, so that ‖r‖² = Σ_d nrmse_d² (local refinements, identifiability).
std::vector<double> scaled_residuals(const Model& model, std::span<const Signals* const> data,
                                     std::span<const double> params);

/// scaled_residuals of many candidates, simulated kLanes at a time (Model::simulate_block) with the lane blocks
/// across cores: the same bits as one call per candidate, at the cost of one block per kLanes candidates.
std::vector<std::vector<double>> scaled_residuals(const Model& model, std::span<const Signals* const> data,
                                                  std::span<const std::vector<double>> candidates);

/// Identifies the model on one or more datasets (the metric is the mean over them, engine/evaluation/batch_evaluator.hpp).
Identification identify(const Model& model, const std::vector<const Signals*>& data, const Bounds& bounds,
                        const OptimizerFactory& make_optimizer, const IdentificationSettings& settings);
Identification identify(const Model& model, const Signals& data, const Bounds& bounds,
                        const OptimizerFactory& make_optimizer, const IdentificationSettings& settings);

}  // namespace dampbench
