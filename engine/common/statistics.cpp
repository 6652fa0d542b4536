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

}  // namespace dampbench
