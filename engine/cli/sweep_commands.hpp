#pragma once
// Sweeps (`dampbench run SWEEP.toml`), their SQLite store, and the commands that read it back
// (`dampbench table STORE`, `dampbench verify STORE`).
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

void add_run_options(CLI::App* cmd, RunOptions& options);
void add_table_options(CLI::App* cmd, TableOptions& options);
void add_verify_options(CLI::App* cmd, VerifyOptions& options);
int table_command(const TableOptions& options);
int verify_command(const VerifyOptions& options);

}  // namespace dampbench::cli
