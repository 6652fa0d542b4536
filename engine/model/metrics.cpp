#include "engine/model/metrics.hpp"

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench {

namespace {

/// A metric's name, the one sum it is finished from and how: one row per metric, so that the sum a kernel
/// computes for an objective (sum_set_of) is by construction the one finish_metric reads.
struct MetricDefinition {
  Metric metric;
  std::string_view name;
  SumSet sums;
  double (*finish)(const MetricSums& s, const Signals& d, double n);  ///< n = samples
};

constexpr std::array<MetricDefinition, kMetricCount> kDefinitions{{
    {Metric::of_abs, "of_abs", SumSet::abs_weighted,
     [](const MetricSums& s, const Signals& d, double) { return s.abs_weighted / (d.measured_std * d.duration_s); }},
    {Metric::of_sq, "of_sq", SumSet::sq_weighted,
     [](const MetricSums& s, const Signals& d, double) {
       return s.sq_weighted / (d.measured_std * d.measured_std * d.duration_s);
     }},
    {Metric::rmse, "rmse", SumSet::sq, [](const MetricSums& s, const Signals&, double n) { return std::sqrt(s.sq / n); }},
    {Metric::nrmse, "nrmse", SumSet::sq,
     [](const MetricSums& s, const Signals& d, double n) { return std::sqrt(s.sq / n) / d.measured_max_abs; }},
    {Metric::mae, "mae", SumSet::abs, [](const MetricSums& s, const Signals&, double n) { return s.abs / n; }},
    {Metric::crfd_eps, "crfd_eps", SumSet::sq,
     [](const MetricSums& s, const Signals& d, double) { return std::sqrt(0.5 * s.sq / d.measured_max_abs) * 100.0; }},
    {Metric::mfm_E, "mfm_E", SumSet::sq,
     [](const MetricSums& s, const Signals& d, double) { return std::sqrt(s.sq / d.measured_sum_sq); }},
    {Metric::fdsp_pct, "fdsp_pct", SumSet::abs_magnitude,
     [](const MetricSums& s, const Signals& d, double n) { return 100.0 * s.abs_magnitude / (n * d.measured_max_abs); }},
    {Metric::fdsp_signed_pct, "fdsp_signed_pct", SumSet::abs,
     [](const MetricSums& s, const Signals& d, double n) { return 100.0 * s.abs / (n * d.measured_max_abs); }},
}};

constexpr bool rows_in_enum_order() {
  for (int i = 0; i < kMetricCount; ++i)
    if (kDefinitions[i].metric != kAllMetrics[i] || static_cast<int>(kAllMetrics[i]) != i) return false;
  return true;
}
static_assert(rows_in_enum_order(), "kDefinitions must list every metric in the order of enum Metric");

const MetricDefinition& definition(Metric m) {
  const auto i = static_cast<std::size_t>(m);
  if (i >= kDefinitions.size()) throw InputError(fmt::format("metric number {} is not a metric (0-{})", i, kMetricCount - 1));
  return kDefinitions[i];
}

}  // namespace

std::string_view metric_name(Metric m) { return definition(m).name; }

std::string metric_names() {
  std::string names;
  for (Metric m : kAllMetrics) names += (names.empty() ? "" : ", ") + std::string(metric_name(m));
  return names;
}

Metric parse_metric(std::string_view name) {
  for (Metric m : kAllMetrics)
    if (metric_name(m) == name) return m;
  throw InputError(fmt::format("unknown metric '{}' (known: {})", name, metric_names()));
}

SumSet sum_set_of(Metric m) { return definition(m).sums; }

double finish_metric(Metric m, const MetricSums& s, const Signals& data) {
  const double value = definition(m).finish(s, data, static_cast<double>(data.size()));
  return std::isfinite(value) ? value : std::numeric_limits<double>::infinity();
}

MetricSums metric_sums(std::span<const double> output, const Signals& data) {
  const std::vector<double>& measured = data.measured();
  if (output.size() != measured.size())
    throw InputError(fmt::format("{}: {} model outputs for {} samples", data.name, output.size(), measured.size()));
  MetricSums s;
  for (std::size_t k = 0; k < output.size(); ++k) {
    if (!std::isfinite(output[k])) {
      const double inf = std::numeric_limits<double>::infinity();
      return {inf, inf, inf, inf, inf};
    }
    const double e = measured[k] - output[k];
    s.abs_weighted += data.w_trapz_s[k] * std::fabs(e);
    s.sq_weighted += data.w_trapz_s[k] * e * e;
    s.abs += std::fabs(e);
    s.sq += e * e;
    s.abs_magnitude += std::fabs(std::fabs(measured[k]) - std::fabs(output[k]));
  }
  return s;
}

std::array<double, kMetricCount> finish_all_metrics(const MetricSums& sums, const Signals& data) {
  std::array<double, kMetricCount> out{};
  for (int i = 0; i < kMetricCount; ++i) out[i] = finish_metric(kAllMetrics[i], sums, data);
  return out;
}

}  // namespace dampbench
