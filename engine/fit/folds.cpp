#include "engine/fit/folds.hpp"

#include <algorithm>
#include <numeric>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/random.hpp"
#include "engine/evaluation/batch_evaluator.hpp"

namespace dampbench {
namespace {

/// The distinct values among `v` (ascending, each the smallest of its group) and each element's index among them.
struct Distinct {
  std::vector<double> values;
  std::vector<int> of;
};

Distinct distinct_values(const std::vector<double>& v) {
  std::vector<int> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return v[a] < v[b]; });
  Distinct d;
  d.of.assign(v.size(), -1);
  for (int i : order) {
    // Against the group's first value, so that a chain of near values cannot drift into one group.
    if (d.values.empty() || !same_operating_value(d.values.back(), v[i])) d.values.push_back(v[i]);
    d.of[i] = static_cast<int>(d.values.size()) - 1;
  }
  return d;
}

double variable_of(const Signals& record, const std::string& variable, std::string_view rule, std::string_view where) {
  const auto it = record.law_variables.find(variable);
  if (it == record.law_variables.end())
    throw InputError(fmt::format("{} {}: record '{}' has no operating variable '{}' (give it with --set {}=... or in "
                                 "the record)",
                                 where, rule, record.name, variable, variable));
  return it->second;
}

std::vector<double> values_of(const std::vector<const Signals*>& records, const std::string& variable,
                              std::string_view rule, std::string_view where) {
  std::vector<double> v;
  for (const Signals* r : records) v.push_back(variable_of(*r, variable, rule, where));
  return v;
}

/// One fold per key that some record has, in the order of the keys: it predicts the records of its key.
std::vector<Fold> folds_by_key(const std::vector<int>& key, int keys, const std::vector<std::string>& names) {
  std::vector<Fold> folds;
  for (int k = 0; k < keys; ++k) {
    Fold f{names[k], {}, {}};
    for (int i = 0; i < static_cast<int>(key.size()); ++i) (key[i] == k ? f.predict : f.fit).push_back(i);
    if (!f.predict.empty()) folds.push_back(std::move(f));
  }
  return folds;
}

std::vector<Fold> leave_one_out(const std::vector<const Signals*>& records, const std::string& variable,
                                std::string_view rule, std::string_view where) {
  const Distinct d = distinct_values(values_of(records, variable, rule, where));
  std::vector<std::string> names;
  for (double v : d.values) names.push_back(fmt::format("{}={:g}", variable, v));
  return folds_by_key(d.of, static_cast<int>(d.values.size()), names);
}

std::vector<Fold> leave_setting_out(const std::vector<const Signals*>& records, std::string_view rule,
                                    std::string_view where) {
  const Distinct amp = distinct_values(values_of(records, "amp", rule, where));
  const Distinct freq = distinct_values(values_of(records, "freq", rule, where));
  const int nf = static_cast<int>(freq.values.size());
  std::vector<int> key;
  for (std::size_t i = 0; i < records.size(); ++i) key.push_back(amp.of[i] * nf + freq.of[i]);
  std::vector<std::string> names;
  for (double a : amp.values)
    for (double f : freq.values) names.push_back(fmt::format("amp={:g},freq={:g}", a, f));
  return folds_by_key(key, static_cast<int>(names.size()), names);
}

int metric_index(Metric metric) {
  return static_cast<int>(std::find(kAllMetrics.begin(), kAllMetrics.end(), metric) - kAllMetrics.begin());
}

}  // namespace

std::vector<Fold> make_folds(const std::vector<const Signals*>& records, std::string_view rule,
                             std::string_view where) {
  std::vector<Fold> folds;
  if (const std::string_view variable = leave_one_variable(rule); !variable.empty()) {
    folds = leave_one_out(records, std::string(variable), rule, where);
  } else if (rule == "leave-setting") {
    folds = leave_setting_out(records, rule, where);
  } else {
    throw InputError(fmt::format("{}: unknown fold rule '{}' (expected leave-one:VAR, e.g. leave-one:I, or "
                                 "leave-setting)",
                                 where, rule));
  }
  if (folds.size() < 2)
    throw InputError(fmt::format("{} {}: the {} record{} give{} {} fold{} ({}); held-out evaluation needs at least two",
                                 where, rule, records.size(), records.size() == 1 ? "" : "s",
                                 records.size() == 1 ? "s" : "", folds.size(), folds.size() == 1 ? "" : "s",
                                 folds.empty() ? "no records" : "every record has " + folds[0].name));
  return folds;
}

std::string_view leave_one_variable(std::string_view rule) {
  constexpr std::string_view kLeaveOne = "leave-one:";
  return rule.starts_with(kLeaveOne) ? rule.substr(kLeaveOne.size()) : std::string_view{};
}

bool same_fold_value(const Signals& a, const Signals& b, std::string_view rule) {
  const auto near = [&](std::string_view v) {
    const auto x = a.law_variables.find(std::string(v)), y = b.law_variables.find(std::string(v));
    return x != a.law_variables.end() && y != b.law_variables.end() && same_operating_value(x->second, y->second);
  };
  if (const std::string_view variable = leave_one_variable(rule); !variable.empty()) return near(variable);
  return rule == "leave-setting" && near("amp") && near("freq");
}

double record_metric(const Model& model, std::span<const double> parameters, const Signals& record, Metric metric) {
  if (static_cast<int>(parameters.size()) != model.dim())
    throw InputError(fmt::format("{} has {} parameters, got {}", model.id(), model.dim(), parameters.size()));
  CandidateBatch batch(model.dim(), 1);
  batch.set_candidate(0, parameters);
  std::vector<MetricRow> row(1);
  BatchEvaluator(model, record).evaluate_all(batch, row);
  return row[0][metric_index(metric)];
}

FitRequest fold_request(const FitRequest& request, const Fold& fold) {
  FitRequest r = request;
  r.records.clear();
  for (int i : fold.fit) r.records.push_back(request.records.at(static_cast<std::size_t>(i)));
  r.settings.task_key = extend_key(request.settings.task_key, hash_name("fold " + fold.name));
  return r;
}

}  // namespace dampbench
