#pragma once
// `ga-lm`: the mfm paper's identification (mfm §3, "curve fitting was performed by a combination of genetic
// algorithm and nonlinear least square method"): a `ga` run (optimizers/ga/ga.hpp) gives the approximate
// global optimum, which starts a bounded Levenberg–Marquardt least-squares fit of the residuals
// LocalProblem::residuals (F_model − F_measured, each dataset scaled by 1/(sqrt(N_d)·max|F_d|), so
// ‖r‖² = Σ_d nrmse_d²; mfm eq. 12's E differs from nrmse only by the scale sqrt(ΣF²/N)/max|F|).
//
// Levenberg–Marquardt, own implementation on Eigen (not Eigen's unsupported LevenbergMarquardt: that one has
// no bounds, and the bounds are part of the problem — the mfm and fdsp boxes come from the papers and many
// models blow up outside them). Works in the unit-cube coordinates y of the free parameters (ga_hybrid.hpp).
// Iteration k, at y with residuals r and cost S = ‖r‖²:
//   J  forward differences, one residual vector per free parameter: column i = (r(y + s_i e_i) − r)/s_i,
//      s_i = fd_step (−fd_step where the forward point would leave the box); a column with a non-finite entry
//      is zero (that parameter is held for the iteration);
//   g = Jᵀr; active set: parameters on a bound whose gradient points out of the box are held (projected LM,
//      Kanzow, Yamashita & Fukushima 2004); stop when ‖g_free‖∞ ≤ gtol ("gradient");
//   step (JᵀJ + λ·D) v = −g on the free set, D = diag(JᵀJ) floored at 1e-12·max diag (Marquardt 1963
//      scaling); with `geodesic` (default) the step is δ = v + a/2, a the geodesic acceleration (Transtrum &
//      Sethna 2012, "Improvements to the Levenberg–Marquardt algorithm for nonlinear least-squares
//      minimization"): −(JᵀJ + λD)⁻¹Jᵀr_vv with r_vv the second directional derivative of r along v by one
//      more residual vector, r_vv ≈ (2/h)((r(y + h·v) − r)/h − J·v), h = 0.1; a step with 2‖a‖/‖v‖ >
//      geodesic_ratio counts as rejected. It lets LM follow the curved valleys of the hysteresis models
//      (Spencer: α and A trade off along z → s·z) in tens of iterations instead of hundreds. Without it δ = v.
//      y⁺ = clamp(y + δ, 0, 1); accepted if S(y⁺) < S (finite), with the gain ratio
//      ρ = (S − S⁺)/(−2δᵀg − δᵀJᵀJδ) updating λ ← λ·max(1/3, 1 − (2ρ − 1)³) (Nielsen 1999); otherwise
//      λ ← λ·ν, ν ← 2ν and the step is solved again;
//   stops: `lm_iterations` Jacobians ("iterations"), accepted relative decrease (S − S⁺)/S ≤ ftol ("ftol"),
//      step ‖δ‖ ≤ xtol·(‖y‖ + xtol) ("xtol"), S ≤ 1e-300 ("zero residual"), 20 rejected steps in a row
//      ("no progress").
//   λ₀ = lambda0 (dimensionless: D carries the scale).
//   A step into a region where the model fails (non-finite residuals) is rejected like a worse one. Against
//   such an implicit wall LM converges slowly in the other parameters: λ grows, the step shrinks in every
//   coordinate, and the run may stop on xtol before them (tests/unit/optimizers/test_ga_lm.cpp, BacksOffFromAFailureRegion).
// Each Jacobian costs m residual evaluations, each trial step one (two with geodesic acceleration); all are
// counted in the run's evaluations. Where the problem's lane block has room (LocalProblem::residuals_ahead), the
// Jacobian at a trial point is simulated in the trial's own block and used if the trial is accepted: one lane block
// per accepted iteration less (a single trial fills one lane of 16), the same values and the same count (the
// Jacobian's m evaluations count when it is used; one beside a refused trial is not counted).
//
// The result is handed back in the run metric's terms: the LM end point is evaluated through
// LocalProblem::evaluate and kept only if its metric is lower than the GA best's (ga_hybrid.hpp). With the
// least-squares metrics (nrmse, rmse, of_sq) the two agree; with of_abs or mae the LM optimum need not be the
// metric's, and the hybrid then never makes the GA result worse.
// Budget: the engine's budgets stop the GA phase; the LM phase is bounded by `lm_iterations`.
#include <cstdint>
#include <limits>
#include <string>

