#include "engine/cli/fit_command.hpp"

#include <algorithm>
#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/cli/cli_options.hpp"
#include "engine/cli/fit_held_out.hpp"
#include "engine/cli/fit_report.hpp"
#include "engine/common/error.hpp"
#include "engine/common/statistics.hpp"
#include "engine/common/table.hpp"
#include "engine/fit/fit.hpp"
#include "engine/fit/fit_defaults.hpp"
#include "engine/fit/law_selection.hpp"
#include "engine/fit/model_file.hpp"
#include "engine/fit/model_file_of_fit.hpp"

namespace dampbench::cli {

void add_fit_options(CLI::App* c, FitOptions& o) {
  FitSpec& fit = o.fit;
  fit.model.option_prefix = "--";
  c->add_option("--model", fit.model.model, "model id")->required();
  c->add_option("--data", fit.paths, "test record (CSV); repeat for several conditions fitted at once")->required();
  c->add_option("--laws", fit.model.laws,
                "parameter laws in operating variables, e.g. 'c0=poly(I,1);alpha=poly(I,1)', or 'auto' to choose them "
                "by leave-one-setting-out folds of the records");
  add_data_options(c, fit.data);
  c->add_option("--metric", fit.metric, metric_names() + " (default of_abs)");
  c->add_option("--optimizer", fit.optimizer,
                "pso, ga, aga, de, cmaes, ga-lm, ... (default: ga-lm for models with internal states, else pso)");
  c->add_option("--optimizer-settings", fit.optimizer_settings, "algorithm settings, e.g. pc=0.6,pm=0.03 or variant=constriction");
  c->add_option("--pop", fit.population, "population size (default 24 for ga-lm on internal states, else 50)");
  c->add_option("--iters", fit.iterations, "iterations (default 30 for ga-lm on internal states, else 100)");
  c->add_option("--runs", fit.runs, "independent runs (default 4 for internal states, else 50)");
  c->add_option("--budget", fit.budget,
                "auto (default unless --pop, --iters or --runs is given: restart the runs with twice the iterations "
                "until they converge and a second opinion finds nothing lower) or fixed");
  c->add_option("--max-evals", fit.max_evaluations,
                "cap of the automatic budget, in evaluations over every run and restart (default 64 x the first "
                "round's evaluations, plus the second opinion's)");
  c->add_option("--max-seconds", fit.max_seconds,
                "wall-clock cap of the automatic budget (a fit it stops is not reproducible bit for bit)");
  c->add_option("--seed", fit.seed, "seed (default 1)");
  c->add_option("--precision", fit.precision,
                "mixed (default): the population search in single-precision lanes (twice the lanes per vector) for the "
                "models that have them, local stages and every reported value in double; or double throughout");
  c->add_option("--bounds", fit.model.bounds, "bounds in SI, name=lo:hi,...");
  c->add_option("--start", fit.start,
                "per-file: start the search from the laws fitted to each record's own fit; or a model file (--save-model) of "
                "the same model and laws: start from its coefficients (member 0 of each run, clamped into the box)");
  c->add_option("--format", o.format, "md (default) or json");
  c->add_option("--report", o.report, "also write an HTML report (loops, convergence, runs) to this file");
  c->add_option("--save-model", o.save_model, "also write the fitted model as JSON (for evaluate/simulate --model-file)");
  add_held_out_options(c, o.held_out);
}

namespace {

/// Progress lines (per-record fits, law choices, the automatic budget's rounds) go to stderr, apart from the
/// output.
void tell_stderr(const std::string& line) { std::cerr << line << std::endl; }

/// What a fit prints: the best run's parameters with their identifiability, its metrics, and the spread of runs.
struct FitTables {
  Table params, metrics, runs;
  Summary spread;
  long long evaluations = 0;
};

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

/// One line per record: "- name: I = 0.5 (--set), amp = 0.01 (record estimate (half peak-to-peak)), ...".
void print_operating(const FitRecords& records) {
  std::cout << "Operating variables (source):\n";
  for (const Signals& s : records.signals) {
    std::string line;
    const nlohmann::ordered_json variables = operating_json(s);
    for (const auto& [name, v] : variables.items())
      line += fmt::format("{}{} = {} ({})", line.empty() ? "" : ", ", name, format_number(v["value"].get<double>()),
                          v["source"].get<std::string>());
    std::cout << fmt::format("- {}: {}\n", s.name, line);
  }
  std::cout << "\n";
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

/// What to do about a fit that did not converge, by what stopped it. `optimizer` ran the fit; `default_optimizer` is
/// fit's default for the model (fit_defaults.hpp).
std::string not_converged_advice(const FitOutcome& fit, const std::string& optimizer,
                                 const std::string& default_optimizer) {
  if (!fit.auto_budget) return ": do not trust this fit; raise --runs, --pop or --iters, or use --budget auto";
  if (fit.auto_budget->stop == "time cap") return ": do not trust this fit; raise --max-seconds";
  const AutoBudgetReport& b = *fit.auto_budget;
  if (b.second_opinion_lower) {
    std::string settings;
    for (const auto& [key, value] : b.second_opinion_optimizer->settings)
      settings += fmt::format("{}{}={}", settings.empty() ? " --optimizer-settings " : ",", key, value);
    return fmt::format(": do not trust this fit; {} found a lower value (fit with --optimizer {}{}, or raise "
                       "--max-evals)",
                       b.second_opinion_label(), b.second_opinion_optimizer->name, settings);
  }
  // A population method gains precision slowly near an optimum (GA's mutation keeps its spread); where the model's
  // default ends its runs with a local stage, that is the way out, not a larger cap.
  const bool still_improving = b.last_restart_rel < -kRestartRel;
  if (still_improving && !has_local_stage(optimizer) && has_local_stage(default_optimizer))
    return fmt::format(": do not trust this fit; its restarts were still improving the best at the cap, and {} has no "
                       "local stage to make it precise (fit with --optimizer {}, fit's default for this model, or "
                       "raise --max-evals)",
                       optimizer, default_optimizer);
  return ": do not trust this fit; raise --max-evals";
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

namespace {

void print_markdown(const PreparedFit& p, const FitOutcome& fit, const FitTables& t) {
  const Convergence& c = fit.convergence;
  const ConvergenceRule rule;
  if (!p.plan.why.empty()) std::cout << p.plan.why << "\n\n";
  std::cout << t.params.to_markdown() << "\n" << t.metrics.to_markdown() << "\n" << t.runs.to_markdown() << "\n";
  print_operating(p.records);
  std::cout << fmt::format("{}: {}{}{}\n", c.converged ? "Converged" : "NOT CONVERGED (" + c.verdict() + ")",
                           c.spread_text(rule),
                           c.best_at_local_optimum ? ", in its local stage, which ended at its optimum" : "",
                           c.converged ? ""
                                       : not_converged_advice(fit, p.plan.optimizer,
                                                              fit_plan(*p.model.model, {}, {}, {}, {}).optimizer));
  if (fit.auto_budget) std::cout << "Budget: " << fit.auto_budget->summary() << "\n";
  const Identification& id = fit.identification;
  std::cout << fmt::format("{} evaluations × {} samples in {:.3f} s ({:.3g} candidate-samples/s)\n", t.evaluations,
                           p.records.samples(), id.wall_time_s, id.candidate_samples / id.wall_time_s);
}

}  // namespace

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

int fit_command(const FitOptions& o) {
  const FitRun run = run_fit_options(o);
  const PreparedFit& prepared = run.prepared;
  if (o.format == "json") {
    std::cout << fit_json(o, run).dump(2) << "\n";
  } else {
    if (prepared.auto_laws)
      std::cout << fmt::format("Laws chosen: {}\n\n", run.selection.laws.empty() ? "none (every parameter shared)"
                                                                                 : run.selection.laws)
                << run.selection.choices.to_markdown() << "\n" << run.selection.folds.to_markdown() << "\n"
                << fmt::format("The records' own fits and the choice: {} evaluations, then {} law sets scored, in "
                               "{:.3f} s; the joint fit below\n\n",
                               run.selection.effort.evaluations, run.selection.scored,
                               run.selection.effort.wall_time_s);
    print_markdown(prepared, run.outcome, fit_tables(prepared, run.outcome, o.fit.metric));
    if (run.held_out)
      for (const Table& t : held_out_tables(*run.held_out, o.held_out.folds, per_file_model(*prepared.model.model).id()))
        std::cout << "\n" << t.to_markdown();
  }
  return 0;
}

}  // namespace dampbench::cli
