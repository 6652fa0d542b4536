#include "optimizers/ga/aga.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/error.hpp"

namespace dampbench {

void AgaSettings::validate() const {
  GeneticSettings::validate("aga");
  const auto probability = [](const char* name, double v) {
    if (!(v >= 0 && v <= 1)) throw InputError(fmt::format("aga: {} must be in [0, 1], got {}", name, v));
  };
  probability("k1", k1);
  probability("k2", k2);
  probability("k3", k3);
  probability("k4", k4);
  probability("pm_min", pm_min);
}

namespace {

const AgaSettings& validated(const AgaSettings& s) {
  s.validate();
  return s;
}

/// Position of f between the best and the mean: 0 at f_min, 1 at f_avg; −1 when f is worse
/// than average, failed, or there is no finite mean.
double relative_rank(double f, double f_min, double f_avg) {
  if (!std::isfinite(f) || !std::isfinite(f_avg) || f > f_avg) return -1;
  const double spread = f_avg - f_min;
  return spread > 0 ? (f - f_min) / spread : 1.0;
}

}  // namespace

Aga::Aga(const AgaSettings& settings, const Bounds& bounds, std::uint64_t run_key)
    : GeneticAlgorithm(validated(settings), bounds, run_key), settings_(settings) {}

GeneticAlgorithm::PairRates Aga::rates(double value_a, double value_b, const PopulationStats& stats) const {
  const auto scaled = [&](double f, double k_good, double k_bad) {
    const double r = relative_rank(f, stats.best, stats.mean_finite);
    return r < 0 ? k_bad : k_good * r;
  };
  PairRates rates{};
  rates.pc = scaled(std::min(value_a, value_b), settings_.k1, settings_.k3);
  rates.pm[0] = std::max(scaled(value_a, settings_.k2, settings_.k4), settings_.pm_min);
  rates.pm[1] = std::max(scaled(value_b, settings_.k2, settings_.k4), settings_.pm_min);
  return rates;
}

}  // namespace dampbench
