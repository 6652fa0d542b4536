#include "engine/cli/fit_held_out.hpp"

#include <algorithm>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "engine/cli/cli_options.hpp"

namespace dampbench::cli {

void add_held_out_options(CLI::App* c, HeldOutSpec& spec) {
  c->add_option("--predict", spec.predict,
                "records predicted with the best parameters of the fit on the --data records (held out)");
  c->add_option("--folds", spec.folds,
                "fit and predict folds of the --data records: leave-one:VAR (e.g. leave-one:I) or leave-setting");
  c->add_option("--reference", spec.reference,
                "per-file: fit the base model (every parameter free) to each record alone and show the ratio");
}

namespace {

std::string joined(const std::vector<std::string>& names, std::string_view separator = ", ") {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : std::string(separator)) + n;
  return s;
}

Table folds_table(const HeldOut& h, std::string_view rule, std::string_view metric) {
  std::string what = rule.empty() ? "" : std::string(rule);
  if (!h.folds.empty() && h.folds.back().fold.name == "all") what += what.empty() ? "--predict" : " and --predict";
  Table t{"held_out_folds", fmt::format("Folds ({}): each fitted on its records, predicting the others", what),
          {"fold", "fitted on", "predicts", fmt::format("fit {}", metric), "verdict"}, {}};
  for (const FoldFit& f : h.folds)
    t.rows.push_back({f.fold.name, joined(f.fit_names), joined(f.predict_names), number_cell(f.fit_value), f.verdict});
  return t;
}

Table records_table(const HeldOut& h, std::string_view metric, std::string_view base_id) {
  Table t{"held_out", "", {"role", "fold", "record", std::string(metric)}, {}};
  t.title = h.reference ? fmt::format("{} of each record beside its per-file fit ({} on the record alone, fit's "
                                      "defaults)",
                                      metric, base_id)
                        : fmt::format("{} of each held-out record", metric);
  if (h.reference) {
    t.columns.push_back(fmt::format("per-file {}", metric));
    t.columns.emplace_back("ratio");
  }
  std::vector<std::string> unconverged;  // each per-file fit once, though its record may be fitted and held out
  std::vector<std::string> failed, extrapolated;
  for (const auto* rows : {&h.fitted, &h.held_out})
    for (const RecordError& e : *rows) {
      if (!e.failure.empty()) failed.push_back(fmt::format("{} (fold {}) {}", e.record, e.fold, e.failure));
      if (!e.extrapolated.empty()) extrapolated.push_back(fmt::format("{} (fold {}): {}", e.record, e.fold, e.extrapolated));
      std::vector<Cell> row{e.role, e.fold, e.record, number_cell(e.metric)};
      if (h.reference) {
        row.push_back(number_cell(*e.per_file));
        row.push_back(number_cell(e.ratio()));
        const std::string item = fmt::format("{} ({})", e.record, *e.per_file_verdict);
        const bool listed = std::find(unconverged.begin(), unconverged.end(), item) != unconverged.end();
        if (*e.per_file_verdict != "converged" && !listed) unconverged.push_back(item);
      }
      t.rows.push_back(std::move(row));
    }
  if (!unconverged.empty())
    t.note = "Per-file fits NOT CONVERGED (their ratios are not to be trusted): " + joined(unconverged);
  if (!failed.empty())
    t.note += fmt::format("{}NO FINITE {} (left out of the means): {}", t.note.empty() ? "" : " ", metric,
                          joined(failed, "; "));
  if (!extrapolated.empty())
    t.note += fmt::format("{}Extrapolated (a law variable outside the range of the records its fold is fitted on): {}",
                          t.note.empty() ? "" : " ", joined(extrapolated, "; "));
  return t;
}

Table summary_table(const HeldOut& h, std::string_view metric) {
  Table t{"held_out_summary", "Means by role", {"role", "records", fmt::format("mean {}", metric)}, {}};
  if (h.reference)
    for (const char* c : {"mean per-file", "ratio of means", "worst ratio", "worst record"}) t.columns.emplace_back(c);
  const bool any_failed = h.fitted_summary.failed > 0 || h.held_out_summary.failed > 0;
  if (any_failed) {
    t.columns.insert(t.columns.begin() + 2, fmt::format("no finite {}", metric));
    t.note = "The means leave out the records without a finite metric (see the records' note).";
  }
  auto add = [&](const std::string& role, const ErrorSummary& s) {
    if (s.count == 0) return;
    std::vector<Cell> row{role, number_cell(s.count), number_cell(s.mean)};
    if (any_failed) row.insert(row.begin() + 2, number_cell(s.failed));
    if (h.reference) {
      row.push_back(number_cell(s.mean_per_file));
      row.push_back(number_cell(s.ratio_of_means));
      row.push_back(number_cell(s.worst_ratio));
      row.emplace_back(s.worst_record);
    }
    t.rows.push_back(std::move(row));
  };
  add("fitted", h.fitted_summary);
  add("held out", h.held_out_summary);
  add("held out by the folds", h.folds_summary);
  add("held out by the fit on every --data record", h.predicted_summary);
  return t;
}

nlohmann::ordered_json optional_number(const std::optional<double>& v) {
  return v ? json_number(*v) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json summary_json(const ErrorSummary& s) {
  return {{"count", s.count},
          {"failed", s.failed},
          {"mean", json_number(s.mean)},
          {"mean_per_file", json_number(s.mean_per_file)},
          {"ratio_of_means", json_number(s.ratio_of_means)},
          {"worst_ratio", json_number(s.worst_ratio)},
          {"worst_record",
           s.worst_record.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(s.worst_record)}};
}

}  // namespace

std::vector<Table> held_out_tables(const HeldOut& h, std::string_view rule, std::string_view base_id) {
  const std::string metric(metric_name(h.metric));
  std::vector<Table> tables;
  if (!h.folds.empty()) tables.push_back(folds_table(h, rule, metric));
  tables.push_back(records_table(h, metric, base_id));
  tables.push_back(summary_table(h, metric));
  return tables;
}

nlohmann::ordered_json held_out_json(const HeldOut& h, const Model& model) {
  const std::string base_id(per_file_model(model).id());
  nlohmann::ordered_json j;
  j["metric"] = std::string(metric_name(h.metric));
  j["reference"] = h.reference ? nlohmann::ordered_json{{"kind", "per-file"}, {"model", base_id}}
                               : nlohmann::ordered_json(nullptr);
  nlohmann::ordered_json folds = nlohmann::ordered_json::array();
  for (const FoldFit& f : h.folds) {
    nlohmann::ordered_json params = nlohmann::ordered_json::object();
    for (std::size_t i = 0; i < f.best_params.size(); ++i) params[f.parameter_names[i]] = f.best_params[i];
    folds.push_back({{"name", f.fold.name}, {"model", f.model_id}, {"fit", f.fit_names}, {"predict", f.predict_names},
                     {"fit_value", json_number(f.fit_value)}, {"converged", f.converged}, {"verdict", f.verdict},
                     {"best_params", params}});
  }
  j["folds"] = folds;
  nlohmann::ordered_json records = nlohmann::ordered_json::array();
  for (const auto* rows : {&h.fitted, &h.held_out})
    for (const RecordError& e : *rows)
      records.push_back({{"role", e.role}, {"fold", e.fold}, {"record", e.record}, {"metric", json_number(e.metric)},
                         {"per_file", optional_number(e.per_file)},
                         {"per_file_verdict", e.per_file_verdict ? nlohmann::ordered_json(*e.per_file_verdict)
                                                                 : nlohmann::ordered_json(nullptr)},
                         {"ratio", e.per_file ? json_number(e.ratio()) : nlohmann::ordered_json(nullptr)},
                         {"failure", e.failure.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(e.failure)},
                         {"extrapolated", e.extrapolated.empty() ? nlohmann::ordered_json(nullptr)
                                                                 : nlohmann::ordered_json(e.extrapolated)}});
  j["records"] = records;
  j["summary"] = {{"fitted", summary_json(h.fitted_summary)}, {"held_out", summary_json(h.held_out_summary)}};
  if (h.folds_summary.count > 0) {
    j["summary"]["held_out_by_folds"] = summary_json(h.folds_summary);
    j["summary"]["held_out_by_all"] = summary_json(h.predicted_summary);
  }
  return j;
}

}  // namespace dampbench::cli
