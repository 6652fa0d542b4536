#include "engine/fit/fit.hpp"

#include <cmath>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/model/law_model.hpp"

namespace dampbench {

void check_record(const Model& model, const Signals& record) {
  if (model.is_system() != record.is_system())
    throw InputError(fmt::format(
        "record '{}' is a {} record and model {} a {} model: {}", record.name, record.is_system() ? "system (t, y, u)" : "rig (t, x, F)",
        model.id(), model.is_system() ? "system" : "rig",
        model.is_system() ? "a system model is driven by a force u and computes the displacement y (columns t,y,u)"
                          : "a rig model is driven by the displacement x and computes the force F (columns t,x,F)"));
  if (record.is_system()) check_uniform_sampling(record);
  if (const auto* law = dynamic_cast<const LawModel*>(&model)) law->check_variables(record);
}

FitOutcome run_fit(const FitRequest& request) {
  if (!request.model || !request.optimizer) throw InputError("fit: a request needs a model and an optimizer");
  const Model& model = *request.model->model;
  for (const Signals* r : request.records) check_record(model, *r);
  FitOutcome out;
  out.bounds = request.box ? *request.box : request.model->bounds_for(request.records);
  if (!request.start.empty()) {
    if (static_cast<int>(request.start.size()) != model.dim())
      throw InputError(fmt::format("fit: a start point of {} values for {} parameters", request.start.size(), model.dim()));
    out.bounds.start = request.start;
    clamp_into_box(model, out.bounds, out.bounds.start);
  }
  if (request.auto_budget) {
    out.auto_budget.emplace();
    out.identification = identify_until_converged(model, request.records, out.bounds, *request.auto_budget,
                                                  request.settings, *out.auto_budget, request.progress);
  } else {
    out.identification = identify(model, request.records, out.bounds, *request.optimizer, request.settings);
  }
  out.convergence = assess_convergence(out.identification, {}, out.auto_budget && out.auto_budget->stop != "converged");
  const RunResult& best = out.best();
  if (request.assess_failed_fit || std::isfinite(best.best_value))
    out.identifiability = assess_identifiability(model, request.records, out.bounds, best.best_params);
  return out;
}

}  // namespace dampbench
