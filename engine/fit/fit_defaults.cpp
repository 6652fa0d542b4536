// Default optimizer, budget and runs of `fit` per model class (engine/cli/fit_defaults.hpp).
#include "engine/cli/fit_defaults.hpp"

#include <fmt/format.h>

#include "engine/model/model.hpp"

namespace dampbench::cli {
namespace {

/// Algebraic models: the fvd paper's PSO and run count. A candidate costs one pass over the record, and 50 runs
/// give the best/worst/mean/std of the papers' tables.
const FitPlan kAlgebraic{"pso", 50, 100, 50, ""};

/// Models with internal states (and law models built on them): a short GA finds the basin, Levenberg–Marquardt
/// the optimum within it (the mfm paper's method; the utfsm preset's ga-lm-ode settings, whose bests lie within
/// 0.08 % of a 10× budget's on all 30 UTFSM files, scripts/utfsm_budget_check.py, 2026-11-25). Four runs, so that their
/// agreement means something. Measured on the 2-core AMD EPYC (Zen 5), UTFSM 10mm1Hz1A (11 854 samples, nrmse):
/// Spencer 4.6 s, best 0.04209 with all 4 runs within 2e-8 %, where the earlier default for every model (pso
/// 50 × 100, 50 runs) took 127 s for a best 3 % worse (0.04344) and runs 5-51 % apart. The joint current-law
/// Spencer fit of issue 13 (12 files) takes 36 s.
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

}  // namespace dampbench::cli
