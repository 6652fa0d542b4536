#pragma once
// Transforms of a loaded record, applied by the loader options of `fit`, `simulate` and presets.
#include <string_view>

#include "engine/record/dataset.hpp"

namespace dampbench {

/// crfd test rig (eqs. 2.1–2.2): the MTS actuator drives the damper arm through a slider-crank,
///   L_AB·cos θ − L_BC·cos γ = 0,   L_AB·sin θ + L_BC·sin γ − H − x_e = 0,
/// H = 114.89 mm, L_AB = 80 mm, L_BC = 140 mm (at x_e = 0: θ = 0, γ = 55.15°).
struct SliderCrank {
  double H_m = 0.11489, L_AB_m = 0.080, L_BC_m = 0.140;
  /// The printed torque T0 = F_e·sin γ·L_AB·sin(θ + γ) instead of the two-force-rod statics
  /// T0 = F_e·L_AB·sin(θ + γ)/sin γ (the printed `· sin γ` is most likely a `/ sin γ`: docs/models.md (crfd)).
  bool printed_torque = false;

  struct Pose {
    double theta_rad, gamma_rad;
  };
  /// θ and γ for an actuator displacement x_e [m] (Newton on θ; throws InputError outside the rig's reach).
  [[nodiscard]] Pose solve(double x_e_m) const;
  /// Damper torque [N·m] for actuator force F_e [N] at a pose.
  [[nodiscard]] double torque(double F_e_N, const Pose& pose) const;
};

/// MTS displacement and force → rotation angle θ [rad] in x and torque [N·m] in F; θ̇ and θ̈ by the
/// 3rd-order differentiation. `source` names the record in messages.
Dataset to_rotary(const Dataset& mts, const SliderCrank& rig);

/// Cycle averaging (crfd: 10 cycles, cycles 1–3 and 8–10 dropped, 4–7 averaged): the record is split into
/// `cycles` periods of equal duration, the first and last `drop` are discarded, and the rest are averaged
/// sample by sample on the time grid of the first kept cycle (linear interpolation), giving one cycle
/// starting at t = 0 (a command column that varies is averaged with them). Throws InputError if fewer than one
/// cycle would remain or a cycle has < 4 samples.
Dataset average_cycles(const Dataset& record, int cycles, int drop);

/// Operating variables from a UTFSM data file name `<amp mm>mm<freq Hz>Hz<current A>A` with 'x' as the
/// decimal point (`25mm0x25Hz0x75A` → amp 0.025 m, freq 0.25 Hz, I 0.75 A). Throws InputError naming the
/// file when the name does not follow the pattern.
std::map<std::string, double> utfsm_conditions(std::string_view file_stem);

}  // namespace dampbench
