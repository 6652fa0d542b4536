#pragma once
// A fit named the way `dampbench fit` names it (model, laws, bounds, files, metric, optimizer, budget, runs,
// seed), made into a request: the model resolved, the class defaults filled in (fit_defaults.hpp), the optimizer
// built and the records loaded. The command only parses its options into a FitSpec and prints the outcome.
#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/fit/fit.hpp"
#include "engine/fit/fit_defaults.hpp"
#include "engine/fit/fit_records.hpp"
#include "engine/fit/resolve_model.hpp"
#include "engine/record/record_options.hpp"
#include "optimizers/registry.hpp"

namespace dampbench {

struct FitSpec {
  ModelChoice model;                ///< model id, laws (one set of coefficients for every record), bounds
  std::vector<std::string> paths;   ///< one or more records (the metric is averaged over them)
  std::vector<Dataset> records;     ///< records already loaded, instead of paths (the Python module's)
  RecordOptions data;               ///< loader options shared by every record (path unused)
  std::string metric = "of_abs";
  std::optional<std::string> optimizer;  ///< not given: by the model's class (fit_defaults.hpp)
  std::string optimizer_settings;        ///< "pc=0.6,pm=0.03" or "preset=lssvm" (optimizers/registry.hpp)
  std::optional<int> population, iterations, runs;
  /// "auto", "fixed", or "" for the default: auto, unless population, iterations or runs is given (then those,
  /// with the class defaults for the others, are a fixed budget). Auto with some of them given starts from them.
  std::string budget;
  std::optional<long long> max_evaluations;  ///< the automatic budget's cap (auto_budget.hpp)
  std::optional<double> max_seconds;         ///< the automatic budget's wall-clock cap
  std::uint64_t seed = 1;
  /// "", "per-file" (engine/fit/record_start.hpp), "narrowed" (three rounds of the mfm paper's bound narrowing from
  /// the default box, engine/fit/record_narrowing.hpp), or a model file (fit --save-model) of the same model whose
  /// coefficients start the search
  std::string start;
  /// "mixed" (default): the population phase in single-precision lanes (IdentificationSettings::search_precision), or "double"
  std::string precision = "mixed";
  /// Once set, the fit stops at the next generation with Interrupted (the Python module's Ctrl-C); may be null.
  const std::atomic<bool>* stop = nullptr;
};

/// Everything a FitSpec names, built and loaded; its request points into it.
struct PreparedFit {
  ModelChoice choice;       ///< what the model was resolved from (--laws auto: laws cleared)
  ResolvedModel model;      ///< with --laws auto: the base model until the laws are chosen
  bool auto_laws = false;   ///< --laws auto (engine/fit/law_selection.hpp)
  bool start_per_file = false;  ///< --start per-file (engine/fit/record_start.hpp)
  bool start_narrowed = false;  ///< --start narrowed: the box and start of bound narrowing (record_narrowing.hpp)
  std::vector<double> start;    ///< --start FILE: the file's coefficients, member 0 of each run; empty: none
  Metric metric = Metric::of_abs;
  FitPlan plan;             ///< optimizer, population, iterations and runs, with the class defaults
  OptimizerSpec optimizer;  ///< the plan's with the settings given
  OptimizerFactory factory;
  std::optional<AutoBudget> auto_budget;  ///< the restarts (auto_budget.hpp); absent: the plan is a fixed budget
  FitRecords records;
  std::uint64_t seed = 1;
  Precision search_precision = Precision::float64;  ///< FitSpec::precision
  const std::atomic<bool>* stop = nullptr;

  /// The request of this fit; its task key names the model id, the records' names and the optimizer
  /// (task_key), so that the same command line gives the same runs.
  [[nodiscard]] FitRequest request() const;
};

/// InputError (and the loader's errors) for what the spec names wrongly, in the order the options are read.
PreparedFit prepare_fit(const FitSpec& spec);

}  // namespace dampbench
