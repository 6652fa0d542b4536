#pragma once
// `ga`: real-coded genetic algorithm with fixed rates — tournament selection, SBX crossover
// (Deb & Agrawal 1995) with probability pc per pair, polynomial mutation (Deb & Goyal 1996) with
// probability pm per gene, elitism. The generation loop, operators, bound handling (none needed: the
// operators keep children inside the box), random streams and cost (N × generations evaluations,
// generation 0 included) are those of optimizers/ga/genetic.hpp.
//
// Preset `lssvm` (GaSettings::lssvm()): the lssvm paper's GA — pc 0.6, pm 0.03, population 50,
// 500 generations; every other field keeps its default.
#include <cstdint>
#include <optional>

#include "optimizers/ga/genetic.hpp"

namespace dampbench {

struct GaSettings : GeneticSettings {
  double pc = 0.9;  ///< crossover probability per pair (NSGA-II, Deb et al. 2002, with SBX)
  std::optional<double> pm;  ///< mutation probability per gene; unset: 1/d for d parameters, one gene per
                             ///< child on average (NSGA-II, Deb et al. 2002). A fixed 0.1 left the 2-D
                             ///< Rosenbrock runs of tests/test_ga.cpp behind random sampling.

  /// The lssvm paper's settings: pc 0.6, pm 0.03, population 50, 500 generations.
  static GaSettings lssvm();

  /// Throws InputError ("ga: pc must be in [0, 1], got 1.5") for any bad field, shared ones included.
  void validate() const;
};

class Ga final : public GeneticAlgorithm {
 public:
  Ga(const GaSettings& settings, const Bounds& bounds, std::uint64_t run_key);

 private:
  [[nodiscard]] PairRates rates(double value_a, double value_b, const PopulationStats& stats) const override;
  double pc_, pm_;  ///< pm_ resolved from the settings and the dimension
};

}  // namespace dampbench
