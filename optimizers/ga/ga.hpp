#pragma once
// `ga`: real-coded genetic algorithm with fixed rates — tournament selection, SBX crossover
// (Deb & Agrawal 1995) with probability pc per pair, polynomial mutation (Deb & Goyal 1996) with
// probability pm per gene, elitism. The generation loop, operators, bound handling (none needed: the
// operators keep children inside the box), random streams and cost (N × generations evaluations,
// generation 0 included) are those of optimizers/ga/genetic.hpp.
//
// Preset `lssvm` (GaSettings::lssvm()): the lssvm paper's GA — pc 0.6, pm 0.03, population 50,
// 500 generations; SBX η_c 15 and one elite (the shared defaults; see lssvm()); the rest as ga's.
#include <cstdint>
#include <optional>

#include "optimizers/ga/genetic.hpp"

namespace dampbench {

struct GaSettings : GeneticSettings {
  /// `ga`'s own defaults over the shared ones: SBX η_c = 2, Deb & Agrawal's (1995) broad setting, and
  /// ⌈N/10⌉ elites (5 of 50), because with 50 × 100 (tests/unit/optimizers/test_ga.cpp, seeds 7…) they bring far more runs
  /// to 1.02 × the noise RMSE on a noisy Kwok record than η_c 15 with one elite (23 of 40 against 6 of 40), and
  /// more within 2 % of the best on the fvd test-3 record (gv_quadratic_elastic: 29 of 40 against 20). The
  /// standard functions (tests/unit/optimizers/test_optimizer_conformance.cpp) improve or hold everywhere (e.g. 10-D
  /// Rastrigin's 18th-best of 20 0.004 against 0.17, 10-D sphere 4e-6 against 6e-4) except 5-D Rosenbrock,
  /// whose runs stop in the local minimum near 3.99 more often (18th best 4.0 against 2.1). A larger η_m (60)
  /// brings Kwok to 33 of 40 but 2-D Rastrigin to 0.99, so it is not taken. docs/performance.md has how the
  /// Kwok counts vary with the code.
  GaSettings() {
    eta_c = 2;
    elite_share = 0.1;
  }
  double pc = 0.9;  ///< crossover probability per pair (NSGA-II, Deb et al. 2002, with SBX)
  std::optional<double> pm;  ///< mutation probability per gene; unset: 1/d for d parameters, one gene per
                             ///< child on average (NSGA-II, Deb et al. 2002). A fixed 0.1 left the 2-D
                             ///< Rosenbrock runs of tests/unit/optimizers/test_ga.cpp behind random sampling.

  /// The lssvm paper's settings: pc 0.6, pm 0.03, population 50, 500 generations (η_c 15, one elite).
  static GaSettings lssvm();

  /// Throws InputError ("ga: pc must be in [0, 1], got 1.5") for any bad field, shared ones included.
  void validate() const;
};

/// pc, pm, then the genetic operators' settings (setting_table.hpp).
const SettingTable<GaSettings>& ga_setting_table();

class Ga final : public GeneticAlgorithm {
 public:
  Ga(const GaSettings& settings, const Bounds& bounds, std::uint64_t run_key);

 private:
  [[nodiscard]] PairRates rates(double value_a, double value_b, const PopulationStats& stats) const override;
  double pc_, pm_;  ///< pm_ resolved from the settings and the dimension
};

}  // namespace dampbench
