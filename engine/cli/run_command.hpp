#pragma once
// `dampbench run SWEEP.toml`: presets (datasets/presets/*.toml) are sweep files (format in engine/sweep/spec.hpp).
// The run loads and checks the whole file, loads every dataset, opens (or resumes) the SQLite store, runs the task
// groups not yet stored (across MPI ranks under mpirun, engine/distributed), and writes the tables and the report.
#include <string>

#include "engine/sweep/plan.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

struct RunOptions {
  std::string preset;      ///< sweep file (presets are sweep files)
  std::string output_dir;  ///< default: results/<sweep name>
  std::string store;       ///< SQLite store; default: <output_dir>/store.sqlite (resumed when it exists)
  bool quiet = false;      ///< no progress bar
  bool fresh = false;      ///< delete an existing store first
  bool no_report = false;  ///< skip <output>/report.html
  std::string shard;       ///< "i/n": only this shard's task groups, into its own store (job arrays)
};

void add_run_options(CLI::App* cmd, RunOptions& options);
int run_command(const RunOptions& options);

/// Reads sweep records with the command line's loader (load_record: units, columns, slider-crank transform,
/// cycle averaging, UTFSM conditions, --set).
sweep::Loader sweep_loader();

}  // namespace dampbench::cli
