#include "engine/sweep/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/random.hpp"
#include "engine/common/statistics.hpp"

namespace dampbench::sweep {
namespace {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

/// Least squares A·c ≈ y with columns scaled to unit norm (well-conditioned for x³ with x ~ 180).
Vec least_squares(const Mat& A, const Vec& y) {
  Vec scale = A.colwise().norm().transpose();
  for (Eigen::Index j = 0; j < scale.size(); ++j)
    if (!(scale[j] > 0)) scale[j] = 1;
  const Mat As = A * scale.cwiseInverse().asDiagonal();
  const Vec cs = As.colPivHouseholderQr().solve(y);
  return cs.cwiseQuotient(scale);
}

double sse_of(const ParameterLaw& law, const std::vector<double>& c, std::span<const std::map<std::string, double>> x,
              std::span<const double> y) {
  double s = 0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double e = y[i] - law.evaluate(c.data(), x[i]);
    s += e * e;
  }
  return std::isfinite(s) ? s : std::numeric_limits<double>::infinity();
}

/// Levenberg–Marquardt on the law's coefficients (central-difference Jacobian, Marquardt scaling).
std::vector<double> levenberg_marquardt(const ParameterLaw& law, std::vector<double> c,
                                        std::span<const std::map<std::string, double>> x, std::span<const double> y,
                                        int max_iterations = 300) {
  const Eigen::Index n = static_cast<Eigen::Index>(y.size()), k = static_cast<Eigen::Index>(c.size());
  auto residuals = [&](const std::vector<double>& p) {
    Vec r(n);
    for (Eigen::Index i = 0; i < n; ++i) r[i] = y[i] - law.evaluate(p.data(), x[i]);
    return r;
  };
  double sse = sse_of(law, c, x, y);
  double lambda = 1e-3;
  for (int it = 0; it < max_iterations && sse > 0; ++it) {
    const Vec r = residuals(c);
    Mat J(n, k);  // d(model)/dc
    for (Eigen::Index j = 0; j < k; ++j) {
      const double h = 1e-6 * std::max(std::fabs(c[j]), 1e-6);
      std::vector<double> up = c, down = c;
      up[j] += h;
      down[j] -= h;
      for (Eigen::Index i = 0; i < n; ++i)
        J(i, j) = (law.evaluate(up.data(), x[i]) - law.evaluate(down.data(), x[i])) / (2 * h);
    }
    if (!J.allFinite()) break;
    const Mat JtJ = J.transpose() * J;
    const Vec g = J.transpose() * r;
    bool improved = false;
    for (int tries = 0; tries < 30 && !improved; ++tries) {
      Mat A = JtJ;
      for (Eigen::Index j = 0; j < k; ++j) A(j, j) += lambda * std::max(JtJ(j, j), 1e-300);
      const Vec step = A.ldlt().solve(g);
      if (!step.allFinite()) {
        lambda *= 10;
        continue;
      }
      std::vector<double> trial = c;
      for (Eigen::Index j = 0; j < k; ++j) trial[j] += step[j];
      const double s = sse_of(law, trial, x, y);
      if (s < sse) {
        const double gain = (sse - s) / sse;
        c = std::move(trial);
        sse = s;
        lambda = std::max(lambda / 10, 1e-15);
        improved = true;
        if (gain < 1e-15) return c;
      } else {
        lambda *= 10;
      }
    }
    if (!improved) break;
  }
  return c;
}

/// Polynomial factor values P_f(x_f) at each observation.
double factor_value(const std::vector<double>& c, int offset, int degree, double x) {
  double s = 0;
  for (int k = degree; k >= 0; --k) s = s * x + c[offset + k];
  return s;
}

std::vector<double> fit_product(const ParameterLaw& law, std::span<const std::map<std::string, double>> x,
                                std::span<const double> y) {
  const auto& factors = law.factors;
  const std::size_t n = y.size();
  std::vector<int> offset;
  int total = 0;
  for (const auto& f : factors) {
    offset.push_back(total);
    total += f.degree + 1;
  }
  std::vector<std::vector<double>> xv(factors.size(), std::vector<double>(n));
  for (std::size_t f = 0; f < factors.size(); ++f)
    for (std::size_t i = 0; i < n; ++i) xv[f][i] = x[i].at(factors[f].variable);
  std::vector<double> c(static_cast<std::size_t>(total), 0.0);
  for (std::size_t f = 1; f < factors.size(); ++f) c[static_cast<std::size_t>(offset[f])] = 1.0;
  const Vec Y = Eigen::Map<const Vec>(y.data(), static_cast<Eigen::Index>(n));
  double previous = std::numeric_limits<double>::infinity();
  // Alternating least squares: each factor in turn, the others held (each step is linear).
  for (int sweep = 0; sweep < 200; ++sweep) {
    for (std::size_t f = 0; f < factors.size(); ++f) {
      const int degree = factors[f].degree;
      Mat A(static_cast<Eigen::Index>(n), degree + 1);
      for (std::size_t i = 0; i < n; ++i) {
        double others = 1;
        for (std::size_t g = 0; g < factors.size(); ++g)
          if (g != f) others *= factor_value(c, offset[g], factors[g].degree, xv[g][i]);
        double p = 1;
        for (int k = 0; k <= degree; ++k, p *= xv[f][i]) A(static_cast<Eigen::Index>(i), k) = p * others;
      }
      const Vec sol = least_squares(A, Y);
      if (!sol.allFinite()) break;
      for (int k = 0; k <= degree; ++k) c[static_cast<std::size_t>(offset[f] + k)] = sol[k];
    }
    const double s = sse_of(law, c, x, y);
    if (!(s < previous * (1 - 1e-13))) break;
    previous = s;
  }
  c = levenberg_marquardt(law, c, x, y);
  // Report every factor after the first with constant term 1 (the product is unchanged).
  for (std::size_t f = 1; f < factors.size(); ++f) {
    const double c0 = c[static_cast<std::size_t>(offset[f])];
    if (!(std::fabs(c0) > 1e-300)) continue;
    for (int k = 0; k <= factors[f].degree; ++k) c[static_cast<std::size_t>(offset[f] + k)] /= c0;
    for (int k = 0; k <= factors[0].degree; ++k) c[static_cast<std::size_t>(offset[0] + k)] *= c0;
  }
  return c;
}

std::vector<double> fit_power(const ParameterLaw& law, std::span<const std::map<std::string, double>> x,
                              std::span<const double> y) {
  const std::size_t n = y.size();
  const Vec Y = Eigen::Map<const Vec>(y.data(), static_cast<Eigen::Index>(n));
  std::vector<double> best;
  double best_sse = std::numeric_limits<double>::infinity();
  for (int step = -60; step <= 60; ++step) {
    if (step == 0) continue;
    const double p = 0.05 * step;
    Mat A(static_cast<Eigen::Index>(n), 2);
    for (std::size_t i = 0; i < n; ++i) {
      A(static_cast<Eigen::Index>(i), 0) = std::pow(x[i].at(law.factors[0].variable), p);
      A(static_cast<Eigen::Index>(i), 1) = 1;
    }
    const Vec s = least_squares(A, Y);
    const std::vector<double> c{s[0], p, s[1]};
    if (const double e = sse_of(law, c, x, y); e < best_sse) {
      best_sse = e;
      best = c;
    }
  }
  if (best.empty()) best = {1, 1, 0};
  return levenberg_marquardt(law, best, x, y, 1000);
}

std::vector<double> fit_gaussian2(const ParameterLaw& law, std::span<const std::map<std::string, double>> x,
                                  std::span<const double> y) {
  const std::size_t n = y.size();
  std::vector<double> xs(n);
  for (std::size_t i = 0; i < n; ++i) xs[i] = x[i].at(law.factors[0].variable);
  const auto [lo_it, hi_it] = std::minmax_element(xs.begin(), xs.end());
  const double lo = *lo_it, range = std::max(*hi_it - lo, 1e-12);
  const Vec Y = Eigen::Map<const Vec>(y.data(), static_cast<Eigen::Index>(n));
  std::vector<double> centres, widths;
  for (int i = 0; i <= 8; ++i) centres.push_back(lo - 0.25 * range + 1.5 * range * i / 8.0);
  for (double w : {0.1, 0.25, 0.5, 1.0, 2.0}) widths.push_back(w * range);
  struct Start {
    double sse;
    std::vector<double> c;
  };
  std::vector<Start> starts;
  for (std::size_t i1 = 0; i1 < centres.size(); ++i1)
    for (double w1 : widths)
      for (std::size_t i2 = i1; i2 < centres.size(); ++i2)
        for (double w2 : widths) {
          Mat A(static_cast<Eigen::Index>(n), 2);
          for (std::size_t i = 0; i < n; ++i) {
            const double g1 = (xs[i] - centres[i1]) / w1, g2 = (xs[i] - centres[i2]) / w2;
            A(static_cast<Eigen::Index>(i), 0) = std::exp(-g1 * g1);
            A(static_cast<Eigen::Index>(i), 1) = std::exp(-g2 * g2);
          }
          const Vec s = least_squares(A, Y);
          std::vector<double> c{s[0], centres[i1], w1, s[1], centres[i2], w2};
          const double e = sse_of(law, c, x, y);
          if (std::isfinite(e)) starts.push_back({e, std::move(c)});
        }
  std::sort(starts.begin(), starts.end(), [](const Start& a, const Start& b) { return a.sse < b.sse; });
  std::vector<double> best = starts.empty() ? std::vector<double>{1, lo, range, 0, lo + range, range} : starts[0].c;
  double best_sse = sse_of(law, best, x, y);
  for (std::size_t s = 0; s < std::min<std::size_t>(8, starts.size()); ++s) {
    auto c = levenberg_marquardt(law, starts[s].c, x, y, 1000);
    if (const double e = sse_of(law, c, x, y); e < best_sse) {
      best_sse = e;
      best = std::move(c);
    }
  }
  // Order the two terms by centre, and report positive widths (the law depends on c² only).
  best[2] = std::fabs(best[2]);
  best[5] = std::fabs(best[5]);
  if (best[4] < best[1]) {
    std::swap(best[0], best[3]);
    std::swap(best[1], best[4]);
    std::swap(best[2], best[5]);
  }
  return best;
}

}  // namespace

