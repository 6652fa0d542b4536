#pragma once
// The automatic budget (`fit --budget auto`, fit's default; sweep optimizer entries that set no budget): the runs
// of a fit are extended by restarts until the convergence verdict holds and a restart confirms the best (or a cap
// is reached).
//
//   round 0     the fixed budget: R runs of population P × I iterations (the same bits as a fixed budget)
//   round k ≥ 1 every run restarts with the same P and I·2^k iterations, its streams keyed (seed, task, k, run)
//   run r       the chain of its rounds: best = the best over the chain, history = the chain's best-so-far
//               over the evaluations of every round, restarts counted
//   converged   the verdict (convergence.hpp) holds on the chains, and the last round, a restart with twice the
//               iterations of the round before, found the chains' best again: its best within kRestartRel of
//               it, neither above (not found again) nor below (a better one, not yet found twice); and a second
//               opinion found nothing lower
//   second      run once, the first time the rest holds: another optimizer (second_opinion()) at its own
//   opinion     default budget for the model, with the fit's run count (at least fit's default,
//               second_opinion_runs()) and its own streams. When its best lies
//               more than kRestartRel below the chains' best, the chains share a basin that is not the lowest:
//               the rounds go on until the chains reach the second opinion's best and a restart confirms it, or
//               the cap stops them and the summary says what the second opinion found. Its runs count in the
//               evaluations and the cap, never in the result: the fit stays the chosen optimizer's.
//
// Restarts, not longer runs: each round is a new run with its own schedule over its iterations (PSO's inertia,
// AGA's rates, a hybrid's hand-over to its local stage), so the schedules keep their meaning. Longer, not wider
// (IPOP, Auger & Hansen 2005, doubles the population): with a fixed generation count, a larger population makes
// GA, PSO and DE more global but ends them less precisely, and on the damper problems the runs' precision is
// what their 100 generations lack (docs/performance.md, "The automatic budget"); cmaes's own ipop restarts
// widen its population inside every run. The confirming restart is what tells a basin every run agrees on from
// the best one: runs that agree can all sit in the same wider, higher basin (the Kwok record's μ–ξ plateau), and
// a restart that merely fails to beat the best has not shown that it is the best. Restarts of one optimizer can
// share its bias (every CMA-ES run and restart lands on that plateau): the second opinion, another optimizer,
// searches the box differently.
// After each round: converged → stop; otherwise the next round starts only if it fits in the cap, its cost
// estimated as twice the last round's; else stop at the cap. The schedule depends only on results, so the same
// inputs give the same bits, unless the optional wall-clock cap fires (and then the outcome says so).
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/identification/identification.hpp"
#include "optimizers/registry.hpp"

namespace dampbench {

/// A restart confirms the best when its own best is within this fraction of it: the 0.1 % of COCO-style targets.
inline constexpr double kRestartRel = 1e-3;

struct AutoBudget {
  OptimizerSpec optimizer;        ///< round 0's optimizer; later rounds double its iterations
  long long max_evaluations = 0;  ///< cap over every round and run (local phases included); 0 = default_cap()
  double max_seconds = 0;         ///< wall-clock cap; 0 = none
};

/// What the restarts did, for the output.
struct AutoBudgetReport {
  std::vector<int> iterations;   ///< of each round run, in order
  long long evaluations = 0;     ///< spent over every round and run
  long long cap = 0;             ///< the evaluation cap in force
  /// (the last round's best − the chains' best before it) / the chains' best after it: negative when the restart
  /// improved the best; +inf after round 0 alone or when the best before it was not finite; NaN when every run
  /// of the last restart failed.
  double last_restart_rel = 0;
  /// "converged"; "cap" (the next round would pass the cap, or round 0 was cut by it); "time cap".
  std::string stop;
  std::optional<OptimizerSpec> second_opinion_optimizer;  ///< the second opinion's optimizer; empty before it ran
  double second_opinion_best = std::numeric_limits<double>::quiet_NaN();  ///< its best value (NaN: not run)
  /// (its best − the chains' final best) / the chains' final best: negative when it found lower; NaN: not run
  double second_opinion_rel = std::numeric_limits<double>::quiet_NaN();
  long long second_opinion_evaluations = 0;  ///< included in `evaluations`
  /// The second opinion found more than kRestartRel below the chains' best: the fit is not converged.
  bool second_opinion_lower = false;
  /// "de", "ga-lm", "ga-lm+cmaes" (the optimizer and its global stage); "" before it ran.
  [[nodiscard]] std::string second_opinion_label() const;
  /// "4 rounds (iterations 100, 200, 400, 800), 750000 of 1280000 evaluations: converged, the last restart
  /// ended 0.0001 % above the best; a second opinion (ga-lm) ended 0.2 % above it".
  [[nodiscard]] std::string summary() const;
};

/// Whether a summary() (a sweep group's stored message) says the budget stopped before converging.
bool stopped_before_converging(std::string_view summary);

/// The cap when none is given: 64 × round 0's evaluations, plus the second opinion's once it ran: room for five
/// restarts (1 + 2 + 4 + 8 + 16 + 32 = 63 round 0s) whatever the second opinion costs (50 de runs beside a fit of 10
/// are 5 of its round 0s) and whatever a hybrid's local stage adds to each round (round 0's evaluations include
/// it, and it does not double with the iterations). `round0` is at least R·P·I.
long long default_cap(long long round0, long long second_opinion);

/// Whether a restart whose best is `restart` confirms the chains' best `before` it: |restart − before| within
/// kRestartRel of the better of the two (plus ConvergenceRule::abs_tol); never when either is not finite.
bool restart_confirms(double before, double restart);

/// The second opinion on a fit by `optimizer`: on an algebraic model de (for de itself ga-lm), whose runs cover the
/// box widely and cost one pass over the record each; on a model with internal states ga-lm (a GA global stage,
/// then Levenberg–Marquardt: the best within the fewest integrations), for ga-lm itself ga-lm with a CMA-ES global
/// stage. Population and iterations are fit's defaults for `model` and that optimizer (fit_defaults.hpp).
OptimizerSpec second_opinion(const Model& model, const OptimizerSpec& optimizer);

/// The second opinion's run count: the fit's, and at least fit's default for `model` (50 on an algebraic model,
/// 4 with internal states), so that a fit of few runs still gets a second opinion that can find a narrow basin.
int second_opinion_runs(const Model& model, int runs);

/// The iterations of round k: I·2^k.
int round_iterations(const OptimizerSpec& optimizer, int round);

/// Appends one round's runs to the chains (run r to chain r): bests compared, histories and evaluations offset
/// by what the chain had spent. An empty `chains` becomes `round`.
void append_round(Identification& chains, const Identification& round);

/// Told one line after each round and after the second opinion; may be empty.
using BudgetProgress = std::function<void(const std::string&)>;

/// identify() in rounds, as the header says. `settings.runs` must be at least 2 (one run cannot show agreement).
/// InputError for fewer runs and whatever identify() rejects.
Identification identify_until_converged(const Model& model, const std::vector<const Signals*>& data,
                                        const Bounds& bounds, const AutoBudget& budget,
                                        const IdentificationSettings& settings, AutoBudgetReport& report,
                                        const BudgetProgress& progress = {});

}  // namespace dampbench
