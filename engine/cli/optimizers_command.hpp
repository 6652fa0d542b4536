#pragma once
// `dampbench optimizers`: every optimizer with its settings (key, type, default, allowed values, meaning), from the
// optimizers' own tables (optimizers/setting_table.hpp); the guide's table of settings is this command's Markdown.
#include <string>

namespace CLI {
class App;
}

namespace dampbench::cli {

void add_optimizers_options(CLI::App* cmd, std::string& format);

/// The Markdown the command prints: one table per optimizer.
std::string optimizers_markdown();

int optimizers_command(const std::string& format);

}  // namespace dampbench::cli