void check_regression_law(const ParameterLaw& law, const std::string& parameter) {
  if (law.kind != ParameterLaw::Kind::product || law.polynomial() || law.single(LawFactor::Family::power) ||
      law.single(LawFactor::Family::gauss2))
    return;
  throw InputError(fmt::format("regression of {}: '{}' has no regression fit (regressions fit poly, prod of poly, "
                               "power and gauss2 laws; fit the others as laws of the model with --laws)",
                               parameter, law.text()));
}

RegressionFit fit_law(const ParameterLaw& law, const std::string& parameter,
                      std::span<const std::map<std::string, double>> x, std::span<const double> y) {
  RegressionFit fit;
  fit.names = law.coefficient_names(parameter);
  const std::size_t n = y.size();
  if (x.size() != n) throw std::invalid_argument("fit_law: variables and observations differ in size");
  if (n < fit.names.size())
    throw InputError(fmt::format("regression of {}: {} observations for {} coefficients ({})", parameter, n,
                                 fit.names.size(), law.text()));
  check_regression_law(law, parameter);
  const std::vector<std::string> vars = law.variables();
  for (std::size_t i = 0; i < n; ++i)
    for (const auto& v : vars)
      if (!x[i].count(v)) throw InputError(fmt::format("regression of {}: observation {} has no variable '{}'", parameter, i + 1, v));

  switch (law.kind) {
    case ParameterLaw::Kind::fixed: break;
    case ParameterLaw::Kind::free:
      fit.coefficients = {std::accumulate(y.begin(), y.end(), 0.0) / static_cast<double>(n)};
      break;
    case ParameterLaw::Kind::product:
      if (law.single(LawFactor::Family::power)) {
        fit.coefficients = fit_power(law, x, y);
      } else if (law.single(LawFactor::Family::gauss2)) {
        fit.coefficients = fit_gaussian2(law, x, y);
      } else if (law.factors.size() == 1) {
        const int degree = law.factors[0].degree;
        Mat A(static_cast<Eigen::Index>(n), degree + 1);
        for (std::size_t i = 0; i < n; ++i) {
          const double xi = x[i].at(law.factors[0].variable);
          double p = 1;
          for (int k = 0; k <= degree; ++k, p *= xi) A(static_cast<Eigen::Index>(i), k) = p;
        }
        const Vec c = least_squares(A, Eigen::Map<const Vec>(y.data(), static_cast<Eigen::Index>(n)));
        fit.coefficients.assign(c.data(), c.data() + c.size());
      } else {
        fit.coefficients = fit_product(law, x, y);
      }
      break;
  }
  double mean = std::accumulate(y.begin(), y.end(), 0.0) / static_cast<double>(n), sst = 0;
  for (std::size_t i = 0; i < n; ++i) {
    fit.fitted.push_back(law.evaluate(fit.coefficients.data(), x[i]));
    fit.residuals.push_back(y[i] - fit.fitted.back());
    fit.sse += fit.residuals.back() * fit.residuals.back();
    sst += (y[i] - mean) * (y[i] - mean);
  }
  fit.r2 = sst > 0 ? 1 - fit.sse / sst : (fit.sse == 0 ? 1.0 : 0.0);
  fit.rms_residual = std::sqrt(fit.sse / static_cast<double>(n));
  return fit;
}

