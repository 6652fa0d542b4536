#include "engine/fit/prepared_fit.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"
#include "engine/fit/model_file.hpp"

namespace dampbench {

FitRequest PreparedFit::request() const {
  FitRequest r;
  r.model = &model;
  r.records = records.pointers();
  r.optimizer = &factory;
  r.settings.runs = plan.runs;
  r.settings.seed = seed;
  r.settings.stop = stop;
  r.settings.metric = metric;
  r.settings.search_precision = search_precision;
  r.settings.task_key = task_key(model.model->id(), records.names, plan.optimizer);
  r.start = start;
  r.assess_failed_fit = true;
  r.auto_budget = auto_budget;
  return r;
}

namespace {

/// The coefficients of a model file (fit --save-model) as the start of a fit of `model`; InputError naming the file
/// when it is not a model file or its model is another (its id, laws included, must be `model`'s).
std::vector<double> start_from_model_file(const std::string& path, const Model& model) {
  if (!std::filesystem::is_regular_file(path))
    throw InputError(fmt::format("--start: expected per-file or a model file (fit --save-model), got '{}', which is "
                                 "not a file",
                                 path));
  const LoadedModel loaded = load_model_file(path);
  if (loaded.model.model->id() != model.id())
    throw InputError(fmt::format("--start {}: the file's model is {} and this fit's {}: a start needs the same model "
                                 "and laws",
                                 path, loaded.model.model->id(), model.id()));
  return loaded.params;
}

/// The automatic budget the spec asks for (FitSpec::budget), or none; InputError for a cap it cannot have.
std::optional<AutoBudget> auto_budget_of(const FitSpec& spec, const OptimizerSpec& optimizer) {
  if (!spec.budget.empty() && spec.budget != "auto" && spec.budget != "fixed")
    throw InputError(fmt::format("--budget: expected auto or fixed, got '{}'", spec.budget));
  const bool fixed_given = spec.population || spec.iterations || spec.runs;
  const bool automatic = spec.budget == "auto" || (spec.budget.empty() && !fixed_given);
  if (!automatic && (spec.max_evaluations || spec.max_seconds))
    throw InputError(fmt::format("--max-evals and --max-seconds cap the automatic budget, and this fit's budget is "
                                 "fixed ({}): add --budget auto, or drop the caps",
                                 spec.budget == "fixed" ? "--budget fixed" : "--pop, --iters or --runs given"));
  if (spec.max_evaluations && *spec.max_evaluations < 1)
    throw InputError(fmt::format("--max-evals: expected a whole number >= 1, got {}", *spec.max_evaluations));
  if (spec.max_seconds && !(*spec.max_seconds > 0))
    throw InputError(fmt::format("--max-seconds: expected a number > 0, got {}", *spec.max_seconds));
  if (!automatic) return std::nullopt;
  return AutoBudget{optimizer, spec.max_evaluations.value_or(0), spec.max_seconds.value_or(0)};
}

}  // namespace

PreparedFit prepare_fit(const FitSpec& spec) {
  PreparedFit p;
  ModelChoice choice = spec.model;
  p.auto_laws = chooses_laws(choice);
  p.start_per_file = spec.start == "per-file";
  p.start_narrowed = spec.start == "narrowed";
  if (p.start_narrowed && !choice.bounds.empty())
    throw InputError("--start narrowed makes the box from the records' narrowed fits: drop --bounds");
  if (!spec.start.empty() && p.auto_laws)
    throw InputError(fmt::format("--start {} with --laws auto: --laws auto always starts from the records' own fits",
                                 spec.start));
  p.model = resolve_model_or_auto_base(choice);  // with --laws auto: the base model, before its laws are chosen
  if (!spec.start.empty() && !p.start_per_file && !p.start_narrowed)
    p.start = start_from_model_file(spec.start, *p.model.model);
  if (p.auto_laws) choice.laws.clear();
  p.choice = choice;
  const Model& model = *p.model.model;
  p.metric = parse_metric(spec.metric);
  p.search_precision = parse_search_precision(spec.precision, "--precision");
  p.plan = fit_plan(model, spec.optimizer, spec.population, spec.iterations, spec.runs);
  p.optimizer = OptimizerSpec{p.plan.optimizer, p.plan.population, p.plan.iterations};
  for (const auto& [key, value] : parse_key_values(spec.optimizer_settings, "--optimizer-settings"))
    p.optimizer.settings[key] = value;
  p.factory = make_optimizer_factory(p.optimizer);
  p.auto_budget = auto_budget_of(spec, p.optimizer);
  if (p.auto_laws && p.auto_budget) {  // its many fits keep the fixed budget (docs/guide.md, fit)
    if (spec.budget == "auto" || spec.max_evaluations || spec.max_seconds)
      throw InputError("--budget auto, --max-evals and --max-seconds do not apply to --laws auto, whose fits use the "
                       "fixed budget (--pop, --iters, --runs)");
    p.auto_budget.reset();
  }
  if (p.auto_budget)
    p.plan.why += fmt::format("{}automatic budget: the runs restart with twice the iterations until they converge and a "
                              "second opinion finds nothing lower, "
                              "within {} evaluations (--max-evals; --budget fixed or --pop, --iters, --runs for a "
                              "fixed budget)",
                              p.plan.why.empty() ? "" : "; ",
                              p.auto_budget->max_evaluations > 0 ? fmt::format("{}", p.auto_budget->max_evaluations)
                                                                 : std::string("64 × the first round's (plus the "
                                                                               "second opinion's)"));
  p.records = command_records(model, spec.paths, spec.records, spec.data, "fit");
  p.seed = spec.seed;
  p.stop = spec.stop;
  return p;
}

}  // namespace dampbench
