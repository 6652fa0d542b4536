#pragma once
// The generational real-coded GA that `ga` (optimizers/ga/ga.hpp) and `aga` (optimizers/ga/aga.hpp) share:
// initialization, tournament selection, SBX crossover, polynomial mutation, elitist replacement and the
// ask/tell bookkeeping. The two algorithms differ only in how each pair's crossover probability and each
// child's per-gene mutation probability are chosen (GeneticAlgorithm::rates).
//
// One generation, for pair k = 0 … ⌈N/2⌉ − 1 (children 2k and 2k + 1; an odd N drops the last second child):
//   1. two parents by tournament selection (`tournament` entrants drawn uniformly with replacement; the
//      lowest value wins, ties to the lowest index; Goldberg & Deb 1991);
//   2. with probability pc, simulated binary crossover (SBX, Deb & Agrawal 1995) in its bounded form
//      (Deb's NSGA-II reference code): each variable is crossed with probability 1/2, the spread factor
//      is drawn so that children never leave [lower, upper], and the two children are swapped with
//      probability 1/2; otherwise the children are copies of the parents;
//   3. each gene of child c mutated with probability pm[c] by bounded polynomial mutation
//      (Deb & Goyal 1996), bounded form of Deb's NSGA-II code, whose perturbation never leaves the box.
//   4. after the offspring are evaluated, elitism: the `elites` best parents replace the `elites` worst
//      offspring, each only where the parent is strictly better (so the best value never gets worse).
// Bounds: the initial population is uniform in the box and both operators keep children inside it, so
// no repair is needed; a parameter with lower == upper stays fixed.
// Cost: every generation, including generation 0 (the initial population), evaluates exactly N
// candidates, so a run costs N × generations evaluations; elites are carried over, not re-evaluated.
// Failed candidates (+inf, NaN or −inf; all read as +inf) lose every tournament and elitism comparison
// against a finite one.
// Random numbers: initial member i from stream (run_key, 0, i); in generation g ≥ 1 pair k selects from
// (run_key, g, k, "select"), crosses over from (run_key, g, k, "crossover"), and child c mutates from
// (run_key, g, c, "mutate"). Nothing depends on evaluation order or batch layout.
// Order of work: a generation computes all its draws first (optimizers/ga/generation_draws.hpp, as vector
// loops), then selects, decides what to cross and mutate, and finishes every crossed variable and mutated gene in
// one vector loop each (optimizers/ga/operators.hpp). Same bits for any thread count; like the kernels' exp and
// log, the last bits of the operators' pow differ between vector levels (engine/kernels/isa.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "engine/common/random.hpp"
#include "optimizers/ga/generation_draws.hpp"
#include "optimizers/ga/operators.hpp"
#include "optimizers/population.hpp"
#include "optimizers/setting_table.hpp"

namespace dampbench {

/// Settings shared by the GAs. Validated by validate(algorithm), whose messages start with `algorithm`.
struct GeneticSettings {
  int population = 50;    ///< N, candidates per generation (as the fvd paper's PSO; the lssvm preset also uses 50)
  int generations = 100;  ///< evaluated generations including the initial one; budget N × generations
  int tournament = 2;     ///< tournament size: binary tournament (Goldberg & Deb 1991)
  std::optional<int> elites;  ///< best parents kept over the worst offspring each generation (De Jong 1975);
                              ///< unset: ⌈elite_share × N⌉, at least 1 (elite_count())
  double elite_share = 0;     ///< the unset rule's share of N: 0 (one elite) here; `ga` uses 0.1
  double eta_c = 15;      ///< SBX distribution index: larger keeps children nearer their parents; NSGA-II
                          ///< (Deb et al. 2002) uses 20, pymoo's GA 15 — the broader of the two (`ga`: 2)
  double eta_m = 20;      ///< polynomial mutation distribution index (NSGA-II, Deb et al. 2002)

  /// Elites in use: `elites` if set, otherwise ⌈elite_share × N⌉, at least 1.
  [[nodiscard]] int elite_count() const {
    return elites.value_or(std::max(1, static_cast<int>(std::ceil(elite_share * population))));
  }

  /// Throws InputError: population < 4, generations < 1, tournament outside [2, population], elites
  /// outside [0, population / 2], eta_c or eta_m negative or not finite.
  void validate(std::string_view algorithm) const;
};

/// The operator settings every genetic algorithm reads (setting_table.hpp): eta_c, eta_m, tournament, elites.
const SettingTable<GeneticSettings>& genetic_setting_table();

/// The generational GA; subclasses choose the rates.
class GeneticAlgorithm : public PopulationOptimizer {
 public:
  void ask(CandidateBatch& batch, int first) override;
  void tell(std::span<const double> values) override;

 protected:
  /// Objective values of the current population (failed candidates as +inf).
  struct PopulationStats {
    double best;          ///< lowest value (+inf if every member failed)
    double mean_finite;   ///< mean of the finite values (+inf if there are none)
  };
  /// Probabilities used for one pair: crossover pc and per-gene mutation pm of each child.
  struct PairRates {
    double pc;
    std::array<double, 2> pm;
  };

  GeneticAlgorithm(const GeneticSettings& settings, const Bounds& bounds, std::uint64_t run_key);
  /// Rates for the pair of parents with these values (child c descends from parent c).
  [[nodiscard]] virtual PairRates rates(double value_a, double value_b, const PopulationStats& stats) const = 0;

 private:
  void breed();

  GeneticSettings settings_;
  // Scratch of breed and tell, kept between generations so that a generation allocates nothing.
  GenerationDraws draws_;
  genetic::CrossedVariables crossed_;            ///< this generation's crossed variables
  genetic::MutatedGenes mutated_;                ///< and mutated genes
  std::vector<std::array<double, 2>> pair_pm_;   ///< each pair's per-gene mutation probabilities
  std::vector<double> told_;                     ///< tell's values of the offspring
  std::vector<int> best_parents_, worst_offspring_;  ///< tell's index orders for elitism
  std::vector<double> values_;     ///< values of the parents (population_)
  std::vector<double> offspring_;  ///< the generation being evaluated (generation ≥ 1)
  // Both pools (population_ and offspring_, swapped every generation) have a row N past the population: when N is
  // odd, the last pair's second child is bred there and never evaluated.
};

/// A told value as the GAs read it: failures (NaN, ±inf) become +inf.
inline double failure_as_inf(double v) { return std::isfinite(v) ? v : std::numeric_limits<double>::infinity(); }

}  // namespace dampbench