RankSum mann_whitney(std::span<const double> a, std::span<const double> b) {
  RankSum out;
  const std::size_t na = a.size(), nb = b.size(), n = na + nb;
  if (na == 0 || nb == 0) return out;
  std::vector<std::pair<double, int>> all;
  for (double v : a) all.emplace_back(v, 0);
  for (double v : b) all.emplace_back(v, 1);
  std::sort(all.begin(), all.end(), [](const auto& p, const auto& q) { return p.first < q.first; });
  double rank_a = 0, tie_term = 0;
  bool ties = false;
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i;
    while (j < n && all[j].first == all[i].first) ++j;
    const double t = static_cast<double>(j - i);
    const double rank = (static_cast<double>(i + 1) + static_cast<double>(j)) / 2;  // mean of ranks i+1 … j
    for (std::size_t k = i; k < j; ++k)
      if (all[k].second == 0) rank_a += rank;
    if (t > 1) {
      ties = true;
      tie_term += t * t * t - t;
    }
    i = j;
  }
  const double dna = static_cast<double>(na), dnb = static_cast<double>(nb), dn = static_cast<double>(n);
  out.U = rank_a - dna * (dna + 1) / 2;
  if (!ties && na <= 25 && nb <= 25) {
    // Exact null distribution of U: f[i][j][u] arrangements of i a's and j b's with statistic u.
    const int U_max = static_cast<int>(na * nb);
    std::vector<std::vector<std::vector<double>>> f(na + 1, std::vector<std::vector<double>>(nb + 1));
    for (std::size_t i = 0; i <= na; ++i)
      for (std::size_t j = 0; j <= nb; ++j) {
        f[i][j].assign(static_cast<std::size_t>(i * j + 1), 0.0);
        if (i == 0 || j == 0) {
          f[i][j][0] = 1;
          continue;
        }
        // The largest value is an a (it exceeds all j b's: adds j) or a b (adds nothing).
        for (std::size_t u = 0; u <= i * j; ++u) {
          double v = 0;
          if (u >= j && u - j < f[i - 1][j].size()) v += f[i - 1][j][u - j];
          if (u < f[i][j - 1].size()) v += f[i][j - 1][u];
          f[i][j][u] = v;
        }
      }
    const auto& dist = f[na][nb];
    const double total = std::accumulate(dist.begin(), dist.end(), 0.0);
    const int u = static_cast<int>(std::lround(out.U));
    double lower = 0, upper = 0;
    for (int k = 0; k <= U_max; ++k) {
      if (k <= u) lower += dist[static_cast<std::size_t>(k)];
      if (k >= u) upper += dist[static_cast<std::size_t>(k)];
    }
    out.p = std::min(1.0, 2 * std::min(lower, upper) / total);
    out.exact = true;
    return out;
  }
  const double mean = dna * dnb / 2;
  const double var = dna * dnb / 12 * ((dn + 1) - tie_term / (dn * (dn - 1)));
  if (!(var > 0)) return out;
  const double d = out.U - mean;
  const double corrected = std::fabs(d) <= 0.5 ? 0.0 : std::fabs(d) - 0.5;
  out.z = (d < 0 ? -1 : 1) * corrected / std::sqrt(var);
  out.p = std::min(1.0, std::erfc(std::fabs(out.z) / std::sqrt(2.0)));
  return out;
}

