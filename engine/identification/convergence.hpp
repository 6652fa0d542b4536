#pragma once
// Convergence evidence of repeated identification runs (docs/design.md, "Evidence with every result"): do the
// runs agree, and had the best one stopped improving? Printed by `fit`, stored and marked by sweeps.
//
//   runs agree  ⇔  median(best values) − best ≤ agree_rel·|best| + abs_tol
//                  (at least half of the runs end within agree_rel of the best one)
//   stalled     ⇔  value(E·(1 − late_fraction)) − best ≤ late_gain_rel·|best| + abs_tol
//                  on the best run's best-so-far history, E its evaluations (it no longer improved in the
//                  last fifth of its budget)
//                  — or the best run ended in a local refinement that stopped on its own convergence test
//                  (hybrids: LM or SLSQP at a local optimum, or LM at its iteration cap gaining ≤ 0.01 % over
//                  its last fifth; RunHistory::at_local_optimum), whose late gain
//                  is by design
//   converged   ⇔  runs agree and stalled (and, under the automatic budget, a restart confirmed the best:
//                  engine/fit/auto_budget.hpp; Convergence::unconfirmed)
// abs_tol keeps differences that no metric can show (noise-free synthetic fits reaching 1e-9 and 1e-8)
// from counting as disagreement. A single run cannot show agreement (a run stuck in a local minimum
// stalls too): it is never called converged, and its verdict says "one run".
#include <span>
#include <string>
#include <vector>

#include "engine/identification/identification.hpp"

namespace dampbench {

/// One point of a best-so-far history.
struct TracePoint {
  long long evaluations = 0;
  double value = 0;  ///< best-so-far metric after `evaluations`
};

/// A run's history reduced to the points where the best-so-far improved, the last iteration, and a final
/// point for a local refinement that improved on the population phase (evaluations included).
std::vector<TracePoint> improvement_points(const RunResult& run);

struct ConvergenceRule {
  double agree_rel = 0.02;      ///< median run within 2 % of the best
  double late_gain_rel = 0.01;  ///< best improved by at most 1 % over the last fifth
  double late_fraction = 0.2;
  double abs_tol = 1e-9;        ///< in the metric's units
};

struct Convergence {
  double median_above_best_rel = 0;  ///< (median − best)/|best| of the runs' best values
  double worst_above_best_rel = 0;   ///< (worst − best)/|best|
  double late_gain_rel = 0;          ///< the best run's improvement over its last fifth, relative to its best
  /// The same three in the metric's units: where the best is within abs_tol of 0 (an exact fit), the relative
  /// figures are infinite or meaningless and the text prints these instead (spread_text, figure).
  double median_above_best = 0, worst_above_best = 0, late_gain = 0;
  bool relative_figures = true;  ///< |best| > abs_tol: the relative figures mean something
  double best_value = 0;         ///< the best run's best value
  bool runs_agree = false, stalled = false, converged = false;
  bool all_failed = false;   ///< no run has a finite best value
  bool no_history = false;   ///< the best run has no best-so-far history (a store written without traces)
  bool single_run = false;   ///< one run: agreement cannot be shown
  bool best_at_local_optimum = false;  ///< the best run's local stage ended at its optimum (its late gain is by design)
  /// The automatic budget stopped before a restart confirmed the best (no restart ran, or the last one did not
  /// land on the best): then not converged, whatever the runs' agreement.
  bool unconfirmed = false;
  /// "converged", or what failed: "runs disagree", "still improving", "runs disagree, still improving",
  /// "not confirmed by a restart" (runs agree and stalled, but `unconfirmed`),
  /// "no history" (stalling cannot be judged), "runs disagree, no history", "every run failed", and for a
  /// single run "one run" or "one run, still improving".
  [[nodiscard]] std::string verdict() const;
  /// "the median run ends 3.2 % above the best, the worst 8.1 %; the best run improved 0.4 % over its last
  /// 20 % of evaluations", with the differences in the metric's units where the best is 0 (relative_figures).
  [[nodiscard]] std::string spread_text(const ConvergenceRule& rule) const;
  /// One of the three figures as printed: "3.2 %" from `relative`, or `absolute` in the metric's units where the
  /// relative figures mean nothing (relative_figures false).
  [[nodiscard]] std::string figure(double relative, double absolute) const;
};

/// One run as the assessment sees it: its best value and its best-so-far history.
struct RunHistory {
  double best_value = 0;
  std::vector<TracePoint> trace;
  bool at_local_optimum = false;  ///< ended by a local refinement's own convergence test
};

/// `unconfirmed`: the automatic budget stopped before a restart confirmed the best (Convergence::unconfirmed).
Convergence assess_convergence(std::span<const RunHistory> runs, const ConvergenceRule& rule = {},
                               bool unconfirmed = false);
Convergence assess_convergence(const Identification& id, const ConvergenceRule& rule = {}, bool unconfirmed = false);

}  // namespace dampbench
