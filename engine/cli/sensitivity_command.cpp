#include "engine/cli/sensitivity_command.hpp"

#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/cli/cli_options.hpp"
#include "engine/common/error.hpp"
#include "engine/common/table.hpp"
#include "engine/evaluation/sensitivity.hpp"
#include "engine/fit/resolve_model.hpp"
#include "engine/record/excitation.hpp"
#include "engine/record/record_options.hpp"

namespace dampbench::cli {

void add_sensitivity_options(CLI::App* c, SensitivityOptions& sens) {
  c->add_option("--model", sens.model, "model id")->required();
  c->add_option("--params", sens.params, "parameter values in SI (repeat for several cases)")->required();
  c->add_option("--sine", sens.sines, "sinusoid input (once, or once per --params)");
  c->add_option("--data", sens.paths, "record input instead of --sine (once, or once per --params)");
  add_data_options(c, sens.data);
  c->add_option("--points", sens.points, "grid points per parameter (default 21)");
  c->add_option("--range", sens.range, "relative half-range (default 0.5 = ±50 %)");
  c->add_option("--objective", sens.objective, "rms (of the model force, default) or a metric name");
  c->add_flag("--normalized", sens.normalized, "report S_z·|z| (elasticity) instead of S_z as printed");
  c->add_option("--format", sens.format, "md (default) or json");
}

int sensitivity_command(const SensitivityOptions& o) {
  check_format(o.format);
  const ResolvedModel resolved = resolve_model(command_line_model(o.model));
  const Model& model = *resolved.model;
  const std::size_t cases = o.params.size();
  const auto& inputs = o.sines.empty() ? o.paths : o.sines;
  if (cases == 0) throw InputError("sensitivity: give --params (once per case)");
  if (o.sines.empty() == o.paths.empty())
    throw InputError("sensitivity: give --sine or --data (not both), once or once per --params");
  if (inputs.size() != 1 && inputs.size() != cases)
    throw InputError(fmt::format("sensitivity: {} --params but {} inputs; give one input or one per case", cases, inputs.size()));
  SensitivitySettings settings;
  settings.points = o.points;
  settings.range = o.range;
  settings.normalized = o.normalized;
  if (o.objective != "rms") settings.metric = parse_metric(o.objective);

  std::vector<std::vector<double>> values;
  std::vector<Sensitivity> results;
  for (std::size_t c = 0; c < cases; ++c) {
    const std::string& input = inputs[inputs.size() == 1 ? 0 : c];
    Dataset data;
    if (o.sines.empty()) {
      RecordOptions d = o.data;
      d.path = input;
      data = load_record(d, settings.metric.has_value());
    } else {
      data = make_sine(parse_sine_option(input));
    }
    values.push_back(parse_params(model, o.params[c]));
    results.push_back(differential_sensitivity(model, values.back(), prepare_signals(data), settings));
  }
  const auto params = model.parameters();
  std::vector<std::string> cols{"parameter"};
  for (std::size_t c = 0; c < cases; ++c) {
    cols.push_back(fmt::format("value ({})", c + 1));
    cols.push_back(fmt::format("S_z ({})", c + 1));
    cols.push_back(fmt::format("SP_z % ({})", c + 1));
  }
  cols.push_back("SP_z % (mean)");
  Table t{"sensitivity",
          fmt::format("Differential sensitivity of {} (crfd eqs. 4.1-4.3), f = {}, ±{:g} %, {} points{}", model.id(),
                      o.objective == "rms" ? "RMS of the model force" : o.objective, 100 * o.range, o.points,
                      o.normalized ? ", S_z·|z|" : ""),
          cols, {}};
  for (int j = 0; j < model.dim(); ++j) {
    std::vector<Cell> row{params[j].name};
    double mean = 0;
    for (std::size_t c = 0; c < cases; ++c) {
      row.push_back(format_number(values[c][j]));
      row.push_back(format_number(results[c].S[j]));
      row.push_back(fmt::format("{:.2f}", results[c].SP[j]));
      mean += results[c].SP[j] / static_cast<double>(cases);
    }
    row.push_back(fmt::format("{:.2f}", mean));
    t.rows.push_back(std::move(row));
  }
  if (o.format == "json") {
    nlohmann::ordered_json j;
    j["model"] = model.id();
    for (int p = 0; p < model.dim(); ++p) {
      double mean = 0;
      for (const auto& r : results) mean += r.SP[p] / static_cast<double>(cases);
      j["SP_mean_percent"][params[p].name] = mean;
    }
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << t.to_markdown();
  }
  return 0;
}

}  // namespace dampbench::cli
