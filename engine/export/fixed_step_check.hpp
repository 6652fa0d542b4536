#pragma once
// The largest sample step dt at which a model runs by the exported fixed-step scheme (RK4 in a fixed number of
// sub-steps per step, engine/export/c_export.hpp, `simulate --fixed-step`), checked by running it: a controller's
// engineer chooses dt before anything runs on the target, and a stiff hysteresis (Bouc–Wen's β·X in the
// thousands) blows up silently above its limit. The check runs the scheme on a sinusoid of the stroke and peak
// velocity the model was fitted on, at the operating variables' fitted extremes, from the RK4 bound
// dt ≤ sub-steps · 2.78 / λ (λ the model's stiffness estimate, engine/kernels/substep_rule.hpp) down by factors of
// 0.8 until the run is finite and within 1 % (relative L2) of the same run at 16 times the sub-steps.
#include <map>
#include <span>
#include <string>
#include <vector>

#include "engine/model/model.hpp"

namespace dampbench::exporting {

/// The motion and variables a fixed-step check runs on.
struct CheckedMotion {
  double stroke_m = 0;              ///< peak-to-peak displacement of the sinusoid
  double velocity_max_abs_m_s = 0;  ///< its peak |v|
  /// Operating variables to check at (each fitted range's ends, every combination); one empty map without laws.
  std::vector<std::map<std::string, double>> variables{{}};
  /// Further points of the ranges whose stiffness estimate is probed: the stiffest is checked too when it is
  /// stiffer than every point of `variables` (a law may stiffen the model most inside its range).
  std::vector<std::map<std::string, double>> probes;
};

struct FixedStepCheck {
  CheckedMotion motion;          ///< with the stiffest probe added to `variables` when it was checked
  bool has_states = true;        ///< false: the model is algebraic and any dt holds
  double stiffness_per_s = 0;    ///< the largest stiffness estimate λ over the variables (0: none; inf: not finite)
  double dt_max_s = 0;           ///< the largest dt tried that passed (0: none down to the last tried)
  double dt_tried_last_s = 0;    ///< the smallest dt tried
  double checked_duration_s = 0; ///< the sinusoid's length at dt_max_s: two periods, or fewer at a tiny dt
  bool period_bound = false;     ///< dt_max_s is the check's coarsest sampling (1/20 of the motion's period)
};

/// The sub-step rule's stability bound on RK4's negative real axis, |h·λ| < 2.785.
inline constexpr double kRk4StabilityBound = 2.78;
/// The most sub-steps per step the check (and the export) takes.
inline constexpr int kMaxExportSubsteps = 4096;
/// The accuracy a dt must keep to pass: relative L2 against 16 times the sub-steps.
inline constexpr double kFixedStepTolerance = 0.01;

/// Whether the exported step advances states (the model's own or a driver lag's): without any, every dt holds.
bool steps_states(const Model& model);

/// Runs the check; InputError for a motion without a finite stroke and velocity above 0, substeps outside
/// 1 … kMaxExportSubsteps or a model that cannot be stepped.
FixedStepCheck check_fixed_step(const Model& model, std::span<const double> params, int substeps,
                                const CheckedMotion& motion);

/// dt_max_s rounded down to 3 significant digits, as the statements print it.
std::string printed_step(const FixedStepCheck& check);

/// The check as the export's head comment states it (lines starting " * ", each ending in a newline).
std::string fixed_step_statement(const FixedStepCheck& check, int substeps);

}  // namespace dampbench::exporting
