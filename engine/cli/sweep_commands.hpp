#pragma once
// Sweeps (`dampbench run SWEEP.toml`), their SQLite store, and the commands that read it back
// (`dampbench table STORE`, `dampbench verify STORE`).
#include <string>

#include "engine/cli/commands.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

struct TableOptions {
  std::string store;
  std::string kind;
  std::string format = "md";  ///< md, csv, latex, json
};

struct VerifyOptions {
  std::string store;
  int sample = 0;  ///< re-run this many stored tasks (0: all)
};

void add_run_options(CLI::App* cmd, RunOptions& options);
void add_table_options(CLI::App* cmd, TableOptions& options);
void add_verify_options(CLI::App* cmd, VerifyOptions& options);
int table_command(const TableOptions& options);
int verify_command(const VerifyOptions& options);

}  // namespace dampbench::cli
