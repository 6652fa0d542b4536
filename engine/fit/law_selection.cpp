#include "engine/fit/law_selection.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>
#include <optional>
#include <tuple>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "engine/common/error.hpp"
#include "engine/fit/folds.hpp"
#include "engine/model/law_model.hpp"

namespace dampbench {
namespace {

/// A set of laws, one per parameter of the gauged model.
using LawSet = std::vector<ValueLaw>;

/// The choice's folds: one per amplitude–frequency setting, then, when the records hold four or more currents, one
/// per current between the lowest and the highest (the shape in I between trained currents; leaving an end current
/// out would judge extrapolation instead).
struct ChoiceFolds {
  std::vector<Fold> folds;
  std::size_t setting_folds = 0;  ///< folds[0, setting_folds) leave a setting out, the rest a current
  std::size_t currents = 0;       ///< distinct currents among the records (0 when a record has none)
};

ChoiceFolds choice_folds(const std::vector<const Signals*>& records, const std::string& where) {
  ChoiceFolds out;
  out.folds = make_folds(records, "leave-setting", where);
  out.setting_folds = out.folds.size();
  const bool every_record_has_a_current = std::all_of(records.begin(), records.end(), [](const Signals* r) {
    return r->law_variables.count("I") > 0;
  });
  const bool currents_differ = std::any_of(records.begin(), records.end(), [&](const Signals* r) {
    return !same_fold_value(*records.front(), *r, "leave-one:I");
  });
  if (!every_record_has_a_current || !currents_differ) return out;
  auto by_current = make_folds(records, "leave-one:I", where);  // ascending in I
  out.currents = by_current.size();
  if (by_current.size() >= kCurrentsForShapeFolds)
    out.folds.insert(out.folds.end(), std::make_move_iterator(by_current.begin() + 1),
                     std::make_move_iterator(by_current.end() - 1));
  return out;
}

/// The smallest box holding the box of a fit of each of `training`'s records alone (their joint fit's box is
/// narrower in the stiffening parameters: RecordBoundsRule::stiffening).
Bounds training_hull(const ResolvedModel& gauged, const std::vector<const Signals*>& records,
                     const std::vector<int>& training) {
  std::vector<const Signals*> kept;
  for (int r : training) kept.push_back(records[r]);
  return gauged.bounds_for(kept, RecordBox::hull);
}

/// What scoring needs, fixed for one selection.
struct Scoring {
  const Model& model;  ///< the gauged model, its parameters those of the per-record fits
  const std::vector<const Signals*>& records;
  const std::vector<std::vector<double>>& per_record;
  ChoiceFolds folds;
  /// Per fold, the hull of the boxes a fit of each of its training records alone searches. A left-out record's
  /// predicted parameters are clamped into it, so that a law extrapolated past what any training record reached
  /// does not end the simulation; the left-out record's own box would scale with its measured force, which a
  /// prediction must not see.
  std::vector<Bounds> fold_boxes;
  Metric metric;
  mutable double simulated_samples = 0;  ///< Σ samples of the left-out records simulated
  /// Law fits by (fold, parameter, law): a coordinate step changes one parameter's law, the others' fits stay.
  mutable std::map<std::tuple<std::size_t, int, std::string>, ValueFit> fits_made = {};

  const ValueFit& law_fit(std::size_t fold, int j, const ValueLaw& law) const {
    const auto key = std::make_tuple(fold, j, law.text());
    auto it = fits_made.find(key);
    if (it == fits_made.end()) {
      std::vector<std::map<std::string, double>> vars;
      std::vector<double> y;
      values(j, folds.folds[fold].fit, vars, y);
      it = fits_made.emplace(key, fit_value_law(law, vars, y)).first;
    }
    return it->second;
  }

  /// Values of parameter j over records `which`, and their variables.
  void values(int j, const std::vector<int>& which, std::vector<std::map<std::string, double>>& vars,
              std::vector<double>& y) const {
    vars.clear(), y.clear();
    for (int r : which) {
      vars.push_back(records[r]->law_variables);
      y.push_back(per_record[r][j]);
    }
  }

