#include "engine/cli/cli_options.hpp"

#include <cmath>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"

namespace dampbench::cli {

void add_data_options(CLI::App* cmd, RecordOptions& d) {
  cmd->add_option("--units", d.units, "units of the file's columns, e.g. x=mm,F=kN (default: header, else SI)");
  cmd->add_option("--columns", d.columns, "column names of a file without header, e.g. t,x,v,F");
  cmd->add_option("--transform", d.transform, "slider-crank or slider-crank-printed: crfd rig MTS record to angle and torque");
  cmd->add_option("--average-cycles", d.average, "cycles=N,drop=K: average cycles K+1..N-K into one (crfd: cycles=10,drop=3)");
  cmd->add_option("--conditions", d.conditions, "utfsm: operating variables from the file name (25mm0x25Hz0x75A)");
  cmd->add_option("--set", d.set, "operating variables, e.g. I=1,amp=0.01,freq=1 (for parameter laws)");
  cmd->add_flag("--periodic", d.periodic,
                "a system record (t,y,u) is one period of a periodic input and y its steady response (default: the "
                "structure starts from rest)");
}

ModelChoice command_line_model(const std::string& model, const std::string& laws, const std::string& bounds,
                               const std::string& fixture) {
  ModelChoice c;
  c.model = model;
  c.fixture = fixture;
  c.laws = laws;
  c.bounds = bounds;
  c.option_prefix = "--";
  return c;
}

std::vector<double> parse_params(const Model& model, const std::string& text, const std::vector<double>& defaults) {
  std::vector<double> values = defaults.empty() ? std::vector<double>(model.dim(), std::nan("")) : defaults;
  for (const auto& [name, value] : parse_key_values(text, "--params"))
    values[model.parameter_index(name)] = parse_number(value, "--params " + name);
  for (int j = 0; j < model.dim(); ++j)
    if (std::isnan(values[j]))
      throw InputError(fmt::format("--params: missing parameter '{}' of model {}", model.parameters()[j].name, model.id()));
  return values;
}

void check_format(const std::string& format) {
  if (format != "md" && format != "json")
    throw InputError(fmt::format("--format: expected md or json, got '{}'", format));
}

nlohmann::ordered_json json_number(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

}  // namespace dampbench::cli
