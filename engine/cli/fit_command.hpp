#pragma once
// `dampbench fit`: a model's parameters identified on one or more records by repeated optimizer runs (engine/fit),
// printed as Markdown or JSON with the runs' convergence and the parameters' identifiability, and optionally an
// HTML report.
#include <string>

#include "engine/fit/held_out.hpp"
#include "engine/fit/prepared_fit.hpp"

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

void add_fit_options(CLI::App* cmd, FitOptions& options);
int fit_command(const FitOptions& options);

}  // namespace dampbench::cli
