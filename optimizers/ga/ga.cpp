#include "optimizers/ga/ga.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench {

GaSettings GaSettings::lssvm() {
  GaSettings s;
  s.pc = 0.6;
  s.pm = 0.03;
  s.population = 50;
  s.generations = 500;
  // Operators as the preset was measured with (tests/unit/optimizers/test_ga.cpp): with ga's own η_c = 2 and ⌈N/10⌉ elites
  // the slow, mutation-poor paper GA converges 10× less far on the 5-D sphere (18th best 2.2e-6 against 2.2e-7).
  s.eta_c = 15;
  s.elites = 1;
  return s;
}

void GaSettings::validate() const {
  GeneticSettings::validate("ga");
  check_ranges("ga", ga_setting_table(), *this);
}

const SettingTable<GaSettings>& ga_setting_table() {
  static const SettingTable<GaSettings> table = joined<GaSettings>(
      {{"pc", &GaSettings::pc, kProbability, "crossover probability per pair"},
       {"pm", &GaSettings::pm, kProbability, "mutation probability per gene", "1/d for d free parameters"}},
      rebased<GaSettings>(genetic_setting_table()));
  return table;
}

Ga::Ga(const GaSettings& settings, const Bounds& bounds, std::uint64_t run_key)
    : GeneticAlgorithm(validated(settings), bounds, run_key), pc_(settings.pc),
      pm_(settings.pm.value_or(1.0 / std::max(bounds.dim(), 1))) {}

GeneticAlgorithm::PairRates Ga::rates(double, double, const PopulationStats&) const { return {pc_, {pm_, pm_}}; }

}  // namespace dampbench
