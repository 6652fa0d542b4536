#include "engine/cli/fvd_tables.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/statistics.hpp"
#include "models/registry.hpp"

namespace dampbench::cli {
namespace {

const GroupResult& group(const std::vector<GroupResult>& results, const Model* model, int dataset) {
  return *std::find_if(results.begin(), results.end(),
                       [&](const GroupResult& g) { return g.model == model && g.dataset == dataset; });
}

std::vector<std::string> dataset_columns(const Preset& preset, std::string first) {
  std::vector<std::string> cols{std::move(first)};
  for (const auto& d : preset.datasets) cols.push_back(d.name);
  return cols;
}

/// Paper-unit values of parameter j over the runs of one group.
std::vector<double> parameter_over_runs(const GroupResult& g, int j) {
  std::vector<double> values;
  for (const auto& r : g.identification.runs) values.push_back(g.model->to_paper_units(r.best_params)[j]);
  return values;
}

Table metric_table(const Preset& preset, const std::vector<GroupResult>& results, const Model* model, int number) {
  Table t{fmt::format("table{:02}_{}_{}", number, metric_name(preset.metric), model->id()),
          fmt::format("Table {}. {} over {} runs — {}", number, metric_name(preset.metric), preset.runs, model->id()),
          {"Test", "Mean", "Max", "Min", "Std"}, {}};
  for (int d = 0; d < static_cast<int>(preset.datasets.size()); ++d) {
    std::vector<double> values;
    for (const auto& r : group(results, model, d).identification.runs) values.push_back(r.best_value);
    const Summary s = summarize(values);
    t.rows.push_back({preset.datasets[d].name, format_number(s.mean), format_number(s.max), format_number(s.min),
                      format_number(s.std)});
  }
  return t;
}

Table parameter_table(const Preset& preset, const std::vector<GroupResult>& results, const Model* model, int number) {
  Table t{fmt::format("table{:02}_params_{}", number, model->id()),
          fmt::format("Table {}. Identified parameters over {} runs (paper units) — {}", number, preset.runs, model->id()),
          dataset_columns(preset, "Parameter"), {}};
  const auto params = model->parameters();
  for (int j = 0; j < model->dim(); ++j) {
    std::vector<Summary> per_test;
    for (int d = 0; d < static_cast<int>(preset.datasets.size()); ++d)
      per_test.push_back(summarize(parameter_over_runs(group(results, model, d), j)));
    const std::pair<const char*, double Summary::*> stats[] = {
        {"mean", &Summary::mean}, {"max", &Summary::max}, {"min", &Summary::min}, {"std", &Summary::std}};
    for (const auto& [label, field] : stats) {
      std::vector<std::string> row{fmt::format("{}({}) [{}]", params[j].name, label, params[j].paper_unit)};
      for (const Summary& s : per_test) row.push_back(format_number(s.*field));
      t.rows.push_back(std::move(row));
    }
  }
  return t;
}

Table variability_table(const Preset& preset, const std::vector<GroupResult>& results, const Model* model, int number) {
  Table t{fmt::format("table{:02}_variability_{}", number, model->id()),
          fmt::format("Table {}. Parameter variability across tests — {}", number, model->id()),
          {"Parameter", "p_mean", "delta_p", "delta_p/p_mean"}, {}};
  const auto params = model->parameters();
  for (int j = 0; j < model->dim(); ++j) {
    std::vector<double> test_means;
    for (int d = 0; d < static_cast<int>(preset.datasets.size()); ++d)
      test_means.push_back(summarize(parameter_over_runs(group(results, model, d), j)).mean);
    const Summary s = summarize(test_means);
    const double delta = s.max - s.min;
    t.rows.push_back({fmt::format("{} [{}]", params[j].name, params[j].paper_unit), format_number(s.mean),
                      format_number(delta), s.mean != 0 ? format_number(delta / s.mean) : "-"});
  }
  return t;
}

Table ranking_table(const Preset& preset, const std::vector<GroupResult>& results) {
  auto cols = dataset_columns(preset, "Model");
  cols.push_back("mean of best");
  Table t{"ranking", fmt::format("Best {} per model and test (lower is better)", metric_name(preset.metric)), cols, {}};
  for (const auto& id : preset.models) {
    const Model* model = &find_model(id);
    std::vector<std::string> row{id};
    double sum = 0;
    for (int d = 0; d < static_cast<int>(preset.datasets.size()); ++d) {
      const auto& ident = group(results, model, d).identification;
      const double best = ident.runs[ident.best_run()].best_value;
      sum += best;
      row.push_back(format_number(best));
    }
    row.push_back(format_number(sum / static_cast<double>(preset.datasets.size())));
    t.rows.push_back(std::move(row));
  }
  return t;
}

}  // namespace

std::vector<Table> fvd_tables(const Preset& preset, const std::vector<GroupResult>& results) {
  std::vector<Table> tables;
  std::vector<const Model*> models;
  for (const auto& id : preset.models) models.push_back(&find_model(id));
  // The paper numbers its tables 3–6, 7–10, 11–14 for its four models; extra models continue the count.
  const int n = static_cast<int>(models.size());
  for (int i = 0; i < n; ++i) tables.push_back(metric_table(preset, results, models[i], 3 + i));
  for (int i = 0; i < n; ++i) tables.push_back(parameter_table(preset, results, models[i], 3 + n + i));
  for (int i = 0; i < n; ++i) tables.push_back(variability_table(preset, results, models[i], 3 + 2 * n + i));
  tables.push_back(ranking_table(preset, results));
  return tables;
}

std::string fvd_summary(const Preset& preset, const std::vector<Table>& tables) {
  std::string out = fmt::format("# {}\n\nProduced tables and the fvd paper's tables they reproduce:\n\n", preset.title);
  out += "| file | paper | content |\n|---|---|---|\n";
  for (const auto& t : tables) {
    const bool numbered = t.id.rfind("table", 0) == 0;
    out += fmt::format("| {}.csv | {} | {} |\n", t.id, numbered ? "Table " + std::to_string(std::stoi(t.id.substr(5, 2))) : "(beyond the paper)",
                       t.title);
  }
  out += fmt::format("\nDatasets:\n\n");
  for (const auto& d : preset.datasets) out += fmt::format("- {}: {} ({})\n", d.name, d.label, d.data.path);
  return out;
}

}  // namespace dampbench::cli