  /// Per fold, the metric of each record it leaves out (in its predict order).
  std::vector<std::vector<double>> left_out_metrics(const LawSet& laws) const {
    std::vector<std::vector<double>> out;
    for (std::size_t f = 0; f < folds.folds.size(); ++f) {
      const Fold& fold = folds.folds[f];
      std::vector<const ValueFit*> fits;
      for (int j = 0; j < model.dim(); ++j) fits.push_back(&law_fit(f, j, laws[j]));
      std::vector<double> m(fold.predict.size());
      for (int r : fold.predict) simulated_samples += static_cast<double>(records[r]->size());
      tbb::parallel_for(std::size_t{0}, fold.predict.size(), [&](std::size_t i) {
        const int r = fold.predict[i];
        std::vector<double> p(model.dim());
        for (int j = 0; j < model.dim(); ++j)
          p[j] = std::clamp(fits[j]->predict(laws[j], records[r]->law_variables), fold_boxes[f].lower[j],
                            fold_boxes[f].upper[j]);
        const double v = record_metric(model, p, *records[r], metric);
        m[i] = std::isfinite(v) ? v : std::numeric_limits<double>::infinity();
      });
      out.push_back(std::move(m));
    }
    return out;
  }

  /// The mean left-out metric of the setting folds (each record once); with current folds, the mean of it and
  /// theirs, so that predicting a new setting and a new current weigh the same.
  double score(const LawSet& laws) const {
    const auto m = left_out_metrics(laws);
    const auto mean_over = [&](std::size_t begin, std::size_t end) {
      double sum = 0, n = 0;
      for (std::size_t f = begin; f < end; ++f)
        for (double v : m[f]) sum += v, ++n;
      return sum / n;
    };
    const double settings = mean_over(0, folds.setting_folds);
    if (folds.setting_folds == m.size()) return settings;
    return 0.5 * (settings + mean_over(folds.setting_folds, m.size()));
  }

  /// BIC of one family on parameter j's values over every record.
  double bic(int j, const ValueLaw& law) const {
    std::vector<int> all(records.size());
    for (std::size_t r = 0; r < all.size(); ++r) all[r] = static_cast<int>(r);
    std::vector<std::map<std::string, double>> vars;
    std::vector<double> y;
    values(j, all, vars, y);
    const double n = static_cast<double>(y.size());
    // Residuals below 1e-12 of the values' energy are rounding: families that fit exactly tie, and the
    // coefficient count decides.
    double energy = 0;
    for (double v : y) energy += v * v;
    const double rss = std::max(fit_value_law(law, vars, y).rss, std::max(1e-12 * energy, std::numeric_limits<double>::min()));
    return n * std::log(rss / n) + law.coefficients() * std::log(n);
  }
};

/// One coordinate step: the family for parameter j, the others held. Returns the new score.
double choose_for_parameter(const Scoring& s, LawSet& laws, int j, int& scored, double& chosen_bic) {
  const auto candidates = value_law_candidates();
  std::vector<double> scores;
  for (const ValueLaw& c : candidates) {
    LawSet trial = laws;
    trial[j] = c;
    scores.push_back(s.score(trial));
    ++scored;
  }
  const double best = *std::min_element(scores.begin(), scores.end());
  int pick = -1;
  double pick_bic = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    if (!(scores[c] <= best * 1.01)) continue;
    const double b = s.bic(j, candidates[c]);
    if (pick < 0 || b < pick_bic) pick = static_cast<int>(c), pick_bic = b;
  }
  laws[j] = candidates[pick];
  chosen_bic = pick_bic;
  return scores[pick];
}

std::string describe_setting(const Signals& r) {
  return fmt::format("amp {:g} mm, freq {:g} Hz", 1e3 * r.law_variables.at("amp"), r.law_variables.at("freq"));
}

Table fold_table(const Scoring& s, const LawSet& shared, const LawSet& chosen) {
  const auto a = s.left_out_metrics(shared), b = s.left_out_metrics(chosen);
  Table t;
  t.id = "law_folds";
  t.title = "Folds of the training records (laws fitted to the per-record values): each setting left out, then each "
            "current between the lowest and the highest when there are four or more";
  t.columns = {"left out", "records", fmt::format("{} shared", metric_name(s.metric)),
               fmt::format("{} chosen laws", metric_name(s.metric))};
  for (std::size_t f = 0; f < s.folds.folds.size(); ++f) {
    const Fold& fold = s.folds.folds[f];
    double sa = 0, sb = 0;
    for (std::size_t i = 0; i < fold.predict.size(); ++i) sa += a[f][i], sb += b[f][i];
    const double n = static_cast<double>(fold.predict.size());
    const Signals& first = *s.records[fold.predict.front()];
    t.rows.push_back({f < s.folds.setting_folds ? describe_setting(first)
                                                : fmt::format("I {:g} A", first.law_variables.at("I")),
                      fmt::format("{}", fold.predict.size()), number_cell(sa / n), number_cell(sb / n)});
  }
  if (s.folds.currents > 1 && s.folds.currents < kCurrentsForShapeFolds)
    t.note = fmt::format("No current is left out: with {} training currents, leaving one out leaves too few to "
                         "determine a law in I, so nothing here judges the laws' shape between the trained currents, "
                         "which decides predictions there. Train on {} or more currents to have it judged.",
                         s.folds.currents, kCurrentsForShapeFolds);
  return t;
}

}  // namespace

