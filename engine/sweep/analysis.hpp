#pragma once
// Analyses of stored results, as pure functions of numbers (engine/sweep/tables.hpp turns them into tables):
//   - regression of identified parameters on operating variables, for every parameter-law form
//     (engine/model/parameter_law.hpp): polynomials by linear least squares (Eigen, QR on a column-scaled
//     Vandermonde matrix: crfd Tables 5–7, mfm eqs. 5–9); products of polynomials by alternating least
//     squares then Levenberg–Marquardt (mfm eqs. 10–11); power and two-Gaussian forms by Levenberg–Marquardt
//     from the best of a grid of linear fits (fdsp eqs. 13–14); with R² and residuals;
//   - Mann–Whitney rank-sum test (exact without ties for small samples, else the normal approximation
//     with tie and continuity corrections);
//   - bootstrap percentile intervals of a mean, from keyed random streams;
//   - fixed-target runtime (evaluations until the best-so-far reaches a target), expected running time and
//     its empirical distribution function (COCO / IOHprofiler style).
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "engine/model/parameter_law.hpp"
#include "engine/sweep/store.hpp"

namespace dampbench::sweep {

struct RegressionFit {
  std::vector<std::string> names;   ///< coefficient names (ParameterLaw::coefficient_names)
  std::vector<double> coefficients;
  std::vector<double> fitted, residuals;  ///< per observation (residual = observed − fitted)
  double sse = 0, r2 = 0, rms_residual = 0;
};

/// InputError when `law` is a form fit_law does not fit (sat, hill, tanh, mono, or products holding them).
void check_regression_law(const ParameterLaw& law, const std::string& parameter);

/// Fits `law` of parameter `parameter` to observations y_i at operating variables x_i (least squares).
/// Products of polynomials are reported with every factor after the first scaled to a constant term of 1.
/// InputError when there are fewer observations than coefficients or a variable is missing.
RegressionFit fit_law(const ParameterLaw& law, const std::string& parameter,
                      std::span<const std::map<std::string, double>> variables, std::span<const double> y);

struct RankSum {
  double U = 0;   ///< Mann–Whitney U of the first sample: pairs (a_i, b_j) with a_i > b_j, ties counting ½
  double z = 0;   ///< normal-approximation statistic (0 when exact)
  double p = 1;   ///< two-sided p-value
  bool exact = false;
};
/// Two-sided Mann–Whitney test of a against b. Exact when there are no ties and both samples have at most
/// 25 values; otherwise normal with tie correction and continuity correction. Empty samples give p = 1.
RankSum mann_whitney(std::span<const double> a, std::span<const double> b);

struct Interval {
  double mean = 0, lower = 0, upper = 0;
};
/// Percentile bootstrap interval of the mean (`resamples` resamples from the keyed stream `key`, level e.g.
/// 0.95; type-7 quantiles). Non-finite values make every field +inf.
Interval bootstrap_mean(std::span<const double> values, std::uint64_t key, int resamples = 2000, double level = 0.95);

/// Evaluations until the best-so-far first reaches value ≤ target (-1 if never).
long long first_hit(const std::vector<TracePoint>& trace, double target);

struct TargetRuntime {
  int runs = 0, successes = 0;
  double ert = 0;  ///< expected running time: Σ evaluations (hit time, or all for a failed run) / successes (inf if none)
};
/// hits[i] = first_hit of run i (or -1), spent[i] = its evaluations.
TargetRuntime expected_runtime(std::span<const long long> hits, std::span<const long long> spent);

/// The median and interquartile band over runs of the best-so-far metric, at `points` evaluation counts spaced
/// evenly in log scale from the earliest first trace point to the largest last one (the report's convergence
/// curves). A run counts at e from its first trace point on (its best-so-far is the value of its last point at
/// or before e); quantiles are type 7 over the runs that count; NaN where none does.
struct ConvergenceBand {
  std::vector<double> evaluations, median, lower_quartile, upper_quartile;
  std::vector<int> runs;  ///< how many runs count at each point
};
ConvergenceBand convergence_band(std::span<const std::vector<TracePoint>> traces, int points = 60);

/// Fraction of runtimes ≤ each budget (a runtime < 0 never counts).
std::vector<double> ecdf(std::span<const long long> runtimes, std::span<const double> budgets);

}  // namespace dampbench::sweep
