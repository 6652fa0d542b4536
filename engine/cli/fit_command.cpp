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
                "per-file: start the search from the laws fitted to each record's own fit; narrowed: search the box of three "
                "rounds of the mfm paper's bound narrowing over the records, from the laws fitted to the last; or a model "
                "file (--save-model) of "
                "the same model and laws: start from its coefficients (member 0 of each run, clamped into the box)");
  c->add_option("--format", o.format, "md (default) or json");
  c->add_option("--report", o.report, "also write an HTML report (loops, convergence, runs) to this file");
  c->add_option("--save-model", o.save_model, "also write the fitted model as JSON (for evaluate/simulate --model-file)");
  add_held_out_options(c, o.held_out);
}

namespace {

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