#include "optimizers/hybrid/ga_hybrid.hpp"

namespace dampbench {

struct GaLmSettings : HybridSettings {
  /// Jacobians at most. 400: on the UTFSM records LM creeps along the Spencer and magic-formula valleys, and
  /// 100 left 5 Spencer and 10 magic-formula groups of the utfsm preset short of LM's own convergence test
  /// (runs 0.02-0.2 % apart); 400 ends every Spencer group at it, with values 0-0.06 % lower, for a few %
  /// more preset time (docs/performance.md). LM stops earlier on its own tests, so an easy fit pays nothing
  /// for it.
  int lm_iterations = 400;
  double fd_step = 1e-7;    ///< forward-difference step, fraction of each parameter's box width
  double ftol = 1e-15;      ///< stop when an accepted step lowers ‖r‖² by less than ftol relative
  double xtol = 1e-12;      ///< stop when the unit-cube step is below xtol·(‖y‖ + xtol)
  double gtol = 0;          ///< stop when the projected gradient's largest entry is ≤ gtol
  double lambda0 = 1e-3;    ///< initial damping λ₀ (relative to diag(JᵀJ), Marquardt scaling)
  int geodesic = 1;         ///< 1: geodesic acceleration (Transtrum & Sethna 2012), 0: plain LM
  double geodesic_ratio = 0.75;  ///< largest accepted 2‖a‖/‖v‖ (Transtrum & Sethna's α)

  /// Throws InputError ("ga-lm: population must be at least 4, got 2", "ga-lm: lm_iterations must be at least
  /// 1, got 0", "ga-lm: fd_step must be in (0, 0.1], got 0", "ga-lm: lambda0 must be a finite number > 0, got 0",
  /// "ga-lm: geodesic must be 0 or 1, got 2", "ga-lm: geodesic_ratio must be a finite number > 0, got 0", ...).
  void validate() const;
};

/// ga-lm's own number settings (setting_table.hpp), read after its global stage's.
const SettingTable<GaLmSettings>& ga_lm_setting_table();

/// What the LM stage did (for tests and callers that hold the optimizer).
struct LmReport {
  bool ran = false;           ///< false when the GA best had no finite residuals
  std::string status;         ///< "gradient", "ftol", "xtol", "iterations", "zero residual", "no progress"
  int iterations = 0;         ///< Jacobians computed
  long long residual_evaluations = 0;
  double start_cost = 0;      ///< ‖r‖² at the GA best
  double end_cost = 0;        ///< ‖r‖² at the LM end point
  double end_metric = 0;      ///< the run metric at the LM end point
  /// 1 − ‖r_end‖/‖r‖ at the Jacobian that began the last fifth of the iterations (at least the last one): how
  /// much the LM still gained at the end; NaN when no Jacobian was taken.
  double late_decrease = std::numeric_limits<double>::quiet_NaN();
};

/// An LM stopped by `lm_iterations` whose last fifth of iterations lowered ‖r‖ by at most this share counts as
/// at its optimum (at_local_optimum): it creeps along a flat valley (the magic formula on UTFSM records: 0.004 %
/// more in 1 100 further Jacobians). 100× stricter than the 1 % a population run may still gain in its last
/// fifth and be called stalled (engine/identification/convergence.hpp).
inline constexpr double kStalledDecrease = 1e-4;

class GaLm final : public GaHybrid {
 public:
  GaLm(const GaLmSettings& settings, const Bounds& bounds, std::uint64_t run_key);
  void refine(const LocalProblem& problem) override;
  [[nodiscard]] const LmReport& report() const { return report_; }
  /// The LM stopped on gradient, ftol, xtol or zero residual, or at `lm_iterations` with a late decrease of at
  /// most kStalledDecrease.
  [[nodiscard]] bool at_local_optimum() const override;

 private:
  GaLmSettings settings_;
  LmReport report_;
};

}  // namespace dampbench
