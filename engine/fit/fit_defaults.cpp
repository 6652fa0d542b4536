// Default optimizer, budget and runs of `fit` per model class (fit_defaults.hpp).
#include "engine/fit/fit_defaults.hpp"

#include <fmt/format.h>

#include "engine/model/model.hpp"

namespace dampbench {
namespace {

/// Algebraic models: the fvd paper's PSO and run count. A candidate costs one pass over the record, and 50 runs
/// give the best/worst/mean/std of the papers' tables.
const FitPlan kAlgebraic{"pso", 50, 100, 50, ""};

/// Models with internal states (and law models built on them): a short GA finds the basin, Levenberg–Marquardt
/// the optimum within it (the mfm paper's method, and the utfsm preset's ga-lm-ode settings, whose bests lie within
/// 0.08 % of a 10× budget's on every UTFSM file: scripts/utfsm_budget_check.py). Four runs, so that their agreement
/// means something. PSO with the algebraic defaults takes some thirty times longer on a UTFSM record for a worse
/// best and runs that disagree.
const FitPlan kStates{"ga-lm", 24, 30, 4, ""};

}  // namespace

FitPlan fit_plan(const Model& model, const std::optional<std::string>& optimizer, std::optional<int> population,
                 std::optional<int> iterations, std::optional<int> runs) {
  const bool states = model.has_internal_states();
  const FitPlan& cls = states ? kStates : kAlgebraic;
  FitPlan plan;
  plan.optimizer = optimizer.value_or(cls.optimizer);
  const bool class_optimizer = plan.optimizer == cls.optimizer;
  plan.population = population.value_or(class_optimizer ? cls.population : kAlgebraic.population);
  plan.iterations = iterations.value_or(class_optimizer ? cls.iterations : kAlgebraic.iterations);
  plan.runs = runs.value_or(cls.runs);
  if (!optimizer || !population || !iterations || !runs)
    plan.why = fmt::format("{}, population {}, {} iterations, {} runs: fit's defaults for {} (--optimizer, --pop, "
                           "--iters, --runs to change)",
                           plan.optimizer, plan.population, plan.iterations, plan.runs,
                           states ? "a model with internal states" : "an algebraic model");
  return plan;
}

}  // namespace dampbench
