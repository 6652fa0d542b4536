#pragma once
// Bound narrowing over several conditions (mfm §5.1, the Spencer model's identification): "set the value
// range of each parameter as [−1e8, 1e8], and identify each parameter by genetic algorithm, respectively,
// under [each current]. The minimum value of each parameter obtained by different current identification is
// used as the lower limit, and the maximum value is taken as the upper limit, which is reset as the parameter
// value range and identified by genetic algorithm. After narrowing the parameter interval several times, the
// final parameter identification result can be obtained (Table 3)."
//
// Procedure, for round k = 1 … rounds:
//   1. every condition c is identified on its own (identify(), `settings.runs` runs of the inner optimizer,
//      any registered one: `ga` as in the paper, or a hybrid) within the round's bounds; its result is the
//      best run's parameters;
//   2. the next bounds are, per parameter, [min, max] of the results over the conditions that did not fail;
//      they lie inside the round's bounds (every result does). A parameter whose results all agree gets
//      lower == upper and is fixed from then on.
// A condition fails in a round when every run of it stayed +inf (at [−1e8, 1e8] nearly every candidate blows
// up and is masked by the kernels). Failed conditions are listed in the round and left out of the min/max.
// When every condition of a round fails, there is nothing to narrow to: the procedure stops there, keeps the
// round's bounds as the final ones (never inf or NaN bounds) and says so in stop_reason.
// Random streams: condition c of round k runs with task key hash_key({settings.task_key, "narrow", k, c}),
// so each (round, condition) has its own runs and the whole procedure is reproducible bit for bit (same
// thread-count and batch-split independence as identify()).
#include <string>
#include <vector>

#include "engine/identification/identification.hpp"
#include "optimizers/registry.hpp"

namespace dampbench {

struct NarrowingCondition {
  std::string name;               ///< the dataset's name
  std::vector<double> best_params;///< best run's parameters (empty when failed)
  double best_value = 0;          ///< best run's metric (+inf when failed)
  int finite_runs = 0;            ///< runs that ended with a finite metric
  long long evaluations = 0;
  bool failed = false;            ///< every run stayed +inf
};

struct NarrowingRound {
  int round = 0;                  ///< 1-based
  Bounds bounds;                  ///< searched in this round
  std::vector<NarrowingCondition> conditions;
  Bounds next;                    ///< [min, max] over the non-failed conditions (== bounds if all failed)
  int failed_conditions = 0;
  double wall_time_s = 0;
};

struct NarrowingResult {
  std::vector<NarrowingRound> rounds;  ///< the rounds run (fewer than asked when stopped early)
  Bounds final_bounds;                 ///< the last round's `next`
  std::string stop_reason;             ///< "rounds", or "round k: every condition failed (all runs +inf); bounds kept"
  [[nodiscard]] bool completed() const { return stop_reason == "rounds"; }
};

/// Runs the narrowing procedure. InputError: rounds < 1 ("narrow: rounds must be at least 1, got 0"), no
/// conditions, a null condition, bad bounds or optimizer spec (the messages of validate_bounds and the
/// registry), or a condition without force.
NarrowingResult narrow_bounds(const Model& model, const std::vector<const Signals*>& conditions, Bounds start,
                              const OptimizerSpec& inner, int rounds, IdentificationSettings settings);

/// The paper's starting box: [−1e8, 1e8] for every parameter of the model.
Bounds wide_bounds(const Model& model, double half_width = 1e8);

}  // namespace dampbench
