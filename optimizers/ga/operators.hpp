#pragma once
// The real-coded GA's operators (optimizers/ga/genetic.hpp runs them): tournament selection, bounded SBX
// crossover and bounded polynomial mutation, each from draws given to it (a generation's draws are computed
// beforehand, optimizers/random_draws.hpp), and the elitism's partial order.
//
// Crossing and mutation run in two halves: a scalar pass over a pair or a child decides, from its draws, which
// variables it crosses or which genes it mutates and appends them to a structure of arrays; one vector loop per
// generation (sbx_finish, mutate_all) then computes every crossed variable's or mutated gene's new value, its
// powers through libmvec's vector pow at the active vector level (engine/kernels/isa.hpp). glibc's scalar pow
// would take 13 % of a `ga` fit on the fvd record. A variable's or gene's result depends on its own inputs and the vector
// level only, not on its place in the arrays or how many others there are; like the kernels' exp and log, the
// last bits of pow differ between vector levels.
#include <algorithm>
#include <span>
#include <vector>

#include "engine/common/random.hpp"

namespace dampbench::genetic {

/// Winner of one tournament over `values` (lowest value, ties to the lowest index): one entrant per draw,
/// index ⌊draw · n⌋ (uniform with replacement). Needs at least one draw; values must be NaN-free (+inf allowed).
int tournament(std::span<const double> values, std::span<const double> draws);
/// The same with `size` ≥ 1 entrants drawn from `rng`.
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

/// The variables a generation crosses, one entry each: where the two children's values go in the pool, the parents'
/// values in order (y1 < y2), the bounds, the draw u and whether the children swap (1 or 0). The arrays have room
/// for `clear`'s capacity rounded up to whole blocks of the vector loop (the padding is sbx_finish's).
struct CrossedVariables {
  std::vector<std::size_t> at_a, at_b;
  std::vector<double> y1, y2, lower, upper, u, swap;
  std::vector<double> child_a, child_b;  ///< sbx_finish's results before they go into the pool
  std::size_t count = 0;
  /// Empties the list and makes room for `capacity` variables.
  void clear(std::size_t capacity);
};

/// Bounded SBX (Deb & Agrawal 1995; Deb's NSGA-II code), first half, for one pair of parents: copies them into the
/// children at `pool` offsets at_a and at_b, then decides which variables to cross: variable j (in order) is crossed
/// when its draw is below 1/2 and its parents differ (identical parents: nothing to spread); a crossed variable
/// takes the next two draws as u and the swap. Appends the crossed variables to `crossed` without branching on the
/// draws and returns how many draws it used (at most 3 × the dimension; `draws` must hold that many).
std::size_t sbx_draw(std::span<const double> parent_a, std::span<const double> parent_b, std::span<double> pool,
                     std::size_t at_a, std::size_t at_b, const std::vector<double>& lower,
                     const std::vector<double>& upper, std::span<const double> draws, CrossedVariables& crossed);
/// Second half: every crossed variable's two children, written into `pool`.
void sbx_finish(CrossedVariables& crossed, double eta_c, std::span<double> pool);
/// Both halves for one pair (children as separate spans), drawing from `rng` the draws sbx_draw uses.
void sbx(std::span<const double> parent_a, std::span<const double> parent_b, std::span<double> child_a,
         std::span<double> child_b, const std::vector<double>& lower, const std::vector<double>& upper,
         double eta_c, RandomStream& rng);

/// The genes a generation mutates, one entry each: where the gene is in the pool, its bounds and the draw u. The
/// arrays have room for `clear`'s capacity rounded up to whole blocks of the vector loop (the padding is
/// mutate_all's).
struct MutatedGenes {
  std::vector<std::size_t> at;
  std::vector<double> x, lower, upper, u;
  std::size_t count = 0;
  /// Empties the list and makes room for `capacity` genes.
  void clear(std::size_t capacity);
};

/// Bounded polynomial mutation (Deb & Goyal 1996; NSGA-II code), first half, for one child whose genes sit at pool
/// offsets at … at + dim − 1: gene j (in order) mutates when its draw is below `rate` and then takes the next
/// draw as u. Appends the mutated genes to `mutated` without branching on the draws and returns how many draws
/// it used (at most 2 × the dimension; `draws` must hold that many).
std::size_t mutation_draw(std::size_t at, double rate, const std::vector<double>& lower,
                          const std::vector<double>& upper, std::span<const double> draws, MutatedGenes& mutated);
/// Second half: every mutated gene's new value, read from and written into `pool` (after crossing); a gene whose
/// bounds are equal stays as it is.
void mutate_all(MutatedGenes& mutated, double eta_m, std::span<double> pool);
/// Both halves for one gene in [lower, upper] (one draw from `rng`: u).
double polynomial_mutation(double x, double lower, double upper, double eta_m, RandomStream& rng);

}  // namespace dampbench::genetic
