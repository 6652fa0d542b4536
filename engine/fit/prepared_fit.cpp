#include "engine/fit/prepared_fit.hpp"

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"

namespace dampbench {

FitRequest PreparedFit::request() const {
  FitRequest r;
  r.model = &model;
  r.records = records.pointers();
  r.optimizer = &factory;
  r.settings.runs = plan.runs;
  r.settings.seed = seed;
  r.settings.metric = metric;
  r.settings.task_key = task_key(model.model->id(), records.names, plan.optimizer);
  r.assess_failed_fit = true;
  return r;
}

PreparedFit prepare_fit(const FitSpec& spec) {
  PreparedFit p;
  ModelChoice choice = spec.model;
  p.auto_laws = choice.laws == "auto";
  if (p.auto_laws) {
    if (!choice.bounds.empty())
      throw InputError("--bounds with --laws auto: the laws' coefficients are not known before they are chosen");
    choice.laws.clear();
  }
  if (!spec.start.empty() && spec.start != "per-file")
    throw InputError(fmt::format("--start: expected per-file, got '{}'", spec.start));
  p.start_per_file = spec.start == "per-file";
  if (p.start_per_file && p.auto_laws)
    throw InputError("--start per-file with --laws auto: --laws auto always starts from the records' own fits");
  p.choice = choice;
  p.model = resolve_model(choice);
  const Model& model = *p.model.model;
  p.metric = parse_metric(spec.metric);
  p.plan = fit_plan(model, spec.optimizer, spec.population, spec.iterations, spec.runs);
  p.optimizer = OptimizerSpec{p.plan.optimizer, p.plan.population, p.plan.iterations};
  for (const auto& [key, value] : parse_key_values(spec.optimizer_settings, "--optimizer-settings"))
    p.optimizer.settings[key] = value;
  p.factory = make_optimizer_factory(p.optimizer);
  if (spec.paths.empty()) throw InputError("fit: give at least one --data FILE");
  p.records = load_fit_records(model, spec.paths, spec.data);
  p.seed = spec.seed;
  return p;
}

}  // namespace dampbench
