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
// Powers: a generation draws all its random numbers first, then finishes every crossed variable and every
// mutated gene with one vector pow per stage (pow_each; 4 per crossed variable, 2 per mutated gene, glibc's
// scalar pow took 13 % of a `ga` fit on the fvd record). Same bits for any thread count; like the kernels'
// exp and log, the last bits of pow differ between vector levels (engine/kernels/isa.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "optimizers/population.hpp"
#include "engine/common/random.hpp"

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

namespace genetic {

/// Winner of one tournament over `values` (lowest value, ties to the lowest index); `size` ≥ 1 entrants uniform
/// with replacement. Values must be NaN-free (+inf allowed).
int tournament(std::span<const double> values, int size, RandomStream& rng);

/// The first `count` of 0 … n − 1 in the strict total order `before`, in that order, into `out` (resized to
/// min(count, n)): what std::partial_sort of 0 … n − 1 gives, in one pass that keeps the `count` first seen so far in a
/// sorted buffer. For the few elites of a generation (count ≪ n) most indices fail the first comparison, with
/// the buffer's last, and nothing moves; partial_sort's heap compared and moved at every index.
template <class Before>
void first_in_order(int n, int count, Before before, std::vector<int>& out) {
  count = std::clamp(count, 0, n);
  out.resize(static_cast<std::size_t>(count));
  int kept = 0;
  for (int i = 0; i < n && count > 0; ++i) {
    if (kept == count && !before(i, out[static_cast<std::size_t>(count - 1)])) continue;
    int at = kept < count ? kept++ : count - 1;  // i goes in at `at` or before; the last kept drops out when full
    for (; at > 0 && before(i, out[static_cast<std::size_t>(at - 1)]); --at)
      out[static_cast<std::size_t>(at)] = out[static_cast<std::size_t>(at - 1)];
    out[static_cast<std::size_t>(at)] = i;
  }
}

/// One crossed variable of one pair, drawn by sbx_draw and finished by sbx_finish: the children's rows, the
/// parents' values in order (y1 <= y2), the bounds, the uniform draw u and whether the children swap.
struct SbxGene {
  double* child_a;
  double* child_b;
  int j;
  double y1, y2, lower, upper, u;
  bool swap;
};

/// Bounded SBX on one pair of parents (Deb & Agrawal 1995; NSGA-II code), first half: copies the parents into
/// the children, writes the variables to cross to the front of `crossed` (room for one per variable) and
/// returns how many; draws every random number of the pair.
std::size_t sbx_draw(std::span<const double> parent_a, std::span<const double> parent_b, std::span<double> child_a,
                     std::span<double> child_b, const std::vector<double>& lower, const std::vector<double>& upper,
                     RandomStream& rng, std::span<SbxGene> crossed);
/// Second half: the children's values of every crossed variable. The powers of all variables go through one
/// vector pow per stage (pow_each), which is why crossing is split in two.
void sbx_finish(std::span<const SbxGene> crossed, double eta_c, std::vector<double>& scratch);

/// sbx_draw then sbx_finish for one pair.
void sbx(std::span<const double> parent_a, std::span<const double> parent_b, std::span<double> child_a,
         std::span<double> child_b, const std::vector<double>& lower, const std::vector<double>& upper,
         double eta_c, RandomStream& rng);

/// One gene to mutate: where it is, its bounds and the uniform draw u.
struct MutationGene {
  double* x;
  double lower, upper, u;
};

/// Bounded polynomial mutation (Deb & Goyal 1996; NSGA-II code) of every gene in `genes`, with one vector pow per
/// stage over all of them.
void mutate_all(std::span<const MutationGene> genes, double eta_m, std::vector<double>& scratch);

/// Bounded polynomial mutation of one gene in [lower, upper] (mutate_all of one gene; draws u from rng).
double polynomial_mutation(double x, double lower, double upper, double eta_m, RandomStream& rng);

/// x[i] = x[i]^exponent for every i, with the vector pow of the active vector level (engine/kernels/isa.hpp;
/// libmvec). Elementwise: an element's bits depend on its value and the level only, not on its neighbours,
/// its position or the span's length.
void pow_each(std::span<double> x, double exponent);

}  // namespace genetic

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
  std::vector<genetic::SbxGene> crossed_;        ///< this generation's crossed variables (room for all)
  std::vector<genetic::MutationGene> mutated_;   ///< and mutated genes (room for all)
  std::vector<double> pow_scratch_;
  std::vector<std::array<double, 2>> pair_pm_;   ///< each pair's per-gene mutation probabilities
  std::vector<double> spare_child_;              ///< the unused second child of the last pair when N is odd
  std::vector<double> told_;                     ///< tell's values of the offspring
  std::vector<int> best_parents_, worst_offspring_;  ///< tell's index orders for elitism
  std::vector<double> values_;     ///< values of the parents (population_)
  std::vector<double> offspring_;  ///< the generation being evaluated (generation ≥ 1)
};

/// A told value as the GAs read it: failures (NaN, ±inf) become +inf.
inline double failure_as_inf(double v) { return std::isfinite(v) ? v : std::numeric_limits<double>::infinity(); }

}  // namespace dampbench
