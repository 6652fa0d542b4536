#include "engine/cli/fit_run.hpp"

#include <iostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/cli/cli_options.hpp"
#include "engine/cli/fit_held_out.hpp"
#include "engine/cli/fit_report.hpp"
#include "engine/common/error.hpp"
#include "engine/common/statistics.hpp"
#include "engine/common/table.hpp"
#include "engine/fit/fit.hpp"
#include "engine/fit/law_selection.hpp"
#include "engine/fit/model_file.hpp"
#include "engine/fit/model_file_of_fit.hpp"

namespace dampbench::cli {
namespace {

/// Progress lines (per-record fits, law choices, the automatic budget's rounds) go to stderr, apart from the
/// output.
void tell_stderr(const std::string& line) { std::cerr << line << std::endl; }

}  // namespace

FitTables fit_tables(const PreparedFit& p, const FitOutcome& fit, const std::string& metric_option) {
  const Model& model = *p.model.model;
  const RunResult& best = fit.best();
  const Identifiability& ident = *fit.identifiability;
  FitTables t;
  std::vector<double> values;
  for (const auto& r : fit.identification.runs) {
    values.push_back(r.best_value);
    t.evaluations += r.evaluations;
  }
  t.spread = summarize(values);
  const auto params = model.parameters();
  const auto paper = model.to_paper_units(best.best_params);
  t.params = {"best_params", fmt::format("{} on {} — best of {} runs", model.id(), p.records.names, p.plan.runs),
              {"parameter", "value (SI)", "unit", "value (paper units)", "paper unit", "std. error (SI)", "rel. error",
               "identifiable"},
              {}};
  for (int i = 0; i < model.dim(); ++i) {
    std::string flags;
    for (const auto& f : ident.flags[i]) flags += (flags.empty() ? "" : "; ") + f;
    t.params.rows.push_back({params[i].name, format_number(best.best_params[i]), params[i].unit, format_number(paper[i]),
                             params[i].paper_unit, format_number(ident.std_error[i]),
                             format_number(ident.relative_error[i]), flags.empty() ? "yes" : "NO: " + flags});
  }
  t.metrics = {"metrics", "Metrics of the best run", {"metric", "value"}, {}};
  for (int i = 0; i < kMetricCount; ++i)
    t.metrics.rows.push_back({std::string(metric_name(kAllMetrics[i])), format_number(best.best_metrics[i])});
  const Summary& s = t.spread;
  t.runs = {"runs", fmt::format("{} over {} runs", metric_option, s.count), {"best", "worst", "mean", "std"},
            {{format_number(s.min), format_number(s.max), format_number(s.mean), format_number(s.std)}}};
  return t;
}

namespace {

nlohmann::ordered_json convergence_json(const Convergence& c) {
  const ConvergenceRule rule;
  return {{"converged", c.converged},
          {"verdict", c.verdict()},
          {"runs_agree", c.runs_agree},
          {"stalled", c.stalled},
          {"median_above_best_rel", json_number(c.median_above_best_rel)},
          {"worst_above_best_rel", json_number(c.worst_above_best_rel)},
          {"late_gain_rel", json_number(c.late_gain_rel)},
          {"unconfirmed", c.unconfirmed},
          {"rule", {{"agree_rel", rule.agree_rel}, {"late_gain_rel", rule.late_gain_rel},
                    {"late_fraction", rule.late_fraction}, {"abs_tol", rule.abs_tol}}}};
}

nlohmann::ordered_json identifiability_json(const Model& model, const Identifiability& ident) {
  const auto params = model.parameters();
  nlohmann::ordered_json per = nlohmann::ordered_json::object();
  for (int i = 0; i < model.dim(); ++i)
    per[params[i].name] = {{"std_error", json_number(ident.std_error[i])},
                           {"relative_error", json_number(ident.relative_error[i])},
                           {"flags", ident.flags[i]}};
  nlohmann::ordered_json corr = nlohmann::ordered_json::array();
  for (const auto& row : ident.correlation) {
    nlohmann::ordered_json r = nlohmann::ordered_json::array();
    for (double c : row) r.push_back(json_number(c));
    corr.push_back(r);
  }
  return {{"identifiable", ident.all_identifiable()}, {"parameters", per}, {"correlation", corr}};
}

/// Each record's operating variables with their sources: [{"record": name, "variables": operating_json}, ...].
nlohmann::ordered_json operating_records_json(const FitRecords& records) {
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  for (const Signals& s : records.signals) all.push_back({{"record", s.name}, {"variables", operating_json(s)}});
  return all;
}

nlohmann::ordered_json selection_json(const LawSelection& s) {
  nlohmann::ordered_json choices = nlohmann::ordered_json::object();
  for (std::size_t j = 0; j < s.parameters.size(); ++j) choices[s.parameters[j]] = s.chosen[j].text();
  nlohmann::ordered_json folds = nlohmann::ordered_json::array();
  for (const auto& row : s.folds.rows)
    folds.push_back({{"left_out", row[0].text}, {"records", std::stoi(row[1].text)},
                     {"shared", json_number(*row[2].value)}, {"chosen", json_number(*row[3].value)}});
  return {{"laws", s.laws}, {"per_parameter", choices}, {"score", json_number(s.score)},
          {"shared_score", json_number(s.shared_score)}, {"sets_scored", s.scored}, {"folds", folds},
          {"wall_time_s", s.effort.wall_time_s}, {"evaluations", s.effort.evaluations},
          {"candidate_samples", s.effort.candidate_samples}, {"folds_note", s.folds.note}};
}

nlohmann::ordered_json budget_json(const FitOutcome& fit) {
  if (!fit.auto_budget) return {{"kind", "fixed"}};
  const AutoBudgetReport& b = *fit.auto_budget;
  return {{"kind", "auto"}, {"rounds", b.iterations.size()}, {"iterations", b.iterations},
          {"evaluations", b.evaluations}, {"cap", b.cap}, {"stop", b.stop},
          {"last_restart_rel", json_number(b.last_restart_rel)},
          {"second_opinion",
           b.second_opinion_optimizer ? nlohmann::ordered_json(b.second_opinion_label()) : nlohmann::ordered_json()},
          {"second_opinion_best", json_number(b.second_opinion_best)},
          {"second_opinion_rel", json_number(b.second_opinion_rel)},
          {"second_opinion_evaluations", b.second_opinion_evaluations}};
}

}  // namespace

nlohmann::ordered_json fit_json(const FitOptions& o, const FitRun& run) {
  const PreparedFit& p = run.prepared;
  const FitOutcome& fit = run.outcome;
  const FitTables t = fit_tables(p, fit, o.fit.metric);
  const LawSelection* selection = p.auto_laws ? &run.selection : nullptr;
  const Model& model = *p.model.model;
  const RunResult& best = fit.best();
  const Summary& s = t.spread;
  nlohmann::ordered_json j;
  j["model"] = model.id();
  if (!o.fit.paths.empty()) {
    j["data"] = o.fit.paths;
  } else {
    std::vector<std::string> names;
    for (const Dataset& d : o.fit.records) names.push_back(d.name);
    j["data"] = names;
  }
  j["samples"] = p.records.samples();
  const std::string laws = selection ? selection->laws : o.fit.model.laws;
  if (!laws.empty()) j["laws"] = laws;
  if (selection) j["law_selection"] = selection_json(*selection);
  j["metric"] = o.fit.metric;
  j["optimizer"] = {{"name", p.plan.optimizer}, {"population", p.plan.population}, {"iterations", p.plan.iterations},
                    {"settings", p.optimizer.settings}};
  j["seed"] = o.fit.seed;
  j["precision"] = search_precision_name(p.search_precision);
  const auto named = [&](const std::vector<double>& values) {
    nlohmann::ordered_json named_values = nlohmann::ordered_json::object();
    for (int i = 0; i < model.dim(); ++i) named_values[model.parameters()[i].name] = values[i];
    return named_values;
  };
  j["best_params"] = named(best.best_params);
  // The box searched: the model's defaults scaled to the records (engine/model/bounds.hpp), then --bounds.
  j["bounds"] = {{"lower", named(fit.bounds.lower)}, {"upper", named(fit.bounds.upper)}};
  nlohmann::ordered_json metrics = nlohmann::ordered_json::object();
  for (int i = 0; i < kMetricCount; ++i) metrics[std::string(metric_name(kAllMetrics[i]))] = json_number(best.best_metrics[i]);
  j["metrics"] = metrics;
  j["runs"] = {{"count", s.count}, {"best", json_number(s.min)}, {"worst", json_number(s.max)},
               {"mean", json_number(s.mean)}, {"std", json_number(s.std)}};
  nlohmann::ordered_json each = nlohmann::ordered_json::array();
  for (const RunResult& r : fit.identification.runs)
    each.push_back({{"best_value", json_number(r.best_value)}, {"evaluations", r.evaluations},
                    {"stop", r.stop_reason}, {"best_params", named(r.best_params)}});
  j["run_results"] = each;
  j["convergence"] = convergence_json(fit.convergence);
  j["budget"] = budget_json(fit);
  // Best-so-far history of every run: [evaluations, value] where it improved, and at its end.
  nlohmann::ordered_json history = nlohmann::ordered_json::array();
  for (const RunResult& r : fit.identification.runs) {
    nlohmann::ordered_json points = nlohmann::ordered_json::array();
    for (const TracePoint& pt : improvement_points(r)) points.push_back({pt.evaluations, json_number(pt.value)});
    history.push_back(points);
  }
  j["history"] = history;
  j["identifiability"] = identifiability_json(model, *fit.identifiability);
  j["operating"] = operating_records_json(p.records);
  if (run.held_out) j["held_out"] = held_out_json(*run.held_out, model);
  j["evaluations"] = t.evaluations;
  j["wall_time_s"] = fit.identification.wall_time_s;
  j["candidate_samples_per_s"] = fit.identification.candidate_samples / fit.identification.wall_time_s;
  return j;
}

FitRun run_fit_options(const FitOptions& o) {
  check_format(o.format);
  check_output_folder("--report", o.report);  // before the fit, not after it
  check_output_folder("--save-model", o.save_model);
  FitRun run = fit_and_predict(o.fit, o.held_out, tell_stderr);
  const PreparedFit& prepared = run.prepared;
  const FitOutcome& fit = run.outcome;
  const FitRequest request = prepared.request();
  if (!o.report.empty()) {
    const FitTables tables = fit_tables(prepared, fit, o.fit.metric);
    FitReport report{prepared.model.model, prepared.plan.optimizer,
                     std::string(DAMPBENCH_VERSION) + " (" + DAMPBENCH_BUILD_FLAGS + ")", prepared.metric,
                     request.records, &fit.identification, fit.convergence.unconfirmed,
                     {tables.params, tables.metrics, tables.runs},
                     run.held_out ? &*run.held_out : nullptr, o.held_out.folds};
    write_fit_report(o.report, report);
  }
  if (!o.save_model.empty())
    write_model_file(o.save_model, model_file_of_fit(run.spec, prepared, fit, DAMPBENCH_VERSION));
  return run;
}

}  // namespace dampbench::cli
