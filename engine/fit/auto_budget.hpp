#pragma once
// The automatic budget (`fit --budget auto`, fit's default; sweep optimizer entries that set no budget): the runs
// of a fit are extended by restarts until the convergence verdict holds (convergence.hpp) or a cap is reached.
//
//   round 0     the fixed budget: R runs of population P × I iterations (the same bits as a fixed budget)
//   round k ≥ 1 every run restarts with population P·2^k and the same I, its streams keyed (seed, task, k, run)
//   run r       the chain of its rounds: best = the best over the chain, history = the chain's best-so-far
//               over the evaluations of every round, restarts counted
//
// A restart with a larger population, not more iterations (IPOP, Auger & Hansen 2005), so that schedules over
// the iterations (PSO's inertia, AGA's rates, a hybrid's hand-over to its local stage) keep their meaning, and a
// larger population makes every algorithm more global. After each round: converged → stop; otherwise the next
// round starts only if it fits in the cap, its cost estimated as twice the last round's; else stop at the cap.
// The schedule depends only on results, so the same inputs give the same bits, unless the optional wall-clock
// cap fires (and then the outcome says so).
#include <string>
#include <vector>

#include "engine/identification/identification.hpp"
#include "optimizers/registry.hpp"

namespace dampbench {

/// The largest population a restart may have: a round's lockstep batch holds runs × population candidates, so a
/// cap far above the default must not grow it without bound.
inline constexpr int kMaxAutoPopulation = 1 << 16;

struct AutoBudget {
  OptimizerSpec optimizer;        ///< round 0's optimizer; later rounds double its population
  long long max_evaluations = 0;  ///< cap over every round and run (local phases included); 0 = default_cap
  double max_seconds = 0;         ///< wall-clock cap; 0 = none
  int max_population = kMaxAutoPopulation;  ///< no round beyond this population
};

/// What the restarts did, for the output.
struct AutoBudgetReport {
  std::vector<int> populations;  ///< of each round run, in order
  int max_population = 0;        ///< the population limit in force
  long long evaluations = 0;     ///< spent over every round and run
  long long cap = 0;             ///< the evaluation cap in force
  /// "converged"; "cap" (the next round would pass the cap, or round 0 was cut by it); "time cap";
  /// "population limit" (the next round's population would pass AutoBudget::max_population).
  std::string stop;
  /// "3 rounds (population 50, 100, 200), 1750000 of 16000000 evaluations: converged".
  [[nodiscard]] std::string summary() const;
};

/// 64 × round 0's population budget R·P·I: room for five restarts (1 + 2 + 4 + 8 + 16 + 32 = 63).
long long default_cap(int runs, int population, int iterations);

/// The population of round k: P·2^k. A cmaes population of 0 (Hansen's default λ₀) stays 0 in round 0, so that
/// round 0 is the fixed budget bit for bit, and is λ₀(free parameters)·2^k after.
int round_population(const OptimizerSpec& optimizer, int free_parameters, int round);

/// Appends one round's runs to the chains (run r to chain r): bests compared, histories and evaluations offset
/// by what the chain had spent. An empty `chains` becomes `round`.
void append_round(Identification& chains, const Identification& round);

/// identify() in rounds, as the header says. `settings.runs` must be at least 2 (one run cannot show agreement).
/// InputError for fewer runs and whatever identify() rejects.
Identification identify_until_converged(const Model& model, const std::vector<const Signals*>& data,
                                        const Bounds& bounds, const AutoBudget& budget,
                                        const IdentificationSettings& settings, AutoBudgetReport& report);

}  // namespace dampbench
