#pragma once
// `ga-sqp`: the fdsp paper's hybrid GA–SQP (fdsp §4, "4.1 Sequential Quadratic Programming", "4.2 Genetic
// Algorithm"): a `ga` run (optimizers/ga/ga.hpp) finds a near-global point; sequential quadratic
// programming then starts from the GA best and minimizes the run's metric f within the bounds and under
// the nonlinear constraint of fdsp eq. 11,
//     g(x) = f(x) − constraint ≤ 0.
//
// The metric and the threshold. The paper's f is its eq. 8 (a percentage) and its threshold 4 (%). In
// dampbench the SQP stage minimizes the run's own metric (IdentificationSettings::metric, what
// LocalProblem::evaluate returns) and `constraint` is read in that metric's units, as given: with a
// percent-scaled metric (fdsp eq. 8 once it is an engine metric) the default 4 is the paper's 4 %; nrmse is
// a fraction, so the paper's 4 % is `constraint=0.04`; of_abs/of_sq are σ-normalized and rmse/mae are in
// newtons, so choose the threshold in those units. `constraint=off` drops the constraint (bounds only).
//
// SQP: NLopt's SLSQP (Kraft 1988, the code scipy's SLSQP also wraps; NLopt made it re-entrant, so runs
// refine side by side on several threads). Chosen over a hand-written SQP because an SQP needs a QP
// sub-solver with bounds and linearized inequality constraints, an inconsistent-linearization fallback and
// a merit-function line search — Kraft's code has all of it, tested for decades. Its callback evaluates one
// point at a time; gradients are where the cost is, and those are batched:
//   gradient: forward differences in the unit-cube coordinates (ga_hybrid.hpp), step `fd_step` × each
//   parameter's box width, taken backwards where the forward point would leave the box. The point and its
//   m perturbations (m free parameters) are ONE batch of m + 1 candidates through LocalProblem::evaluate;
//   a perturbation whose value is not finite contributes a zero derivative. The objective and the
//   constraint share each evaluation (cached by position).
//   a non-finite value at a trial point is handed to SLSQP as a large finite penalty (1e6 × (1 + |f_GA|)),
//   so its line search backs off instead of reading inf − inf.
// Stops: `sqp_iterations` SLSQP function calls (each costs 1 or m + 1 evaluations), relative step of the
// unit coordinates below `xtol`, relative change of f below `ftol`.
//
// Infeasibility. Since g is the metric itself, the lowest value seen is also the least infeasible point.
// The run keeps the lowest value seen (GA best included, ga_hybrid.hpp); it is feasible iff that value ≤
// constraint. Callers see it as:
//   - through identify(): RunResult::best_value ≤ constraint (the reported value is the metric at the
//     returned point, re-evaluated by the engine);
//   - on the object: GaSqp::report().feasible, with the SLSQP status and call count;
//   - `dampbench compare`: the "feasible" column counts the feasible runs of each ga-sqp entry.
// An infeasible run is not an error: its result is the best point found, flagged.
// Budget: the engine's budgets (IdentificationSettings::budget) stop the GA phase; the SQP phase is bounded
// by `sqp_iterations` and adds its evaluations to RunResult::evaluations.
#include <cstdint>
#include <string>

#include "optimizers/hybrid/ga_hybrid.hpp"

namespace dampbench {

struct GaSqpSettings : HybridSettings {
  double constraint = 4;    ///< fdsp eq. 11 threshold, in the run metric's units (+inf: no constraint)
  int sqp_iterations = 100; ///< SLSQP function calls at most (NLopt maxeval)
  double fd_step = 1e-7;    ///< forward-difference step, fraction of each parameter's box width
  double xtol = 1e-10;      ///< stop when the unit-cube step is below xtol relative (NLopt xtol_rel)
  double ftol = 1e-12;      ///< stop when f changes by less than ftol relative (NLopt ftol_rel)

  /// Throws InputError ("ga-sqp: population must be at least 4, got 2", "ga-sqp: pc must be in [0, 1], got
  /// 1.5", "ga-sqp: constraint must be a number > 0 or off, got -1", "ga-sqp: fd_step must be in (0, 0.1],
  /// got 0", "ga-sqp: sqp_iterations must be at least 1, got 0", ...).
  void validate() const;
};

/// ga-sqp's own number settings but `constraint` (a number or off, which the registry reads), after its global
/// stage's (setting_table.hpp).
const SettingTable<GaSqpSettings>& ga_sqp_setting_table();

/// What the SQP stage did (for tests and callers that hold the optimizer).
struct SqpReport {
  bool ran = false;         ///< false when the GA best was not finite (nothing to start from)
  std::string status;       ///< NLopt result: "xtol", "ftol", "maxeval", "roundoff", "failure", ...
  int calls = 0;            ///< SLSQP function calls (gradient calls included)
  long long evaluations = 0;///< metric evaluations of the SQP stage
  double start_value = 0;   ///< GA best
  double end_value = 0;     ///< best_value() after refine
  bool feasible = false;    ///< end_value ≤ constraint
};

class GaSqp final : public GaHybrid {
 public:
  GaSqp(const GaSqpSettings& settings, const Bounds& bounds, std::uint64_t run_key);
  void refine(const LocalProblem& problem) override;
  [[nodiscard]] const SqpReport& report() const { return report_; }
  /// SLSQP ended with NLopt's success, ftol or xtol.
  [[nodiscard]] bool at_local_optimum() const override;

 private:
  GaSqpSettings settings_;
  SqpReport report_;
};

}  // namespace dampbench
