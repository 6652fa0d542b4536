#include "engine/fit/fit_entry.hpp"

#include <utility>

#include "engine/fit/fit.hpp"
#include "engine/fit/record_seed.hpp"

namespace dampbench {
namespace {

/// `laws = auto`: chooses the laws, fits them, and makes `result` describe the chosen model, so that tables, reports
/// and model files show it.
FitOutcome fit_with_chosen_laws(FitResult& result, const HeldOutPlan& held_out) {
  LawSearch search = law_search(result.prepared, result.prepared.request());
  search.record_fits = held_out.record_fits.get();  // the folds reuse each record's own fit
  search.progress = held_out.progress;
  ResolvedModel fitted;
  FitOutcome outcome = fit_with_auto_laws(search, fitted, result.selection);
  result.prepared.model = std::move(fitted);
  result.spec.model.laws = result.selection.laws;
  return outcome;
}

}  // namespace

FitResult fit_and_predict(const FitSpec& spec, const HeldOutSpec& held_out,
                          const std::function<void(const std::string&)>& progress) {
  FitResult result{spec, prepare_fit(spec), {}, {}, {}, {}};
  result.plan = plan_held_out(result.prepared, spec.data, held_out);  // bad input before the fit
  HeldOutPlan& plan = result.plan;
  plan.progress = progress;
  FitRequest seeded = result.prepared.request();
  seeded.progress = progress;
  seed_start(result.prepared, seeded, plan.record_fits.get(), progress);
  result.outcome = result.prepared.auto_laws ? fit_with_chosen_laws(result, plan) : run_fit(seeded);
  if (held_out.any()) result.held_out = run_held_out(result.prepared, result.outcome, plan);
  return result;
}

}  // namespace dampbench
