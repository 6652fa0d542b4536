#pragma once
// Sweeps (`dampbench run SWEEP.toml`), their SQLite store, the commands that read it back
// (`dampbench table STORE`, `dampbench verify STORE`, `dampbench merge OUT PARTS`), and the synthetic grids presets read
// (`dampbench datasets generate`).
#include <string>
#include <vector>

#include "engine/cli/commands.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

struct TableOptions {
  std::string store;
  std::string kind;           ///< a table kind (engine/sweep/tables.hpp) or "sweep": the sweep file's tables
  std::string format = "md";  ///< md, csv, latex, json
  std::string split;          ///< only this split
  std::vector<std::string> models, optimizers;  ///< only these (names / labels)
  std::string metric;         ///< metric shown (errors) / optimized metric chosen
  std::string role;           ///< errors: fit or predict
  double target_rel = 0.01;   ///< runtime: relative distance of the target to the best known value
};

struct VerifyOptions {
  std::string store;
  int sample = 0;     ///< re-run this many stored task groups, spread evenly over the store (0: all)
  std::string spec;   ///< the sweep file (default: the path recorded in the store)
};

/// `dampbench datasets generate [GRID...] [--into DIR]`: the synthetic grids presets name "@generated/...",
/// written ahead of first use (datasets/synthetic/grids.hpp).
struct DatasetsOptions {
  std::vector<std::string> grids;  ///< default: every grid
  std::string into;                ///< default: the cache folder `run` reads (engine/sweep/spec.hpp generated_dir)
};

void add_run_options(CLI::App* cmd, RunOptions& options);
void add_merge_options(CLI::App* cmd, MergeOptions& options);
void add_datasets_options(CLI::App* cmd, DatasetsOptions& options);
int datasets_command(const DatasetsOptions& options);
void add_table_options(CLI::App* cmd, TableOptions& options);
void add_verify_options(CLI::App* cmd, VerifyOptions& options);
int table_command(const TableOptions& options);
int verify_command(const VerifyOptions& options);

}  // namespace dampbench::cli
