#pragma once
// `dampbench fit`: a model's parameters identified on one or more records by repeated optimizer runs (engine/fit),
// printed as Markdown or JSON with the runs' convergence and the parameters' identifiability, and optionally an
// HTML report.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/fit/fit_entry.hpp"

namespace CLI {
class App;
}

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

void add_fit_options(CLI::App* cmd, FitOptions& options);

/// Checks the options, fits, and writes the report and model file they ask for (the Python module's fit too).
FitRun run_fit_options(const FitOptions& options);

/// What `fit --format json` prints: parameters, metrics, convergence, budget, history, identifiability, each run.
nlohmann::ordered_json fit_json(const FitOptions& options, const FitRun& run);

int fit_command(const FitOptions& options);

}  // namespace dampbench::cli
