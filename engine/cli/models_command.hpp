#pragma once
// `dampbench models`: every model with its parameters, units and default bounds (md or json).
#include <string>

namespace CLI {
class App;
}

namespace dampbench::cli {

void add_models_options(CLI::App* cmd, std::string& format);
int models_command(const std::string& format);

}  // namespace dampbench::cli
