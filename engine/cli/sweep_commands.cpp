// placeholder, replaced by the sweep implementation
#include "engine/cli/sweep_commands.hpp"

#include <CLI/CLI.hpp>

#include "engine/error.hpp"

namespace dampbench::cli {
void add_run_options(CLI::App* cmd, RunOptions& o) {
  cmd->add_option("preset", o.preset, "preset or sweep file")->required();
  cmd->add_option("-o,--output", o.output_dir, "output folder (default results/<preset name>)");
}
void add_table_options(CLI::App*, TableOptions&) {}
void add_verify_options(CLI::App*, VerifyOptions&) {}
int table_command(const TableOptions&) { throw InputError("table: not built yet"); }
int verify_command(const VerifyOptions&) { throw InputError("verify: not built yet"); }
}  // namespace dampbench::cli
