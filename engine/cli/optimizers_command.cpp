#include "engine/cli/optimizers_command.hpp"

#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/common/error.hpp"
#include "engine/common/table.hpp"
#include "optimizers/registry.hpp"

namespace dampbench::cli {

void add_optimizers_options(CLI::App* cmd, std::string& format) {
  format = "md";
  cmd->add_option("--format", format, "md or json");
}

std::string optimizers_markdown() {
  std::string md;
  for (const std::string& name : optimizer_names()) {
    Table t{name, fmt::format("{} (`--optimizer {}`)", name, name),
            {"setting", "type", "default", "allowed", "meaning"}, {}};
    for (const SettingRow& row : optimizer_setting_rows(name))
      t.rows.push_back({Cell("`" + row.key + "`"), Cell(row.type), Cell(row.default_value), Cell(row.allowed),
                        Cell(row.meaning)});
    md += t.to_markdown() + "\n";
  }
  return md;
}

int optimizers_command(const std::string& format) {
  if (format == "md") {
    std::cout << optimizers_markdown();
    return 0;
  }
  if (format != "json") throw InputError(fmt::format("--format: expected md or json, got '{}'", format));
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (const std::string& name : optimizer_names()) {
    nlohmann::ordered_json settings = nlohmann::ordered_json::array();
    for (const SettingRow& row : optimizer_setting_rows(name))
      settings.push_back({{"key", row.key}, {"type", row.type}, {"default", row.default_value},
                          {"allowed", row.allowed}, {"meaning", row.meaning}});
    out[name] = {{"settings", settings}};
  }
  std::cout << nlohmann::ordered_json{{"optimizers", out}}.dump(2) << "\n";
  return 0;
}

}  // namespace dampbench::cli
