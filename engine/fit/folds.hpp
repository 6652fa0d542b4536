#pragma once
// Folds of a record set for held-out evaluation and the law choice: named by a rule over the records' operating
// variables (leave one value of a variable out, leave one amplitude–frequency setting out); each fold's fit is an
// ordinary FitRequest whose task key is extended by the fold's name, so that every fold has its own reproducible
// streams. And the metric of given parameters on one record: what predicting a held-out record means.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/fit/fit.hpp"
#include "engine/model/metrics.hpp"
#include "engine/model/model.hpp"
#include "engine/record/signals.hpp"

namespace dampbench {

/// One fold: fit on `fit`, predict `predict` (indices into the record list).
struct Fold {
  std::string name;
  std::vector<int> fit, predict;
};

/// Folds by a rule: "leave-one:VAR" (one fold per distinct value of operating variable VAR among the records,
/// e.g. leave-one:I), "leave-setting" (one fold per distinct (amp, freq) pair: leave one amplitude–frequency
/// setting out). Folds are sorted by the value (setting) they leave out; values within a relative 1e-9 of each
/// other are one value. InputError (naming `where` and the rule) for an unknown rule, a variable a record lacks,
/// or a rule that gives fewer than two folds.
std::vector<Fold> make_folds(const std::vector<const Signals*>& records, std::string_view rule, std::string_view where);

/// VAR of a "leave-one:VAR" rule; empty for any other rule.
std::string_view leave_one_variable(std::string_view rule);

/// Whether record `a` has the value by which `rule` groups record `b` (the same setting for leave-setting, the same
/// VAR for leave-one:VAR; values within a relative 1e-9): a record that the fold leaving `b` out predicts too.
bool same_fold_value(const Signals& a, const Signals& b, std::string_view rule);

/// The metric of a model with given parameters on one record (what predicting a held-out record means): the
/// evaluation `evaluate` prints (BatchEvaluator::evaluate_all), so the two agree bit for bit.
double record_metric(const Model& model, std::span<const double> parameters, const Signals& record, Metric metric);

/// The request of one fold: `request` (model, optimizer, settings) on the fold's fit records, which index
/// `request.records`, with its task key extended by the fold's name.
FitRequest fold_request(const FitRequest& request, const Fold& fold);

}  // namespace dampbench
