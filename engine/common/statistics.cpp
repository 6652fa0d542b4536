#include "engine/common/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dampbench {

Summary summarize(std::span<const double> values) {
  Summary s;
  s.count = static_cast<int>(values.size());
  if (values.empty()) return s;
  const bool all_finite = std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
  if (!all_finite) {
    const double inf = std::numeric_limits<double>::infinity();
    s.mean = s.max = s.min = s.std = inf;
    return s;
  }
  double sum = 0;
  s.min = s.max = values[0];
  for (double v : values) {
    sum += v;
    s.min = std::min(s.min, v);
    s.max = std::max(s.max, v);
  }
  s.mean = sum / s.count;
  double ss = 0;
  for (double v : values) ss += (v - s.mean) * (v - s.mean);
  s.std = s.count > 1 ? std::sqrt(ss / (s.count - 1)) : 0.0;
  return s;
}

double sorted_quantile(const std::vector<double>& v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double h = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  const double frac = h - static_cast<double>(lo);
  if (frac == 0 || v[lo] == v[hi]) return v[lo];
  if (!std::isfinite(v[hi])) return std::numeric_limits<double>::infinity();
  return v[lo] + (v[hi] - v[lo]) * frac;
}

}  // namespace dampbench
