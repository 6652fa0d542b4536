#pragma once
// Held-out evaluation: a model fitted on some records predicts others, and each predicted record's error stands
// beside that record's own per-file fit. A joint or law model is judged by how well it predicts records it was
// not fitted on; the ratio to the per-file fit (the best the base model does on that record alone) is the honest
// measure, because records differ in how well any model can describe them.
//
// Folds are named by a rule over the records' operating variables (leave one value of a variable out, leave one
// amplitude–frequency setting out) or given as explicit fit / predict lists. Each fold's fit is an ordinary
// FitRequest whose task key is extended by the fold's name, so that every fold has its own reproducible streams.
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/fit/fit.hpp"
#include "engine/fit/folds.hpp"
#include "engine/fit/prepared_fit.hpp"
#include "engine/fit/record_fit_cache.hpp"
#include "engine/model/metrics.hpp"
#include "engine/model/model.hpp"
#include "engine/record/record_options.hpp"
#include "engine/record/signals.hpp"

namespace dampbench {

/// Why `model` with `parameters` gives no finite metric on `record`, for a message: for a law model, its base
/// parameters at the record's operating variables that lie outside the box a fit of that record alone searches
/// (the gauged model's box when the law model applies the gauge), e.g. "at amp=0.002, freq=5, I=0: the laws give
/// n = 7.5 outside a per-record fit's box (1 to 3)"; otherwise, or when every one lies inside, that the simulation
/// itself gives no finite force.
std::string prediction_failure(const Model& model, std::span<const double> parameters, const Signals& record);

/// The model a per-file reference fits: a law model's base (every parameter free), a plain model itself.
const Model& per_file_model(const Model& model);

/// The per-file reference of one record: `model` fitted to it alone with fit's defaults for the model's class
/// (fit_defaults.hpp), its default bounds and the task key `dampbench fit --model ID --data FILE` uses, so that
/// `dampbench fit --model ID --data FILE --metric METRIC --seed SEED` gives the same bits.
FitOutcome per_file_fit(const Model& model, const Signals& record, Metric metric, std::uint64_t seed);

/// What `fit` evaluates beyond the fit itself (its options --predict, --folds, --reference).
struct HeldOutSpec {
  std::vector<std::string> predict;  ///< records predicted by the fit on every --data record
  std::string folds;                 ///< fold rule over the --data records ("" = none)
  std::string reference;             ///< "per-file" or "" (no reference fits)
  [[nodiscard]] bool any() const { return !predict.empty() || !folds.empty() || !reference.empty(); }
};

/// One record's metric (predicted, or fitted) beside its own per-file fit.
struct RecordError {
  std::string role;    ///< "fitted" (a record of the fit on every --data record) or "held out"
  std::string fold;    ///< the fold whose fit gives `metric` ("all": the fit on every --data record)
  std::string record;  ///< the record's name
  double metric = 0;
  std::optional<double> per_file;            ///< the per-file reference fit's best value (--reference per-file)
  std::optional<std::string> per_file_verdict;  ///< its convergence verdict
  std::string failure = {};  ///< why `metric` is not finite (prediction_failure); "" when it is
  std::string extrapolated = {};  ///< its law variables outside the fold's fitted records' (FittedRange::outside)
  [[nodiscard]] double ratio() const;        ///< metric / per_file; NaN without a reference
};

/// Means over records and the worst ratio to the per-file fits. A record whose metric is not finite (a model that
/// gives no finite force there) is counted in `failed` and left out of the means and the worst ratio, so that one
/// such record does not hide what the others show; the tables say how many the means leave out.
struct ErrorSummary {
  int count = 0;   ///< every record
  int failed = 0;  ///< records without a finite metric, not in the means
  double mean = 0;
  double mean_per_file = 0, ratio_of_means = 0, worst_ratio = 0;  ///< NaN without a reference
  std::string worst_record;  ///< the record of the worst ratio ("" without a reference)
};
ErrorSummary summarize_errors(std::span<const RecordError> errors);

/// One fold's fit as held-out evaluation reports it.
struct FoldFit {
  Fold fold;
  std::vector<std::string> fit_names, predict_names;
  std::vector<double> best_params;  ///< the fit's best parameters (what predicts the fold's records)
  std::vector<std::string> parameter_names;  ///< of the fold's model (with --laws auto each fold has its laws)
  std::string model_id;
  /// The predicted records (in the order of predict_names; owned by the fit's records or the plan's --predict
  /// records) and each one's force simulated by the fold's model with best_params (Model::simulate), kept so that a
  /// report can draw measured against predicted after the fold's model is gone (with --laws auto it is the fold's).
  std::vector<const Signals*> predicted;
  std::vector<std::vector<double>> predicted_force;
  double fit_value = 0;  ///< the fit's best value (the metric's mean over the fold's fit records)
  std::string verdict;   ///< the fit's convergence verdict
  bool converged = false;
};

/// The held-out evaluation of a fit, checked and loaded before anything is fitted.
struct HeldOutPlan {
  HeldOutSpec spec;
  FitRecords predict;       ///< --predict records (loaded with the fit's loader options, checked against the model)
  std::vector<Fold> folds;  ///< of the fit's records
  /// `--laws auto` and `--start per-file`: each --data record's own fit (LawSearch::record_fits), made by the fit on
  /// all of them and reused by the folds.
  std::shared_ptr<RecordFitCache> record_fits = std::make_shared<RecordFitCache>();
  /// Told one line per step of a `--laws auto` or `--start per-file` fold (LawSearch::progress) and one per fold
  /// fitted; may be empty.
  std::function<void(const std::string&)> progress;
};

/// The plan of `spec` for `fit`, the --predict records loaded with the fit's loader options `data`. InputError for
/// an unknown --reference or a bad fold rule, and the loader's errors for the --predict records.
HeldOutPlan plan_held_out(const PreparedFit& fit, const RecordOptions& data, const HeldOutSpec& spec);

struct HeldOut {
  Metric metric = Metric::of_abs;
  bool reference = false;
  std::vector<FoldFit> folds;  ///< the rule's, then "all" (the fit on every --data record) when it predicts
  std::vector<RecordError> fitted;  ///< each --data record under the fit on all of them (with --reference)
  std::vector<RecordError> held_out;  ///< each fold's predicted records, then the --predict records
  ErrorSummary fitted_summary, held_out_summary;
  /// With both folds and --predict records: the held-out records of the folds and those of the fit on every --data
  /// record apart (count 0 otherwise).
  ErrorSummary folds_summary, predicted_summary;
};

/// Runs the plan: each fold fitted and its records predicted, the --predict records predicted by `outcome` (the
/// fit of `fit`'s request), and with a reference every record involved fitted alone (once each). The folds'
/// `predicted` point into `fit`'s and `plan`'s records: the result is read while they live.
HeldOut run_held_out(const PreparedFit& fit, const FitOutcome& outcome, const HeldOutPlan& plan);

}  // namespace dampbench