Interval bootstrap_mean(std::span<const double> values, std::uint64_t key, int resamples, double level) {
  Interval out;
  const std::size_t n = values.size();
  if (n == 0) return {std::nan(""), std::nan(""), std::nan("")};
  if (!std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); })) {
    const double inf = std::numeric_limits<double>::infinity();
    return {inf, inf, inf};
  }
  out.mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(n);
  std::vector<double> means(static_cast<std::size_t>(resamples));
  RandomStream rng(key);
  for (auto& m : means) {
    double s = 0;
    for (std::size_t i = 0; i < n; ++i) s += values[static_cast<std::size_t>(rng.uniform() * static_cast<double>(n))];
    m = s / static_cast<double>(n);
  }
  std::sort(means.begin(), means.end());
  out.lower = sorted_quantile(means, (1 - level) / 2);
  out.upper = sorted_quantile(means, 1 - (1 - level) / 2);
  return out;
}

long long first_hit(const std::vector<TracePoint>& trace, double target) {
  for (const auto& p : trace)
    if (p.value <= target) return p.evaluations;
  return -1;
}

TargetRuntime expected_runtime(std::span<const long long> hits, std::span<const long long> spent) {
  TargetRuntime t;
  t.runs = static_cast<int>(hits.size());
  double total = 0;
  for (std::size_t i = 0; i < hits.size(); ++i) {
    if (hits[i] >= 0) {
      ++t.successes;
      total += static_cast<double>(hits[i]);
    } else {
      total += static_cast<double>(spent[i]);
    }
  }
  t.ert = t.successes > 0 ? total / t.successes : std::numeric_limits<double>::infinity();
  return t;
}

