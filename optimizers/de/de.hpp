#pragma once
// `de`: differential evolution (Storn & Price 1997, "Differential evolution — a simple and efficient
// heuristic for global optimization over continuous spaces", J. Global Optim. 11), synchronous form: the
// whole generation of trial vectors is built from the current population, evaluated as one batch, then
// each trial replaces its target if it is no worse (u_i ≤ x_i).
//
// Mutant of target i, with r1, r2, r3 distinct indices ≠ i drawn uniformly, and `best` the lowest-valued
// member (ties to the lowest index):
//   rand1bin            v = x_r1 + F · (x_r2 − x_r3)                         (the default, DE/rand/1/bin)
//   best1bin            v = x_best + F · (x_r1 − x_r2)
//   currenttobest1bin   v = x_i + F · (x_best − x_i) + F · (x_r1 − x_r2)
// Binomial crossover: u_j = v_j if U[0, 1) < CR or j = j_rand (one forced mutant component), else x_i,j.
// Bounds: a mutant component outside [lower, upper] is put midway between the target's value and the
// violated bound, u_j = (x_i,j + lower_j) / 2 or (x_i,j + upper_j) / 2 (Zhang & Sanderson 2009, JADE), so
// trials stay inside the box and approach a bound geometrically instead of piling up on it.
// Cost: generation 0 evaluates the initial population (uniform in the box), each later generation the N
// trials: exactly N × generations evaluations.
// Failed candidates (+inf, NaN or −inf; all read as +inf) never replace a finite target; a failed target is
// replaced by any trial. The best individual is never lost (selection is one-to-one and elitist).
// Random numbers: initial member i from stream (run_key, 0, i); trial i of generation g ≥ 1 from
// (run_key, g, i) — indices, j_rand and crossover draws in that order.
#include <cstdint>
#include <string_view>
#include <vector>

#include "optimizers/population.hpp"
#include "optimizers/setting_table.hpp"

namespace dampbench {

enum class DeStrategy { rand1bin, best1bin, currenttobest1bin };

/// Parses "rand1bin", "best1bin" or "currenttobest1bin" (InputError naming the known ones otherwise).
DeStrategy parse_de_strategy(std::string_view name);
std::string_view de_strategy_name(DeStrategy strategy);

struct DeSettings {
  int population = 50;    ///< N; Storn & Price suggest 5–10 × d, 50 matches the suite's default budget
  int generations = 100;  ///< evaluated generations including the initial one; budget N × generations
  DeStrategy strategy = DeStrategy::rand1bin;  ///< DE/rand/1/bin (Storn & Price 1997)
  double F = 0.5;         ///< differential weight, in (0, 2]; 0.5 is Storn & Price's (1997) initial choice
  double CR = 0.9;        ///< crossover rate, in [0, 1]; 0.9 is Storn & Price's (1997) choice for fast
                          ///< convergence (0.1 for separable functions)

  /// Throws InputError: population < 4, generations < 1, F outside (0, 2], CR outside [0, 1].
  void validate() const;
};

/// de's number settings (setting_table.hpp); `strategy` is a choice the registry reads.
const SettingTable<DeSettings>& de_setting_table();

class De final : public PopulationOptimizer {
 public:
  De(const DeSettings& settings, const Bounds& bounds, std::uint64_t run_key);

  void ask(CandidateBatch& batch, int first) override;
  void tell(std::span<const double> values) override;

 private:
  void make_trials();
  double& u(int i, int j) { return trials_[static_cast<std::size_t>(i) * dim_ + j]; }

  DeSettings settings_;
  std::vector<double> values_, trials_;  ///< values of the population; trials row-major N × dim
};

}  // namespace dampbench
