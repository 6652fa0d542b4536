#pragma once
// Error metrics between measured and model force. Kernels accumulate four sums per candidate while the
// model runs (no candidates × samples force matrix); the metrics are finished from the sums.
#include <array>
#include <span>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include "engine/record/signals.hpp"

namespace dampbench {

enum class Metric {
  of_abs,  ///< fvd eq. 7 with |·|: ∫|F_m − F| dt / (σ(F_m)·(t_end − t_start)), trapezoid rule
  of_sq,   ///< squared variant: ∫(F_m − F)² dt / (σ(F_m)²·(t_end − t_start))
  rmse,    ///< sqrt(Σ e² / N) [N]
  nrmse,   ///< rmse / max|F_m|
  mae,     ///< Σ|e| / N [N]
  crfd_eps,         ///< crfd eq. 7.6 as printed: sqrt(½·Σe² / T_max)·100 (not dimensionless; nrmse·100 is
                    ///< the normalized RMS error the paper describes)
  mfm_E,            ///< mfm eq. 12: sqrt(Σe² / ΣF_m²)
  fdsp_pct,         ///< fdsp eq. 8 as printed: 100·Σ||F_m| − |F|| / (N·max|F_m|) (compares magnitudes)
  fdsp_signed_pct,  ///< its signed variant: 100·Σ|F_m − F| / (N·max|F_m|)
};
inline constexpr std::array kAllMetrics = {Metric::of_abs,   Metric::of_sq, Metric::rmse,     Metric::nrmse,
                                           Metric::mae,      Metric::crfd_eps, Metric::mfm_E, Metric::fdsp_pct,
                                           Metric::fdsp_signed_pct};
inline constexpr int kMetricCount = static_cast<int>(kAllMetrics.size());

std::string_view metric_name(Metric m);
/// Throws InputError "unknown metric 'x' (known: <metric_names()>)".
Metric parse_metric(std::string_view name);
/// "of_abs, of_sq, rmse, nrmse, mae, crfd_eps, ...": every metric's name, in the order of kAllMetrics.
std::string metric_names();

/// Per-candidate sums over the samples, e = F_measured − F_model.
struct MetricSums {
  double abs_weighted = 0;  ///< Σ w_k |e_k|  (trapezoid weights, s·N)
  double sq_weighted = 0;   ///< Σ w_k e_k²
  double abs = 0;           ///< Σ |e_k|
  double sq = 0;            ///< Σ e_k²
  double abs_magnitude = 0; ///< Σ ||F_m,k| − |F_k|| (fdsp eq. 8)
};

/// Which of the MetricSums an evaluation computes: every one, or the one sum a metric is finished from
/// (an optimizer's objective needs one, and for a cheap law such as fvd.gv_linear_elastic the unused sums are a
/// large share of the block's arithmetic: docs/performance.md).
/// The sums not computed are NaN, so a metric finished from them is +inf, never a wrong number.
enum class SumSet { every, abs_weighted, sq_weighted, abs, sq, abs_magnitude };

/// The sum `m` is finished from.
SumSet sum_set_of(Metric m);

/// The metric from the sums; +inf whenever the candidate's force was NaN or Inf anywhere (a NaN never
/// reaches a statistic).
double finish_metric(Metric m, const MetricSums& sums, const Signals& data);

/// Every metric, in the order of kAllMetrics.
std::array<double, kMetricCount> finish_all_metrics(const MetricSums& sums, const Signals& data);

/// The sums of a model output given as a series (a model outside the lane kernels: the LS-SVM's free run), with the
/// kernels' definitions: e = the record's measured output − `output`, trapezoid weights w_k. Every sum is +inf when
/// `output` is not finite somewhere; InputError when its length is not the record's.
MetricSums metric_sums(std::span<const double> output, const Signals& data);

}  // namespace dampbench
