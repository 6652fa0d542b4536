#include "engine/cli/models_command.hpp"

#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/cli/cli_options.hpp"
#include "engine/common/table.hpp"
#include "engine/model/bounds.hpp"
#include "models/registry.hpp"

namespace dampbench::cli {

void add_models_options(CLI::App* cmd, std::string& format) {
  format = "md";
  cmd->add_option("--format", format, "md or json");
}

namespace {

/// The record rule of a parameter, if any ("" otherwise): its default box when a record is fitted.
std::string rule_of(const Model& m, const ParameterInfo& p) {
  for (const RecordBoundsRule& r : m.record_bounds_rules())
    if (r.name == p.name) return r.describe();
  return std::string();
}

}  // namespace

nlohmann::ordered_json models_json(std::span<const Signals* const> records) {
  nlohmann::ordered_json models = nlohmann::ordered_json::object();
  for (const Model* m : all_models()) {
    const Bounds bounds = default_bounds(*m, records);
    nlohmann::ordered_json params = nlohmann::ordered_json::array();
    for (int j = 0; j < m->dim(); ++j) {
      const ParameterInfo& p = m->parameters()[j];
      params.push_back({{"name", p.name}, {"unit", p.unit}, {"lower", bounds.lower[j]}, {"upper", bounds.upper[j]},
                        {"paper_unit", p.paper_unit}});
      if (const std::string rule = rule_of(*m, p); !rule.empty()) params.back()["record_rule"] = rule;
    }
    models[std::string(m->id())] = {{"citation", m->citation()}, {"law", m->law()}, {"parameters", params}};
  }
  return models;
}

int models_command(const std::string& format) {
  check_format(format);
  if (format == "json") {
    std::cout << nlohmann::ordered_json{{"models", models_json()}}.dump(2) << "\n";
    return 0;
  }
  for (const Model* m : all_models()) {
    Table t{std::string(m->id()), fmt::format("{} ({}): {}", m->id(), m->citation(), m->law()),
            {"parameter", "unit (SI)", "lower", "upper", "when fitting a record (F, V, X: its peak force, peak velocity, amplitude)"}, {}};
    for (const auto& p : m->parameters())
      t.rows.push_back({p.name, p.unit, format_number(p.lower), format_number(p.upper), rule_of(*m, p)});
    std::cout << t.to_markdown() << "\n";
  }
  return 0;
}

}  // namespace dampbench::cli
