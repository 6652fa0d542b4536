#include "engine/cli/cli_options.hpp"

#include <cmath>
#include <filesystem>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"

namespace dampbench::cli {

void add_data_options(CLI::App* cmd, RecordOptions& d) {
  cmd->add_option("--units", d.units, "units of the file's columns, e.g. x=mm,F=kN (default: header, else SI)");
  cmd->add_option("--columns", d.columns,
                  "column names of a file without header, e.g. t,x,v,F; or the record's columns picked from a .mat "
                  "file's variables or a rig export's channels, e.g. t=time,x=data[:,0],F=data[:,1:6] (a range: one "
                  "record per column; indices from 0)");
  cmd->add_option("--skip-header", d.skip_header,
                  "lines before a text export's column names (default: a 'Header Size: N' block is detected)");
  cmd->add_option("--scale", d.scale, "gains from the file's values to SI, before --units, e.g. x=10e-3,F=980.665 (V to m, N)");
  cmd->add_option("--split", d.split,
                  "events: one record per test between DAQ Pause/Resume events; nan: between rows of NaN (records "
                  "<file>#1, #2, ...)");
  cmd->add_option("--smooth", d.smooth_samples, "centred moving average of x and F over N samples");
  cmd->add_option("--remove-mean", d.remove_mean, "columns whose mean is removed, e.g. x,F");
  cmd->add_flag("--whole-cycles", d.whole_cycles, "trim to whole cycles of x (first to last upward mean crossing)");
  cmd->add_option("--transform", d.transform, "slider-crank or slider-crank-printed: crfd rig MTS record to angle and torque");
  cmd->add_option("--average-cycles", d.average, "cycles=N,drop=K: average cycles K+1..N-K into one (crfd: cycles=10,drop=3)");
  cmd->add_option("--conditions", d.conditions, "utfsm: operating variables from the file name (25mm0x25Hz0x75A)");
  cmd->add_option("--set", d.set,
                  "operating variables, e.g. I=1,amp=0.01,freq=1 (for parameter laws); one per record of a file of "
                  "several: I=0,0.25,0.5,0.75,1");
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

LoadedModel load_named_model(const ModelByName& o, const std::string& command) {
  if (!o.model_file.empty()) {
    if (!o.model.empty() || !o.fixture.empty() || !o.laws.empty() || !o.params.empty())
      throw InputError(command + ": --model-file gives the model, its laws and coefficients: drop --model, --fixture, "
                                 "--laws and --params");
    return load_model_file(o.model_file);
  }
  if (o.model.empty() == o.fixture.empty())
    throw InputError(command + ": give exactly one of --model M or --fixture NAME (or --model-file FILE)");
  // A fixture is a law model already: --laws applies to --model only.
  LoadedModel m;
  m.model = resolve_model(o.fixture.empty() ? command_line_model(o.model, o.laws) : command_line_model("", "", "", o.fixture));
  m.params = parse_params(*m.model.model, o.params, m.model.defaults);
  return m;
}

void add_model_by_name_options(CLI::App* c, ModelByName& o) {
  c->add_option("--model-file", o.model_file, "the identified model (fit --save-model)");
  c->add_option("--model", o.model, "a model id instead of --model-file (with --laws and --params)");
  c->add_option("--fixture", o.fixture, "a published law fixture instead of --model-file");
  c->add_option("--laws", o.laws, "laws on --model's parameters, e.g. 'c0=poly(I,1)'");
  c->add_option("--params", o.params, "--model's parameter (or law coefficient) values in SI, name=value,...");
}

CommandRange parse_command_range(const std::string& text, std::string_view option) {
  const auto eq = text.find('=');
  const auto colon = text.find(':', eq == std::string::npos ? 0 : eq);
  if (eq == std::string::npos || colon == std::string::npos || eq == 0)
    throw InputError(fmt::format("{}: expected VARIABLE=LOW:HIGH, e.g. I=0:1, got '{}'", option, text));
  CommandRange r;
  r.variable = std::string(trim(std::string_view(text).substr(0, eq)));
  r.low = parse_number(std::string_view(text).substr(eq + 1, colon - eq - 1), fmt::format("{}'s low value", option));
  r.high = parse_number(std::string_view(text).substr(colon + 1), fmt::format("{}'s high value", option));
  return r;
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

void check_output_folder(std::string_view option, const std::string& path) {
  if (!path.empty() && !std::filesystem::is_directory(std::filesystem::absolute(path).parent_path()))
    throw InputError(fmt::format("{}: the folder of '{}' does not exist", option, path));
}

nlohmann::ordered_json json_number(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

}  // namespace dampbench::cli
