#include "optimizers/cmaes/bound_transform.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/kernels/isa.hpp"

namespace dampbench {

namespace {
constexpr double a = kBoundTransformMargin;

/// T(g), written with selects instead of branches and early returns, so that the loop of to_phenotypes()
/// vectorizes; to_phenotype() is the same function, so both give the same bits.
inline double phenotype(double g) {
  const bool finite = std::fabs(g) <= std::numeric_limits<double>::max();  // false for ±inf and NaN
  // Shift into one period [s, s + period), then mirror into [−a, 1 + a].
  const double s = -2 * a - 0.5, period = 2 * (1 + 2 * a);
  double h = finite ? g : 0.5;
  h -= period * std::floor((h - s) / period);
  h = h > 1 + a ? 2 * (1 + a) - h : h;
  h = h < -a ? -2 * a - h : h;
  const double low = (h + a) * (h + a) / (4 * a), high = 1 - (h - 1 - a) * (h - 1 - a) / (4 * a);
  const double y = h < a ? low : h <= 1 - a ? h : high;
  return finite ? std::min(std::max(y, 0.0), 1.0) : 0.5;  // rounding of the shift never leaves the interval
}

/// The loop, compiled per vector level (IsaClones); IEEE arithmetic and floor only, so every level gives the same
/// bits. This file is compiled with -fno-trapping-math (optimizers/CMakeLists.txt), without which GCC keeps the
/// selects as branches and the loop scalar.
struct PhenotypeLoop {
  static void run(const double* g, double* y, std::size_t n) {
#pragma omp simd
    for (std::size_t i = 0; i < n; ++i) y[i] = phenotype(g[i]);
  }
};

}  // namespace

double to_phenotype(double g) { return phenotype(g); }

void to_phenotypes(std::span<const double> g, std::span<double> y) {
  IsaClones<PhenotypeLoop>::call(g.data(), y.data(), g.size());
}

double to_genotype(double y) {
  y = std::clamp(y, 0.0, 1.0);
  if (y < a) return -a + 2 * std::sqrt(a * y);
  if (y > 1 - a) return 1 + a - 2 * std::sqrt(a * (1 - y));
  return y;
}

}  // namespace dampbench