std::vector<double> ecdf(std::span<const long long> runtimes, std::span<const double> budgets) {
  std::vector<double> out;
  for (double b : budgets) {
    std::size_t hit = 0;
    for (long long r : runtimes)
      if (r >= 0 && static_cast<double>(r) <= b) ++hit;
    out.push_back(runtimes.empty() ? 0.0 : static_cast<double>(hit) / static_cast<double>(runtimes.size()));
  }
  return out;
}

ConvergenceBand convergence_band(std::span<const std::vector<TracePoint>> traces, int points) {
  ConvergenceBand band;
  long long first = std::numeric_limits<long long>::max(), last = 0;
  for (const auto& t : traces)
    if (!t.empty()) {
      first = std::min(first, std::max<long long>(1, t.front().evaluations));
      last = std::max(last, t.back().evaluations);
    }
  if (last == 0 || points < 1) return band;
  const double ratio = static_cast<double>(std::max(last, first)) / static_cast<double>(first);
  std::vector<double> values;
  for (int i = 0; i < points; ++i) {
    const double e = points == 1 ? static_cast<double>(last)
                                 : static_cast<double>(first) * std::pow(ratio, static_cast<double>(i) / (points - 1));
    // The last grid point is exactly the largest evaluation count (pow may round it below).
    const double at = i == points - 1 ? static_cast<double>(last) : e;
    values.clear();
    for (const auto& t : traces) {
      const auto after = std::upper_bound(t.begin(), t.end(), at,
                                          [](double x, const TracePoint& p) { return x < static_cast<double>(p.evaluations); });
      if (after != t.begin()) values.push_back(std::prev(after)->value);
    }
    band.evaluations.push_back(at);
    band.runs.push_back(static_cast<int>(values.size()));
    std::sort(values.begin(), values.end());
    band.median.push_back(sorted_quantile(values, 0.5));
    band.lower_quartile.push_back(sorted_quantile(values, 0.25));
    band.upper_quartile.push_back(sorted_quantile(values, 0.75));
  }
  return band;
}

}  // namespace dampbench::sweep
