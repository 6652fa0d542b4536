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
// disrupted. pm is per gene (S&P mutate per bit of a binary string). When every finite value equals f_min
// (0/0) the ratio is taken as 1 — every member is average — so a collapsed population keeps searching.
// Failed members (+inf) and a population without any finite value use k3 and k4.
#include <cstdint>

#include "optimizers/ga/genetic.hpp"

namespace dampbench {

struct AgaSettings : GeneticSettings {
  double k1 = 1.0;       ///< pc scale for above-average pairs (Srinivas & Patnaik 1994)
  double k2 = 0.5;       ///< pm scale for above-average parents (Srinivas & Patnaik 1994)
  double k3 = 1.0;       ///< pc of below-average pairs (Srinivas & Patnaik 1994)
  double k4 = 0.5;       ///< pm of below-average parents (Srinivas & Patnaik 1994)
  double pm_min = 0.005; ///< floor on pm, S&P's "default mutation rate" that prevents stagnation

  /// Throws InputError ("aga: k1 must be in [0, 1], got 2") for any bad field, shared ones included.
  void validate() const;
};

class Aga final : public GeneticAlgorithm {
 public:
  Aga(const AgaSettings& settings, const Bounds& bounds, std::uint64_t run_key);

 private:
  [[nodiscard]] PairRates rates(double value_a, double value_b, const PopulationStats& stats) const override;
  AgaSettings settings_;
};

}  // namespace dampbench
