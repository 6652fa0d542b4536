// placeholder, replaced by the LS-SVM implementation
#include "engine/cli/lssvm_command.hpp"

#include <CLI/CLI.hpp>

#include "engine/error.hpp"

namespace dampbench::cli {
void add_lssvm_options(CLI::App*, LssvmOptions&) {}
int lssvm_command(const LssvmOptions&) { throw InputError("lssvm: not built yet"); }
}  // namespace dampbench::cli
