#include "engine/cli/fit_command.hpp"

#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/cli/cli_options.hpp"
#include "engine/cli/fit_held_out.hpp"
#include "engine/cli/report_command.hpp"
#include "engine/common/error.hpp"
#include "engine/common/statistics.hpp"
#include "engine/common/table.hpp"
#include "engine/fit/fit.hpp"

namespace dampbench::cli {

void add_fit_options(CLI::App* c, FitOptions& o) {
  FitSpec& fit = o.fit;
  fit.model.option_prefix = "--";
  c->add_option("--model", fit.model.model, "model id")->required();
  c->add_option("--data", fit.paths, "test record (CSV); repeat for several conditions fitted at once")->required();
  c->add_option("--laws", fit.model.laws, "parameter laws in operating variables, e.g. 'c0=poly(I,1);alpha=poly(I,1)'");
  add_data_options(c, fit.data);
  c->add_option("--metric", fit.metric, metric_names() + " (default of_abs)");
  c->add_option("--optimizer", fit.optimizer,
                "pso, ga, aga, de, ga-lm, ... (default: ga-lm for models with internal states, else pso)");
  c->add_option("--optimizer-settings", fit.optimizer_settings, "algorithm settings, e.g. pc=0.6,pm=0.03 or variant=constriction");
  c->add_option("--pop", fit.population, "population size (default 24 for ga-lm on internal states, else 50)");
  c->add_option("--iters", fit.iterations, "iterations (default 30 for ga-lm on internal states, else 100)");
  c->add_option("--runs", fit.runs, "independent runs (default 4 for internal states, else 50)");
  c->add_option("--seed", fit.seed, "seed (default 1)");
  c->add_option("--bounds", fit.model.bounds, "bounds in SI, name=lo:hi,...");
  c->add_option("--format", o.format, "md (default) or json");
  c->add_option("--report", o.report, "also write an HTML report (loops, convergence, runs) to this file");
  add_held_out_options(c, o.held_out);
}

namespace {

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

void print_json(const FitOptions& o, const PreparedFit& p, const FitOutcome& fit, const FitTables& t,
                const std::optional<HeldOut>& held_out) {
  const Model& model = *p.model.model;
  const RunResult& best = fit.best();
  const Summary& s = t.spread;
  nlohmann::ordered_json j;
  j["model"] = model.id();
  j["data"] = o.fit.paths;
  j["samples"] = p.records.samples();
  j["metric"] = o.fit.metric;
  j["optimizer"] = {{"name", p.plan.optimizer}, {"population", p.plan.population}, {"iterations", p.plan.iterations},
                    {"settings", p.optimizer.settings}};
  j["seed"] = o.fit.seed;
  nlohmann::ordered_json bp = nlohmann::ordered_json::object();
  for (int i = 0; i < model.dim(); ++i) bp[model.parameters()[i].name] = best.best_params[i];
  j["best_params"] = bp;
  nlohmann::ordered_json metrics = nlohmann::ordered_json::object();
  for (int i = 0; i < kMetricCount; ++i) metrics[std::string(metric_name(kAllMetrics[i]))] = json_number(best.best_metrics[i]);
  j["metrics"] = metrics;
  j["runs"] = {{"count", s.count}, {"best", json_number(s.min)}, {"worst", json_number(s.max)},
               {"mean", json_number(s.mean)}, {"std", json_number(s.std)}};
  j["convergence"] = convergence_json(fit.convergence);
  // Best-so-far history of every run: [evaluations, value] where it improved, and at its end.
  nlohmann::ordered_json history = nlohmann::ordered_json::array();
  for (const RunResult& r : fit.identification.runs) {
    nlohmann::ordered_json points = nlohmann::ordered_json::array();
    for (const TracePoint& pt : improvement_points(r)) points.push_back({pt.evaluations, json_number(pt.value)});
    history.push_back(points);
  }
  j["history"] = history;
  j["identifiability"] = identifiability_json(model, *fit.identifiability);
  j["evaluations"] = t.evaluations;
  j["wall_time_s"] = fit.identification.wall_time_s;
  j["candidate_samples_per_s"] = fit.identification.candidate_samples / fit.identification.wall_time_s;
  if (held_out) j["held_out"] = held_out_json(*held_out, model);
  std::cout << j.dump(2) << "\n";
}

void print_markdown(const PreparedFit& p, const FitOutcome& fit, const FitTables& t) {
  const Convergence& c = fit.convergence;
  const ConvergenceRule rule;
  if (!p.plan.why.empty()) std::cout << p.plan.why << "\n\n";
  std::cout << t.params.to_markdown() << "\n" << t.metrics.to_markdown() << "\n" << t.runs.to_markdown() << "\n";
  std::cout << fmt::format("{}: the median run ends {:.3g} % above the best, the worst {:.3g} %; the best run "
                           "improved {:.3g} % over its last {:.0f} % of evaluations{}{}\n",
                           c.converged ? "Converged" : "NOT CONVERGED (" + c.verdict() + ")",
                           100 * c.median_above_best_rel, 100 * c.worst_above_best_rel, 100 * c.late_gain_rel,
                           100 * rule.late_fraction,
                           c.best_at_local_optimum ? ", in its local stage, which ended at its optimum" : "",
                           c.converged ? "" : ": do not trust this fit; raise --runs, --pop or --iters");
  const Identification& id = fit.identification;
  std::cout << fmt::format("{} evaluations × {} samples in {:.3f} s ({:.3g} candidate-samples/s)\n", t.evaluations,
                           p.records.samples(), id.wall_time_s, id.candidate_samples / id.wall_time_s);
}

}  // namespace

int fit_command(const FitOptions& o) {
  check_format(o.format);
  if (!o.report.empty()) {  // before the fit, not after it
    const auto folder = std::filesystem::absolute(o.report).parent_path();
    if (!std::filesystem::is_directory(folder))
      throw InputError(fmt::format("--report: the folder of '{}' does not exist", o.report));
  }
  const PreparedFit prepared = prepare_fit(o.fit);
  const HeldOutPlan held_out_plan = plan_held_out(prepared, o.fit.data, o.held_out);  // bad input before the fit
  const FitRequest request = prepared.request();
  const FitOutcome fit = run_fit(request);
  std::optional<HeldOut> held_out;
  if (o.held_out.any()) held_out = run_held_out(prepared, fit, held_out_plan);
  const FitTables tables = fit_tables(prepared, fit, o.fit.metric);
  if (!o.report.empty()) {
    FitReport report{prepared.model.model, prepared.plan.optimizer,
                     std::string(DAMPBENCH_VERSION) + " (" + DAMPBENCH_BUILD_FLAGS + ")", prepared.metric,
                     request.records, &fit.identification, {tables.params, tables.metrics, tables.runs}};
    write_fit_report(o.report, report);
  }
  if (o.format == "json") {
    print_json(o, prepared, fit, tables, held_out);
  } else {
    print_markdown(prepared, fit, tables);
    if (held_out)
      for (const Table& t : held_out_tables(*held_out, o.held_out.folds, per_file_model(*prepared.model.model).id()))
        std::cout << "\n" << t.to_markdown();
  }
  return 0;
}

}  // namespace dampbench::cli