LawSearch law_search(const FitRequest& request, const Model& model, std::string optimizer_name) {
  LawSearch search;
  const auto* law = dynamic_cast<const LawModel*>(&model);
  search.base = law ? &law->base() : &model;
  search.records = request.records;
  search.optimizer = request.optimizer;
  search.optimizer_name = std::move(optimizer_name);
  search.settings = request.settings;
  return search;
}

LawSearch law_search(const PreparedFit& fit, const FitRequest& request) {
  return law_search(request, *fit.model.model, fit.plan.optimizer);
}

ResolvedModel gauged_model(const Model& base) {
  ResolvedModel r;
  r.keep.push_back(std::make_shared<LawModel>(base, std::map<std::string, ParameterLaw>{}));
  r.model = r.keep.back().get();
  r.bounds = default_bounds(*r.model);
  r.bounds_option = "--bounds";
  return r;
}

namespace {

/// One record fitted alone with the search's optimizer and settings, and what that cost.
RecordFit fit_record_alone(const LawSearch& search, const ResolvedModel& gauged, const Signals& record,
                           double& best_value) {
  const auto start = std::chrono::steady_clock::now();
  FitRequest request;
  request.model = &gauged;
  request.records = {&record};
  request.optimizer = search.optimizer;
  request.settings = search.settings;
  request.settings.task_key = task_key(gauged.model->id(), record.name, search.optimizer_name);
  const FitOutcome outcome = run_fit(request);
  best_value = outcome.best().best_value;
  if (!std::isfinite(best_value))
    throw DataError(fmt::format("{}: the fit of {} alone failed (every run ended without a finite {})", search.label,
                                record.name, metric_name(search.settings.metric)));
  RecordFit fit;
  fit.best_params = outcome.best().best_params;
  for (const auto& run : outcome.identification.runs) fit.effort.evaluations += run.evaluations;
  fit.effort.candidate_samples = outcome.identification.candidate_samples;
  fit.effort.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return fit;
}

}  // namespace

std::vector<std::vector<double>> fit_each_record(const LawSearch& search, const ResolvedModel& gauged,
                                                 PreFitEffort* effort) {
  std::vector<std::vector<double>> out;
  for (const Signals* record : search.records) {
    const std::string key = RecordFitCache::key(*record, gauged.model->id(), search.optimizer, search.settings);
    std::optional<RecordFit> fit = search.record_fits ? search.record_fits->find(key) : std::nullopt;
    if (!fit) {
      double best_value = 0;
      fit = fit_record_alone(search, gauged, *record, best_value);
      if (search.record_fits) search.record_fits->store(key, *fit);
      if (search.progress)
        search.progress(fmt::format("{}: {} fitted alone ({}/{}): {} {:.6g}", search.label, record->name,
                                    out.size() + 1, search.records.size(), metric_name(search.settings.metric),
                                    best_value));
    }
    if (effort) *effort += fit->effort;
    out.push_back(std::move(fit->best_params));
  }
  return out;
}

