#include "engine/fit/held_out.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/random.hpp"
#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/fit/fitted_range.hpp"
#include "engine/fit/record_seed.hpp"
#include "engine/fit/law_selection.hpp"
#include "engine/model/bounds.hpp"
#include "engine/model/law_model.hpp"
#include "optimizers/registry.hpp"

namespace dampbench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

const Model& per_file_model(const Model& model) {
  if (const auto* law = dynamic_cast<const LawModel*>(&model)) return law->base();
  return model;
}

FitOutcome per_file_fit(const Model& model, const Signals& record, Metric metric, std::uint64_t seed) {
  ResolvedModel resolved;
  resolved.model = &model;
  resolved.bounds = default_bounds(model);
  resolved.bounds_option = "--bounds";
  const FitPlan plan = fit_plan(model, std::nullopt, std::nullopt, std::nullopt, std::nullopt);
  const OptimizerSpec optimizer{plan.optimizer, plan.population, plan.iterations};
  const OptimizerFactory factory = make_optimizer_factory(optimizer);
  FitRequest r;
  r.model = &resolved;
  r.records = {&record};
  r.optimizer = &factory;
  r.settings.runs = plan.runs;
  r.settings.seed = seed;
  r.settings.metric = metric;
  r.settings.task_key = task_key(model.id(), record.name, plan.optimizer);  // as PreparedFit::request names it
  r.assess_failed_fit = true;
  r.auto_budget = AutoBudget{optimizer, 0, 0};  // `fit`'s default budget, so the reference is what fit prints
  return run_fit(r);
}

double RecordError::ratio() const { return per_file ? metric / *per_file : kNaN; }

ErrorSummary summarize_errors(std::span<const RecordError> errors) {
  ErrorSummary s;
  s.count = static_cast<int>(errors.size());
  std::vector<const RecordError*> scored;  // the records with a finite metric
  for (const RecordError& e : errors)
    if (std::isfinite(e.metric)) scored.push_back(&e);
  s.failed = s.count - static_cast<int>(scored.size());
  double sum = 0, sum_per_file = 0;
  bool reference = !scored.empty();
  for (const RecordError* e : scored) {
    sum += e->metric;
    if (e->per_file) sum_per_file += *e->per_file;
    else reference = false;
  }
  const auto n = static_cast<double>(scored.size());
  s.mean = scored.empty() ? kNaN : sum / n;
  s.mean_per_file = s.ratio_of_means = s.worst_ratio = kNaN;
  if (!reference) return s;
  s.mean_per_file = sum_per_file / n;
  s.ratio_of_means = s.mean / s.mean_per_file;
  for (const RecordError* e : scored) {
    // A NaN ratio (a reference that failed) counts as the worst: it must not hide.
    if (s.worst_record.empty() || !(e->ratio() <= s.worst_ratio)) {
      s.worst_ratio = e->ratio();
      s.worst_record = e->record;
      if (std::isnan(s.worst_ratio)) break;
    }
  }
  return s;
}

std::string prediction_failure(const Model& model, std::span<const double> parameters, const Signals& record) {
  std::string at;
  for (const auto& [name, value] : record.law_variables)
    at += fmt::format("{}{}={:g}", at.empty() ? "" : ", ", name, value);
  at = at.empty() ? "on this record" : "at " + at;
  const auto* law = dynamic_cast<const LawModel*>(&model);
  if (!law) return fmt::format("{}: the fit's parameters give no finite force", at);
  const std::vector<double> base = law->base_parameters(parameters, record);
  // The box a fit of this record alone searches, in the units the laws' values have (the gauge's when applied).
  const Signals* const one[] = {&record};
  const ResolvedModel gauged = law->applied_gauge() ? gauged_model(law->base()) : ResolvedModel{};
  const Model& boxed = law->applied_gauge() ? *gauged.model : law->base();
  const Bounds box = law->applied_gauge() ? gauged.bounds_for(one) : default_bounds(law->base(), one);
  std::string outside;
  int count = 0;
  for (int j = 0; j < box.dim(); ++j) {
    const std::string& name = boxed.parameters()[j].name;
    const double v = base[static_cast<std::size_t>(law->base().parameter_index(name))];
    if (v >= box.lower[j] && v <= box.upper[j]) continue;  // a NaN value is outside too
    outside += fmt::format("{}{} = {:.3g} ({:.4g} to {:.4g})", outside.empty() ? "" : ", ", name, v, box.lower[j],
                           box.upper[j]);
    ++count;
  }
  if (count == 0)
    return fmt::format("{}: the laws give every parameter inside a per-record fit's box, and the model gives no finite "
                       "force",
                       at);
  return fmt::format("{}: the laws give {} outside a per-record fit's box: {}", at,
                     count == 1 ? "a parameter" : fmt::format("{} parameters", count), outside);
}

