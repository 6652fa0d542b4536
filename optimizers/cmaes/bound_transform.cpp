#include "optimizers/cmaes/bound_transform.hpp"

#include <algorithm>
#include <cmath>

namespace dampbench {

namespace {
constexpr double a = kBoundTransformMargin;
}  // namespace

double to_phenotype(double g) {
  if (!std::isfinite(g)) return 0.5;
  // Shift into one period [s, s + period), then mirror into [−a, 1 + a].
  const double s = -2 * a - 0.5, period = 2 * (1 + 2 * a);
  g -= period * std::floor((g - s) / period);
  if (g > 1 + a) g = 2 * (1 + a) - g;
  if (g < -a) g = -2 * a - g;
  double y;
  if (g < a) y = (g + a) * (g + a) / (4 * a);
  else if (g <= 1 - a) y = g;
  else y = 1 - (g - 1 - a) * (g - 1 - a) / (4 * a);
  return std::clamp(y, 0.0, 1.0);  // rounding of the shift never leaves the interval
}

double to_genotype(double y) {
  y = std::clamp(y, 0.0, 1.0);
  if (y < a) return -a + 2 * std::sqrt(a * y);
  if (y > 1 - a) return 1 + a - 2 * std::sqrt(a * (1 - y));
  return y;
}

}  // namespace dampbench