LawSelection select_laws(const LawSearch& search, const ResolvedModel& gauged,
                         const std::vector<std::vector<double>>& per_record) {
  const auto start = std::chrono::steady_clock::now();
  const Model& model = *gauged.model;
  Scoring s{model, search.records, per_record, choice_folds(search.records, search.label), {}, search.settings.metric};
  for (const Fold& fold : s.folds.folds) s.fold_boxes.push_back(training_hull(gauged, search.records, fold.fit));
  LawSelection out;
  for (const auto& p : model.parameters()) out.parameters.push_back(p.name);
  const LawSet shared(static_cast<std::size_t>(model.dim()));
  LawSet laws = shared;
  out.shared_score = out.score = s.score(shared);
  std::vector<double> bics(laws.size()), scores(laws.size(), out.score);
  for (int pass = 0; pass < kLawChoicePasses; ++pass) {
    bool changed = false;
    for (int j = 0; j < model.dim(); ++j) {
      const ValueLaw before = laws[j];
      out.score = scores[j] = choose_for_parameter(s, laws, j, out.scored, bics[j]);
      changed |= laws[j].text() != before.text();
      if (search.progress)
        search.progress(fmt::format("{}: pass {}, {} = {} (mean left-out {} {:.6g})", search.label, pass + 1,
                                    out.parameters[j], laws[j].text(), metric_name(s.metric), out.score));
    }
    if (!changed) break;
  }
  out.chosen = laws;
  out.folds = fold_table(s, shared, laws);
  out.effort.candidate_samples = s.simulated_samples;
  out.effort.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.choices.id = "law_choices";
  out.choices.title = "Chosen laws (BIC of each on the per-record values; score: mean left-out metric when chosen)";
  out.choices.columns = {"parameter", "law", "coefficients", "BIC", "score"};
  std::vector<int> all(search.records.size());
  for (std::size_t r = 0; r < all.size(); ++r) all[r] = static_cast<int>(r);
  std::vector<std::map<std::string, double>> vars;
  std::vector<double> y;
  for (int j = 0; j < model.dim(); ++j) {
    const std::string text = laws[j].text();
    if (text != "free") out.laws += fmt::format("{}{}={}", out.laws.empty() ? "" : ";", out.parameters[j], text);
    s.values(j, all, vars, y);
    const auto c = fit_value_law(laws[j], vars, y).coefficients;
    out.start.insert(out.start.end(), c.begin(), c.end());
    out.choices.rows.push_back({out.parameters[j], text, fmt::format("{}", laws[j].coefficients()),
                                number_cell(bics[j]), number_cell(scores[j])});
  }
  return out;
}

std::string chosen_laws_text(const LawSelection& selection) {
  return selection.laws.empty() ? selection.parameters.at(0) + "=free" : selection.laws;
}

FitOutcome fit_with_auto_laws(const LawSearch& search, ResolvedModel& fitted_model, LawSelection& selection) {
  const ResolvedModel gauged = gauged_model(*search.base);
  PreFitEffort fits;
  selection = select_laws(search, gauged, fit_each_record(search, gauged, &fits));
  selection.effort += fits;
  ModelChoice choice;
  choice.model = std::string(search.base->id());
  choice.laws = chosen_laws_text(selection);
  choice.option_prefix = "--";
  fitted_model = resolve_model(choice);
  if (fitted_model.model->dim() != static_cast<int>(selection.start.size()))
    throw std::logic_error(fmt::format("--laws auto: {} start values for {} coefficients", selection.start.size(),
                                       fitted_model.model->dim()));
  FitRequest request;
  request.model = &fitted_model;
  request.records = search.records;
  request.optimizer = search.optimizer;
  request.settings = search.settings;
  std::string names;
  for (const Signals* r : search.records) names += (names.empty() ? "" : "+") + r->name;
  request.settings.task_key = task_key(fitted_model.model->id(), names, search.optimizer_name);
  request.start = selection.start;
  if (search.progress)
    search.progress(fmt::format("{}: fitting {} on the {} records together", search.label, fitted_model.model->id(),
                                search.records.size()));
  return run_fit(request);
}

}  // namespace dampbench
