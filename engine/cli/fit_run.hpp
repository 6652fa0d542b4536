#pragma once
// A fit as the command line asks for it (`dampbench fit`'s options), run and turned into what it writes: the outputs
// checked before the fit, the fit itself (engine/fit/fit_entry.hpp), the HTML report and model file it asks for, its
// tables and its JSON. `fit` prints it; the Python module's fit and the system benchmark use the same pieces, so no
// command calls another command's function.
#include <string>

#include <nlohmann/json.hpp>

#include "engine/common/statistics.hpp"
#include "engine/common/table.hpp"
#include "engine/fit/fit_entry.hpp"

namespace dampbench::cli {

struct FitOptions {
  FitSpec fit;                ///< what to fit (the command line's --model, --data, --optimizer, ...)
  HeldOutSpec held_out;       ///< what to predict beside the fit (--predict, --folds, --reference)
  std::string format = "md";
  std::string report;         ///< HTML report file ("" = none)
  std::string save_model;     ///< model file of the best run (engine/fit/model_file.hpp; "" = none)
};

/// A finished fit as `dampbench fit` makes it (engine/fit/fit_entry.hpp), before it is printed.
using FitRun = FitResult;

/// Checks the options, fits, and writes the report and model file they ask for (the Python module's fit too).
FitRun run_fit_options(const FitOptions& options);

/// What a fit prints: the best run's parameters with their identifiability, its metrics, and the spread of runs.
struct FitTables {
  Table params, metrics, runs;
  Summary spread;
  long long evaluations = 0;
};
FitTables fit_tables(const PreparedFit& prepared, const FitOutcome& fit, const std::string& metric_option);

/// What `fit --format json` prints: parameters, metrics, convergence, budget, history, identifiability, each run.
nlohmann::ordered_json fit_json(const FitOptions& options, const FitRun& run);

}  // namespace dampbench::cli
