#pragma once
// One fit: a model identified on one or more records by repeated optimizer runs, with the evidence that goes
// with every result (the runs' agreement and stalling, the parameters' standard errors and correlations).
// `dampbench fit`, every sweep group and so every MPI worker run this one sequence, so that the same request
// gives the same bits whichever entry point asks for it.
//
// The random streams of the runs are keyed (seed, task key, run): the task key is part of the request, because
// the entry points name a task differently (a fit by model id, record names and optimizer; a sweep group also by
// its labels, metric and split), and a request that names the same key gets the same streams.
#include <optional>
#include <string>
#include <vector>

#include "engine/fit/auto_budget.hpp"
#include "engine/fit/resolve_model.hpp"
#include "engine/identification/convergence.hpp"
#include "engine/identification/identifiability.hpp"
#include "engine/identification/identification.hpp"
#include "engine/identification/optimizer.hpp"

namespace dampbench {

struct FitRequest {
  const ResolvedModel* model = nullptr;
  std::vector<const Signals*> records;  ///< fitted together: the metric is their mean
  const OptimizerFactory* optimizer = nullptr;
  IdentificationSettings settings;      ///< runs, seed, task key, metric, budget
  /// Assess identifiability even when every run failed (no finite best value): `fit` prints it whatever the
  /// outcome, a sweep stores it only for a fit that found something.
  bool assess_failed_fit = false;
  /// A start point for the search (Bounds::start), in the model's parameter order; empty: none.
  std::vector<double> start;
  /// The box to search instead of the model's box for these records (a sweep's narrowed bounds,
  /// engine/fit/record_narrowing.hpp); absent: ResolvedModel::bounds_for.
  std::optional<Bounds> box;
  /// Restarts until the runs converge (auto_budget.hpp), its optimizer the one `optimizer` makes; absent: the
  /// fixed budget of `optimizer` and `settings`.
  std::optional<AutoBudget> auto_budget;
  /// Told the automatic budget's rounds as they end (a fit of a law model on many records runs for many
  /// minutes); may be empty.
  BudgetProgress progress;
};

struct FitOutcome {
  Bounds bounds;                                  ///< the box the runs searched
  Identification identification;
  Convergence convergence;                        ///< the verdict on the runs (convergence.hpp)
  std::optional<Identifiability> identifiability; ///< at the best run's parameters
  std::optional<AutoBudgetReport> auto_budget;    ///< what the restarts did, with an automatic budget

  [[nodiscard]] const RunResult& best() const { return identification.runs[identification.best_run()]; }
};

/// Checks that a record has what the model needs (the operating variables of a law model's laws); InputError
/// names what is missing.
void check_record(const Model& model, const Signals& record);

/// Runs the request: checks the records, works out the bounds for them, identifies, and assesses convergence
/// and identifiability. Throws for bad input (InputError, DataError) and model errors.
FitOutcome run_fit(const FitRequest& request);

}  // namespace dampbench
