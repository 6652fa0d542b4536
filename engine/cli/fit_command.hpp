#pragma once
// `dampbench fit`: a model's parameters identified on one or more records by repeated optimizer runs (engine/fit),
// printed as Markdown or JSON with the runs' convergence and the parameters' identifiability, and optionally an
// HTML report. Running it is fit_run.hpp's.
#include "engine/cli/fit_run.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

void add_fit_options(CLI::App* cmd, FitOptions& options);

int fit_command(const FitOptions& options);

}  // namespace dampbench::cli
