// placeholder, replaced by the optimizer-comparison implementation
#include "engine/cli/compare_command.hpp"

#include "engine/error.hpp"

namespace dampbench::cli {
void add_compare_options(CLI::App*, CompareOptions&) {}
int compare_command(const CompareOptions&) { throw InputError("compare: not built yet"); }
}  // namespace dampbench::cli