HeldOutPlan plan_held_out(const PreparedFit& fit, const RecordOptions& data, const HeldOutSpec& spec) {
  HeldOutPlan plan;
  plan.spec = spec;
  if (!spec.reference.empty() && spec.reference != "per-file")
    throw InputError(fmt::format("--reference: expected per-file, got '{}'", spec.reference));
  if (!spec.folds.empty()) plan.folds = make_folds(fit.records.pointers(), spec.folds, "--folds");
  if (!spec.predict.empty()) plan.predict = load_fit_records(*fit.model.model, spec.predict, data);
  return plan;
}

namespace {

/// The per-file reference fits of a held-out evaluation, each record's fitted once however often it is asked for.
class References {
 public:
  References(const PreparedFit& fit, bool enabled, std::function<void(const std::string&)> progress)
      : model_(per_file_model(*fit.model.model)), metric_(fit.metric), seed_(fit.seed), enabled_(enabled),
        progress_(std::move(progress)) {}

  /// `model`'s metric with `params` on `record` beside the record's per-file fit; when the metric is not finite,
  /// why (told to the progress too, as it happens).
  RecordError judge(std::string role, std::string fold, const Model& model, std::span<const double> params,
                    const Signals& record, const FittedRange& fitted) {
    RecordError e = error(std::move(role), std::move(fold), record, record_metric(model, params, record, metric_));
    e.extrapolated = fitted.outside(record.law_variables);
    if (std::isfinite(e.metric)) return e;
    e.failure = prediction_failure(model, params, record);
    if (progress_)
      progress_(fmt::format("{} {} (fold {}): no finite {}; {}", e.role, e.record, e.fold, metric_name(metric_),
                            e.failure));
    return e;
  }

 private:
  /// `record`'s metric beside its per-file fit (when references are enabled).
  RecordError error(std::string role, std::string fold, const Signals& record, double metric) {
    RecordError e{std::move(role), std::move(fold), record.name, metric, std::nullopt, std::nullopt};
    if (!enabled_) return e;
    auto it = done_.find(&record);
    if (it == done_.end()) {
      const FitOutcome f = per_file_fit(model_, record, metric_, seed_);
      it = done_.emplace(&record, std::make_pair(f.best().best_value, f.convergence.verdict())).first;
    }
    e.per_file = it->second.first;
    e.per_file_verdict = it->second.second;
    return e;
  }

  const Model& model_;
  Metric metric_;
  std::uint64_t seed_;
  bool enabled_;
  std::function<void(const std::string&)> progress_;
  std::map<const Signals*, std::pair<double, std::string>> done_;
};


/// The range of `model`'s law variables over `records`.
FittedRange fitted_range(const Model& model, const std::vector<const Signals*>& records) {
  std::vector<std::map<std::string, double>> variables;
  for (const Signals* r : records) variables.push_back(r->law_variables);
  return FittedRange(model, variables);
}

/// A fold of a `--laws auto` fit: its laws chosen and fitted on the fold's records alone.
FitOutcome fit_fold_with_auto_laws(const PreparedFit& fit, const FitRequest& request, const Fold& fold,
                                   ResolvedModel& fold_model, RecordFitCache* record_fits,
                                   const std::function<void(const std::string&)>& progress) {
  LawSearch search = law_search(fit, fold_request(request, fold));
  search.record_fits = record_fits;
  if (progress) search.progress = [&](const std::string& line) { progress(fmt::format("fold {}: {}", fold.name, line)); };
  LawSelection selection;
  return fit_with_auto_laws(search, fold_model, selection);
}

FoldFit fold_fit(const Fold& fold, const std::vector<const Signals*>& records, const FitOutcome& outcome,
                 const Model& model, const std::vector<const Signals*>& predicted) {
  FoldFit f;
  f.fold = fold;
  f.best_params = outcome.best().best_params;
  f.fit_value = outcome.best().best_value;
  f.verdict = outcome.convergence.verdict();
  f.converged = outcome.convergence.converged;
  for (const auto& p : model.parameters()) f.parameter_names.push_back(p.name);
  f.model_id = std::string(model.id());
  for (int i : fold.fit) f.fit_names.push_back(records[i]->name);
  for (const Signals* r : predicted) {
    f.predict_names.push_back(r->name);
    f.predicted.push_back(r);
    f.predicted_force.push_back(model.simulate(f.best_params, *r));
  }
  return f;
}

}  // namespace

