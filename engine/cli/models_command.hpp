#pragma once
// `dampbench models`: every model with its parameters, units and default bounds (md or json).
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/record/signals.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

void add_models_options(CLI::App* cmd, std::string& format);

/// What `models --format json` prints under "models": by model id, its citation, law and parameters (name, unit,
/// lower, upper, paper_unit and record_rule where one applies). The bounds are those for fitting `records`
/// (default_bounds(model, records)): with none, the fixed defaults (the Python module's models too).
nlohmann::ordered_json models_json(std::span<const Signals* const> records = {});

int models_command(const std::string& format);

}  // namespace dampbench::cli
