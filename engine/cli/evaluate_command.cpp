#include "engine/cli/evaluate_command.hpp"

#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/cli/cli_options.hpp"
#include "engine/common/error.hpp"
#include "engine/common/table.hpp"
#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/fit/fit_records.hpp"
#include "engine/fit/model_file.hpp"
#include "engine/fit/resolve_model.hpp"

namespace dampbench::cli {

void add_evaluate_options(CLI::App* c, EvaluateOptions& eval) {
  c->add_option("--model", eval.model, "model id");
  c->add_option("--laws", eval.laws, "parameter laws (then --params gives their coefficients)");
  c->add_option("--params", eval.params, "parameter values in SI, name=value,...");
  c->add_option("--model-file", eval.model_file, "a fitted model (fit --save-model) instead of --model, --laws, --params");
  c->add_option("--data", eval.paths, "record(s)")->required();
  add_data_options(c, eval.data);
  c->add_option("--format", eval.format, "md (default) or json");
}

int evaluate_command(const EvaluateOptions& o) {
  check_format(o.format);
  LoadedModel loaded;
  if (!o.model_file.empty()) {
    if (!o.model.empty() || !o.laws.empty() || !o.params.empty())
      throw InputError("evaluate: --model-file gives the model, its laws and coefficients: drop --model, --laws and --params");
    loaded = load_model_file(o.model_file);
  } else {
    if (o.model.empty() || o.params.empty())
      throw InputError("evaluate: give --model and --params (or --model-file FILE)");
    loaded.model = resolve_model(command_line_model(o.model, o.laws));
    loaded.params = parse_params(*loaded.model.model, o.params);
  }
  const Model& model = *loaded.model.model;
  const std::vector<double>& params = loaded.params;
  if (o.paths.empty()) throw InputError("evaluate: give at least one --data FILE");
  const FitRecords records = load_fit_records(model, o.paths, o.data);
  CandidateBatch batch(model.dim(), 1);
  batch.set_candidate(0, params);
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  std::vector<std::string> cols{"record"};
  for (Metric m : kAllMetrics) cols.emplace_back(metric_name(m));
  Table t{"evaluate", fmt::format("{} at the given parameters", model.id()), cols, {}};
  for (std::size_t r = 0; r < records.signals.size(); ++r) {
    const Signals& s = records.signals[r];
    std::vector<MetricRow> row(1);
    BatchEvaluator(model, s).evaluate_all(batch, row);
    std::vector<Cell> cells{s.name};
    for (int m = 0; m < kMetricCount; ++m) {
      j[o.paths[r]][std::string(metric_name(kAllMetrics[m]))] = json_number(row[0][m]);
      cells.push_back(format_number(row[0][m]));
    }
    t.rows.push_back(std::move(cells));
  }
  if (o.format == "json") std::cout << j.dump(2) << "\n";
  else std::cout << t.to_markdown();
  return 0;
}

}  // namespace dampbench::cli
