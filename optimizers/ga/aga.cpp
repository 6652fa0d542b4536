#include "optimizers/ga/aga.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench {

void AgaSettings::validate() const {
  GeneticSettings::validate("aga");
  check_ranges("aga", aga_setting_table(), *this);
}

const SettingTable<AgaSettings>& aga_setting_table() {
  static const SettingTable<AgaSettings> table = joined<AgaSettings>(
      {{"k1", &AgaSettings::k1, kProbability, "pc scale for above-average pairs"},
       {"k2", &AgaSettings::k2, kProbability, "pm scale for above-average parents"},
       {"k3", &AgaSettings::k3, kProbability, "pc of below-average pairs"},
       {"k4", &AgaSettings::k4, kProbability, "pm of below-average parents"},
       {"pm_min", &AgaSettings::pm_min, kProbability, "floor on pm", "1/(2d) for d free parameters"}},
      rebased<AgaSettings>(genetic_setting_table()));
  return table;
}

namespace {

/// Position of f between the best and the mean: 0 at f_min, 1 at f_avg; −1 when f is worse
/// than average, failed, or there is no finite mean.
double relative_rank(double f, double f_min, double f_avg) {
  if (!std::isfinite(f) || !std::isfinite(f_avg) || f > f_avg) return -1;
  const double spread = f_avg - f_min;
  return spread > 0 ? (f - f_min) / spread : 1.0;
}

}  // namespace

double aga_crossover_probability(const AgaSettings& s, double f_pair, double f_min, double f_avg) {
  const double r = relative_rank(f_pair, f_min, f_avg);
  return r < 0 ? s.k3 : s.k1 * r;
}

double aga_mutation_probability(const AgaSettings& s, double f_parent, double f_min, double f_avg, int dim) {
  const double r = relative_rank(f_parent, f_min, f_avg);
  return std::max(r < 0 ? s.k4 : s.k2 * r, s.pm_min.value_or(0.5 / std::max(dim, 1)));
}

Aga::Aga(const AgaSettings& settings, const Bounds& bounds, std::uint64_t run_key)
    : GeneticAlgorithm(validated(settings), bounds, run_key), settings_(settings) {}

GeneticAlgorithm::PairRates Aga::rates(double value_a, double value_b, const PopulationStats& stats) const {
  const double f_min = stats.best, f_avg = stats.mean_finite;
  return {aga_crossover_probability(settings_, std::min(value_a, value_b), f_min, f_avg),
          {aga_mutation_probability(settings_, value_a, f_min, f_avg, dim_),
           aga_mutation_probability(settings_, value_b, f_min, f_avg, dim_)}};
}

}  // namespace dampbench
