#include "engine/model/metrics.hpp"

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench {

std::string_view metric_name(Metric m) {
  switch (m) {
    case Metric::of_abs: return "of_abs";
    case Metric::of_sq: return "of_sq";
    case Metric::rmse: return "rmse";
    case Metric::nrmse: return "nrmse";
    case Metric::mae: return "mae";
    case Metric::crfd_eps: return "crfd_eps";
    case Metric::mfm_E: return "mfm_E";
    case Metric::fdsp_pct: return "fdsp_pct";
    case Metric::fdsp_signed_pct: return "fdsp_signed_pct";
  }
  return "?";
}

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

SumSet sum_set_of(Metric m) {
  switch (m) {
    case Metric::of_abs: return SumSet::abs_weighted;
    case Metric::of_sq: return SumSet::sq_weighted;
    case Metric::rmse:
    case Metric::nrmse:
    case Metric::crfd_eps:
    case Metric::mfm_E: return SumSet::sq;
    case Metric::mae:
    case Metric::fdsp_signed_pct: return SumSet::abs;
    case Metric::fdsp_pct: return SumSet::abs_magnitude;
  }
  return SumSet::every;
}

double finish_metric(Metric m, const MetricSums& s, const Signals& data) {
  const double n = static_cast<double>(data.size());
  double value = 0;
  switch (m) {
    case Metric::of_abs: value = s.abs_weighted / (data.force_std_N * data.duration_s); break;
    case Metric::of_sq: value = s.sq_weighted / (data.force_std_N * data.force_std_N * data.duration_s); break;
    case Metric::rmse: value = std::sqrt(s.sq / n); break;
    case Metric::nrmse: value = std::sqrt(s.sq / n) / data.force_max_abs_N; break;
    case Metric::mae: value = s.abs / n; break;
    case Metric::crfd_eps: value = std::sqrt(0.5 * s.sq / data.force_max_abs_N) * 100.0; break;
    case Metric::mfm_E: value = std::sqrt(s.sq / data.force_sum_sq); break;
    case Metric::fdsp_pct: value = 100.0 * s.abs_magnitude / (n * data.force_max_abs_N); break;
    case Metric::fdsp_signed_pct: value = 100.0 * s.abs / (n * data.force_max_abs_N); break;
  }
  return std::isfinite(value) ? value : std::numeric_limits<double>::infinity();
}

std::array<double, kMetricCount> finish_all_metrics(const MetricSums& sums, const Signals& data) {
  std::array<double, kMetricCount> out{};
  for (int i = 0; i < kMetricCount; ++i) out[i] = finish_metric(kAllMetrics[i], sums, data);
  return out;
}

}  // namespace dampbench
