#pragma once
// `aga`: adaptive genetic algorithm (Srinivas & Patnaik 1994, "Adaptive probabilities of crossover and
// mutation in genetic algorithms", IEEE Trans. SMC 24(4), eqs. (5)–(6)), in minimization form. The
// operators, elitism, bound handling (none needed: children stay in the box), random streams and cost
// (N × generations evaluations, generation 0 included) are the GA's (optimizers/ga/genetic.hpp); only the
// rates adapt. With f_min the population's lowest value and f_avg the mean of its finite values:
//
//   pc = k1 · (f' − f_min) / (f_avg − f_min)  if f' ≤ f_avg,  else k3     (f' = the pair's lower value)
//   pm = k2 · (f  − f_min) / (f_avg − f_min)  if f  ≤ f_avg,  else k4     (f  = the value of the parent
//                                                                          the child descends from)
//   pm ← max(pm, pm_min)
//
// so good solutions are protected (the best gets pc = 0 and pm = pm_min) and below-average ones are
// disrupted. pm is per gene; S&P mutate a binary string per bit. Their floor ("default mutation rate")
// of 0.005 is per bit, and applied per real-coded gene it lets a population of copies of the best
// stagnate: measured with N = 30–50 on the five standard functions of tests/unit/optimizers/test_aga.cpp, 0.005 left
// 2-D Ackley and Rastrigin no better than random sampling of the same budget. The default floor is
// therefore 1/(2d) per gene (half the GA's 1/d rule), the best of 0.005, 0.05, 0.1, 0.2, 1/d and 1/(2d)
// in 2, 5 and 10 dimensions; set pm_min = 0.005 for S&P's literal value. When every finite value equals f_min
// (0/0) the ratio is taken as 1 — every member is average — so a collapsed population keeps searching.
// Failed members (+inf) and a population without any finite value use k3 and k4.
#include <cstdint>
#include <optional>

#include "optimizers/ga/genetic.hpp"

namespace dampbench {

struct AgaSettings : GeneticSettings {
  double k1 = 1.0;       ///< pc scale for above-average pairs (Srinivas & Patnaik 1994)
  double k2 = 0.5;       ///< pm scale for above-average parents (Srinivas & Patnaik 1994)
  double k3 = 1.0;       ///< pc of below-average pairs (Srinivas & Patnaik 1994)
  double k4 = 0.5;       ///< pm of below-average parents (Srinivas & Patnaik 1994)
  std::optional<double> pm_min;  ///< floor on pm; unset: 1/(2d) for d parameters (see above; S&P: 0.005/bit)

  /// Throws InputError ("aga: k1 must be in [0, 1], got 2") for any bad field, shared ones included.
  void validate() const;
};

/// k1 to k4, pm_min, then the genetic operators' settings (setting_table.hpp).
const SettingTable<AgaSettings>& aga_setting_table();

/// pc of a pair whose lower value is f_pair, given the population's f_min and f_avg (finite mean).
[[nodiscard]] double aga_crossover_probability(const AgaSettings& s, double f_pair, double f_min, double f_avg);
/// Per-gene pm of a child whose parent has value f_parent, in a problem of `dim` parameters (floor included).
[[nodiscard]] double aga_mutation_probability(const AgaSettings& s, double f_parent, double f_min, double f_avg,
                                              int dim);

class Aga final : public GeneticAlgorithm {
 public:
  Aga(const AgaSettings& settings, const Bounds& bounds, std::uint64_t run_key);

 private:
  [[nodiscard]] PairRates rates(double value_a, double value_b, const PopulationStats& stats) const override;
  AgaSettings settings_;
};

}  // namespace dampbench
