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
#include "engine/fit/lssvm_model_file.hpp"
#include "engine/fit/model_file.hpp"
#include "engine/fit/resolve_model.hpp"

namespace dampbench::cli {

void add_evaluate_options(CLI::App* c, EvaluateOptions& eval) {
  c->add_option("--model", eval.model, "model id");
  c->add_option("--laws", eval.laws, "parameter laws (then --params gives their coefficients)");
  c->add_option("--params", eval.params, "parameter values in SI, name=value,...");
  c->add_option("--model-file", eval.model_file,
                "a fitted model (fit --save-model; or lssvm --save-model: its free run) instead of --model, --laws, --params");
  c->add_option("--data", eval.paths, "record(s)")->required();
  add_data_options(c, eval.data);
  c->add_option("--format", eval.format, "md (default) or json");
}

namespace {

/// The model and its parameters from --model-file, or from --model, --laws and --params (all required).
LoadedModel evaluated_model(const EvaluateOptions& o) {
  LoadedModel loaded;
  if (!o.model_file.empty()) {
    if (!o.model.empty() || !o.laws.empty() || !o.params.empty())
      throw InputError("evaluate: --model-file gives the model, its laws and coefficients: drop --model, --laws and --params");
    return load_model_file(o.model_file);
  }
  if (o.model.empty() || o.params.empty()) throw InputError("evaluate: give --model and --params (or --model-file FILE)");
  loaded.model = resolve_model(command_line_model(o.model, o.laws));
  loaded.params = parse_params(*loaded.model.model, o.params);
  return loaded;
}

}  // namespace

/// An LS-SVM model file (lssvm --save-model): each record's metrics of the model's free run, what simulating it
/// means (its first lag samples are the record's measured forces, engine/fit/lssvm_model_file.hpp).
Evaluation evaluate_lssvm(const EvaluateOptions& o) {
  if (!o.model.empty() || !o.laws.empty() || !o.params.empty())
    throw InputError("evaluate: --model-file gives the model: drop --model, --laws and --params");
  const lssvm::Model model = load_lssvm_model_file(o.model_file);
  Evaluation e{"lssvm (free run)", {}, {}};
  for (const std::string& path : o.paths) {
    RecordOptions data = o.data;
    data.path = path;
    for (const Dataset& record : load_records(data, true)) {
      const Signals signals = prepare_signals(record);
      e.names.push_back(record.name);
      e.metrics.push_back(finish_all_metrics(metric_sums(model.simulate(record), signals), signals));
    }
  }
  return e;
}

Evaluation run_evaluate(const EvaluateOptions& o) {
  if (!o.model_file.empty() && is_lssvm_model_file(o.model_file)) return evaluate_lssvm(o);
  const LoadedModel loaded = evaluated_model(o);
  const Model& model = *loaded.model.model;
  const FitRecords records = command_records(model, o.paths, o.records, o.data, "evaluate");
  CandidateBatch batch(model.dim(), 1);
  batch.set_candidate(0, loaded.params);
  Evaluation e{std::string(model.id()), {}, {}};
  const bool from_file = !o.model_file.empty();
  const FittedRange fitted = from_file ? fitted_range_of(loaded) : FittedRange(model, {});
  for (const Signals& s : records.signals) {
    std::vector<MetricRow> row(1);
    BatchEvaluator(model, s).evaluate_all(batch, row);
    e.names.push_back(s.name);
    e.metrics.push_back(row[0]);
    if (from_file) e.extrapolated.push_back(fitted.outside(s.law_variables));
  }
  return e;
}

int evaluate_command(const EvaluateOptions& o) {
  check_format(o.format);
  const Evaluation e = run_evaluate(o);
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  std::vector<std::string> cols{"record"};
  for (Metric m : kAllMetrics) cols.emplace_back(metric_name(m));
  Table t{"evaluate", fmt::format("{} at the given parameters", e.model_id), cols, {}};
  // Keyed by the path given, or by the record's name ("<stem>#k") when a file gave several records.
  const bool by_path = o.paths.size() == e.metrics.size();
  for (std::size_t r = 0; r < e.metrics.size(); ++r) {
    const std::string& key = by_path ? o.paths[r] : e.names[r];
    std::vector<Cell> cells{e.names[r]};
    for (int m = 0; m < kMetricCount; ++m) {
      j[key][std::string(metric_name(kAllMetrics[m]))] = json_number(e.metrics[r][m]);
      cells.push_back(format_number(e.metrics[r][m]));
    }
    t.rows.push_back(std::move(cells));
    if (!e.extrapolated.empty()) {
      const std::string& outside = e.extrapolated[r];
      j[key]["extrapolated"] = outside.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(outside);
      if (!outside.empty())
        t.note += fmt::format("{}{}: {}", t.note.empty() ? "Outside the range the model file was fitted on: " : "; ",
                              e.names[r], outside);
    }
  }
  if (o.format == "json") std::cout << j.dump(2) << "\n";
  else std::cout << t.to_markdown();
  return 0;
}

}  // namespace dampbench::cli
