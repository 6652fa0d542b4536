#pragma once
// The subcommands of the `dampbench` command line. Each returns the process exit code; bad input is
// thrown as InputError and reported by main().
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/record/csv_loader.hpp"
#include "engine/record/dataset.hpp"
#include "engine/record/record_options.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

/// Declares the loader options (--units, --columns, --transform, --average-cycles, --conditions, --set) on a
/// subcommand.
void add_data_options(CLI::App* cmd, RecordOptions& data);

struct SimulateOptions {
  std::string model;
  std::string fixture;  ///< a published law fixture instead of --model (models/fixtures.hpp)
  std::string laws;     ///< "c0=poly(I,1);..." laws on the model's parameters
  std::string params;   ///< "name=value,..." in SI (the fixture's values by default)
  RecordOptions input;   ///< used when sine is empty
  std::string sine;    ///< "amp=...,freq=...,cycles=...,fs=..."
  double noise_rel = 0;
  std::uint64_t seed = 1;
  std::string output;  ///< CSV path; stdout when empty
};

struct FitOptions {
  std::string model;
  std::string laws;                 ///< parameter laws; with several --data, one set of coefficients for all
  std::vector<std::string> paths;   ///< one or more records (the metric is averaged over them)
  RecordOptions data;                 ///< loader options shared by every record (path unused)
  std::string metric = "of_abs";
  /// Not given: by the model's class (engine/cli/fit_defaults.hpp).
  std::optional<std::string> optimizer;
  std::string optimizer_settings;  ///< "pc=0.6,pm=0.03" or "preset=lssvm" (optimizers/registry.hpp)
  std::optional<int> population, iterations, runs;
  std::uint64_t seed = 1;
  std::string bounds;
  std::string format = "md";
  std::string report;  ///< HTML report file ("" = none)
};

/// One or more cases (parameters + input); SP is reported per case and averaged (crfd averages
/// 1 Hz–1 mm and 3 Hz–3 mm).
struct SensitivityOptions {
  std::string model;
  std::vector<std::string> params;  ///< one per case
  std::vector<std::string> sines;   ///< one per case (or one for all)
  std::vector<std::string> paths;   ///< records instead of sines
  RecordOptions data;                 ///< loader options for the records
  int points = 21;
  double range = 0.5;
  std::string objective = "rms";    ///< rms (of the model force) or a metric name
  bool normalized = false;
  std::string format = "md";
};

/// Metrics of given parameters on one or more records (no optimization).
struct EvaluateOptions {
  std::string model;
  std::string laws;
  std::string params;
  std::vector<std::string> paths;
  RecordOptions data;
  std::string format = "md";
};

/// `dampbench run SWEEP.toml` (engine/cli/preset.cpp, engine/sweep).
struct RunOptions {
  std::string preset;      ///< sweep file (presets are sweep files)
  std::string output_dir;  ///< default: results/<sweep name>
  std::string store;       ///< SQLite store; default: <output_dir>/store.sqlite (resumed when it exists)
  bool quiet = false;      ///< no progress bar
  bool fresh = false;      ///< delete an existing store first
  bool no_report = false;  ///< skip <output>/report.html
  std::string shard;       ///< "i/n": only this shard's task groups, into its own store (job arrays)
};

/// `dampbench merge OUT PART...` (engine/distributed/merge.hpp).
struct MergeOptions {
  std::string out;
  std::vector<std::string> parts;
};

int models_command(const std::string& format);
int simulate_command(const SimulateOptions& options);
int fit_command(const FitOptions& options);
int run_command(const RunOptions& options);
int merge_command(const MergeOptions& options);
int sensitivity_command(const SensitivityOptions& options);
int evaluate_command(const EvaluateOptions& options);

}  // namespace dampbench::cli