HeldOut run_held_out(const PreparedFit& fit, const FitOutcome& outcome, const HeldOutPlan& plan) {
  HeldOut h;
  h.metric = fit.metric;
  h.reference = !plan.spec.reference.empty();
  const Model& model = *fit.model.model;
  const FitRequest request = fit.request();
  References references(fit, h.reference, plan.progress);
  RecordFitCache* record_fits = plan.record_fits.get();  // --laws auto, --start per-file: each record's own fit, once
  for (const Fold& fold : plan.folds) {
    ResolvedModel fold_model;
    FitRequest seeded = fold_request(request, fold);
    seed_start(fit, seeded, record_fits, plan.progress);
    const FitOutcome f = fit.auto_laws ? fit_fold_with_auto_laws(fit, request, fold, fold_model, record_fits, plan.progress)
                                       : run_fit(seeded);
    const Model& predicting = fit.auto_laws ? *fold_model.model : model;
    std::vector<const Signals*> predicted;
    for (int i : fold.predict) predicted.push_back(request.records[i]);
    if (plan.spec.folds == "leave-setting")  // the --predict records of the left-out setting too
      for (const Signals* r : plan.predict.pointers())
        if (same_fold_value(*r, *request.records[fold.predict.front()], plan.spec.folds)) predicted.push_back(r);
    h.folds.push_back(fold_fit(fold, request.records, f, predicting, predicted));
    if (plan.progress)
      plan.progress(fmt::format("fold {}: fitted on {} records, {} {:.6g} ({}); predicts {}", fold.name,
                                fold.fit.size(), metric_name(fit.metric), f.best().best_value,
                                f.convergence.verdict(), predicted.size()));
    const FittedRange range = fitted_range(predicting, seeded.records);
    for (const Signals* r : predicted)
      h.held_out.push_back(references.judge("held out", fold.name, predicting, f.best().best_params, *r, range));
  }
  const std::vector<double>& best = outcome.best().best_params;
  const FittedRange range = fitted_range(model, request.records);
  if (!plan.predict.signals.empty()) {
    // The fit on every --data record, as a fold of its own: it predicts the --predict records.
    std::vector<const Signals*> all = request.records;
    const std::vector<const Signals*> predicted = plan.predict.pointers();
    all.insert(all.end(), predicted.begin(), predicted.end());
    Fold fold{"all", {}, {}};
    for (int i = 0; i < static_cast<int>(all.size()); ++i)
      (i < static_cast<int>(request.records.size()) ? fold.fit : fold.predict).push_back(i);
    h.folds.push_back(fold_fit(fold, all, outcome, model, predicted));
    for (const Signals* r : predicted)
      h.held_out.push_back(references.judge("held out", "all", model, best, *r, range));
  }
  if (h.reference)
    for (const Signals* r : request.records)
      h.fitted.push_back(references.judge("fitted", "all", model, best, *r, range));
  h.fitted_summary = summarize_errors(h.fitted);
  h.held_out_summary = summarize_errors(h.held_out);
  if (!plan.folds.empty() && !plan.predict.signals.empty()) {
    std::vector<RecordError> by_folds, by_all;
    for (const RecordError& e : h.held_out) (e.fold == "all" ? by_all : by_folds).push_back(e);
    h.folds_summary = summarize_errors(by_folds);
    h.predicted_summary = summarize_errors(by_all);
  }
  return h;
}

}  // namespace dampbench
