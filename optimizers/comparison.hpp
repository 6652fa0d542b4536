#pragma once
// Several optimizers on the same (model, datasets), side by side (`dampbench compare`: its
// convergence curves and fixed-target runtimes). Each optimizer runs `runs` independent lockstep runs through
// identify() with its own task key (model id, data name, the optimizer's label), so adding or removing an
// entry never changes another entry's results.
//
// Per optimizer:
//   best, worst, mean, std   of the runs' best metric values (engine/common/statistics.hpp: +inf if any run failed);
//   success rate             runs with best ≤ b + success_tolerance·|b|, b the best value found by any run of
//                            any optimizer in the comparison (default tolerance 0.01: "within 1 % of the best");
//   evaluations to target    per run, the evaluations at the first point of its convergence trace whose
//                            best-so-far is ≤ target; +inf for a run that never gets there. Reported: the median
//                            over the runs (+inf, printed "—", when fewer than half reach it) and the count that
//                            reach it. Default target: b + 0.01·|b| (1.01 × b for b > 0), the success threshold,
//                            so the default answers "how fast do the successful runs get there";
//   convergence curve        at every evaluation count where any run has a trace point, the 25 %, 50 % and 75 %
//                            quantiles (linear interpolation between order statistics, R type 7) over the runs of
//                            their best-so-far value (+inf before a run's first point);
//   feasible                 ga-sqp entries only: runs with best ≤ the entry's constraint (fdsp eq. 11,
//                            optimizers/hybrid/ga_sqp.hpp).
// Traces: RunResult::trace has one point per population iteration; a hybrid's local phase (refine) adds
// evaluations after the last one. The comparison appends that end point, (RunResult::evaluations,
// min(last trace value, RunResult::best_value)), so a hybrid's curve and its evaluations to target include
// its local phase.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/identification/identification.hpp"
#include "engine/common/statistics.hpp"
#include "engine/common/table.hpp"
#include "optimizers/registry.hpp"

namespace dampbench {

/// "NAME" or "NAME:key=value,key=value": population and iterations go to the spec's fields (defaults as
/// given), every other key to its settings (validated by make_optimizer_factory). InputError names the
/// entry: "--optimizer 'ga:population=x': population: expected a whole number, got 'x'".
OptimizerSpec parse_optimizer_entry(std::string_view text, int default_population = 50, int default_iterations = 100);

struct ComparisonEntry {
  std::string label;  ///< as the user wrote it, e.g. "ga-sqp:population=240"; unique within a comparison
  OptimizerSpec spec;
};

struct ComparisonSettings {
  IdentificationSettings identification;  ///< runs, seed, metric, grain_blocks, budget (task_key is set per entry)
  std::string data_name;                  ///< names the datasets in the task keys
  std::optional<double> target;           ///< evaluations-to-target threshold; default b + 0.01·|b|
  double success_tolerance = 0.01;        ///< relative distance to the best value counted as success
};

struct CurvePoint {
  long long evaluations = 0;
  double q25 = 0, median = 0, q75 = 0;
};

struct OptimizerComparison {
  std::string label;
  OptimizerSpec spec;
  std::vector<RunResult> runs;
  Summary summary;                 ///< min = best, max = worst
  int successes = 0;
  double success_rate = 0;         ///< successes / runs
  int reached_target = 0;
  double median_evaluations_to_target = 0;  ///< +inf when fewer than half the runs reach the target
  double mean_evaluations = 0;     ///< per run, local phases included
  std::optional<int> feasible_runs;///< ga-sqp only
  std::optional<double> constraint;///< ga-sqp only: the constraint the feasibility was read against
  double wall_time_s = 0;          ///< the entry's lockstep group
  std::vector<CurvePoint> curve;
};

struct Comparison {
  double best_found = 0;        ///< lowest best value over every run of every entry (+inf if all failed)
  double success_tolerance = 0.01;
  double success_threshold = 0; ///< best_found + success_tolerance·|best_found|
  double target = 0;
  bool target_given = false;
  std::vector<OptimizerComparison> optimizers;
};

/// Runs every entry. InputError for no entries, duplicate labels, bad specs (registry messages prefixed by the
/// label), a non-finite target, a success tolerance < 0, and whatever identify() rejects.
Comparison compare_optimizers(const Model& model, const std::vector<const Signals*>& data, const Bounds& bounds,
                              const std::vector<ComparisonEntry>& entries, const ComparisonSettings& settings);

/// A run's convergence trace with the local phase's end point appended (see the header comment).
void completed_trace(const RunResult& run, std::vector<long long>& evaluations, std::vector<double>& values);

/// The summary table (one row per optimizer) and the convergence curves as CSV
/// (optimizer,evaluations,q25,median,q75).
Table comparison_table(const Comparison& comparison, std::string_view metric);
std::string convergence_csv(const Comparison& comparison);

}  // namespace dampbench
