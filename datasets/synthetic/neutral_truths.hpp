#pragma once
// Neutral truths: damper physics that none of the models a paper compares has, so that a comparison made on
// their records is not decided by the choice of truth (datasets/README.md, "The synthetic truths"). Each is a
// fluid damper built from parts an engineer would name (a valve, the compressible oil column, seals, an
// accumulator), integrated with SUNDIALS CVODE under the exact motion of the test.
#include <functional>
#include <span>
#include <vector>

namespace dampbench::synthetic {

/// An MR valve damper (the mfm grid's neutral truth). The piston pushes oil through an MR valve whose
/// Herschel–Bulkley law gives the force at the piston for a flow velocity u (flow over piston area),
///   f(u) = sgn(u)·(F_y + c·|u|^m)  beyond yield, with a laminar bypass u_l = f/c_l below it;
/// the oil column between piston and valve is a spring of stiffness k, so the valve force f is a state:
///   ḟ = k·(v − u(f)),   u(f) = sgn(f)·(max(|f| − F_y, 0)/c)^(1/m) + f/c_l,
/// and the damper force is F = f + F_s·tanh(v/v_s) + F_g·((1 − x/L)^(−1.4) − 1) (seal friction, the
/// accumulator's gas spring). No compared model has a yield stress in series with a spring, a shear-thinning
/// exponent, or a gas spring: Spencer's hysteresis is a Bouc–Wen state beside its dashpots, the magic formula a
/// curve in velocity.
struct MrValveDamper {
  double yield_N = 0;            ///< F_y
  double viscous_N = 0;          ///< c: post-yield valve force at a flow velocity of 1 m/s, N/(m/s)^m
  double flow_exponent = 0.7;    ///< m < 1: shear thinning
  double leak_N_s_m = 0;         ///< c_l
  double column_N_m = 0;         ///< k
  double seal_friction_N = 0, seal_velocity_m_s = 0.005;
  double gas_N = 0, gas_length_m = 0.2;
};

/// The mfm grid's damper at a current: the yield force and the post-yield viscosity grow with I and saturate
/// (the valve's magnetic circuit), F_y = 60 + 900·tanh(I/1.2 A) N, c = 1500 + 700·tanh(I/1.2 A) N/(m/s)^0.7.
MrValveDamper mfm_valve_damper(double current_A);

/// The fdsp grid's damper (a small damper at 0 V, forces of a few hundred newtons at 6.35 mm and 1.5–5 Hz, as the
/// paper's): a low residual yield force, a strongly shear-thinning valve (m = 0.6: the force per unit velocity falls
/// as the frequency rises) and a compliant oil column (the loops open with frequency), F_y = 40 N,
/// c = 900 N/(m/s)^0.6, k = 2e5 N/m. Neither side of fdsp Table 3 has these: both are Spencer's model, whose
/// dashpots are linear, the frequency-dependent one with its two viscosities as laws in the record's frequency.
MrValveDamper fdsp_valve_damper();

/// A rotary orifice damper (the crfd grid's neutral truth), in the crfd records' rotary units (θ rad, T N·m).
/// The vane drives oil through an orifice whose opening the motor angle φ sets; the orifice's torque for a flow
/// rate ω (over vane displacement) is laminar plus turbulent, T(ω) = c_l·ω + c_t·ω|ω|, behind the oil column's
/// stiffness k, so the orifice torque T_o is a state; seals are a Dahl friction state z; a return spring and the
/// rotor's inertia act in parallel:
///   Ṫ_o = k·(θ̇ − ω(T_o)),   ż = σ·θ̇·(1 − z·sgn θ̇),
///   T = J·θ̈ + T_o + T_c·z + k_1·θ + k_3·θ³.
/// The opening a(φ) = 0.2 + 0.8·cos²(φ/2) scales c_l by 1/a and c_t by 1/a². No compared model has the
/// series column with a laminar-turbulent orifice, Dahl friction or a cubic spring: the GV–NEM and Kwok are
/// algebraic in θ and θ̇, the generalized Maxwell model one power-law dashpot in series with a power-law spring.
struct RotaryOrificeDamper {
  double inertia_kg_m2 = 0;
  double laminar_N_m_s = 0;      ///< c_l, N·m per rad/s
  double turbulent_N_m_s2 = 0;   ///< c_t, N·m per (rad/s)²
  double column_N_m_rad = 0;     ///< k
  double friction_N_m = 0;       ///< T_c
  double friction_1_rad = 0;     ///< σ: the Dahl state's rise per radian
  double spring_N_m_rad = 0, spring3_N_m_rad3 = 0;
};

/// The crfd grid's damper at a motor angle φ [deg].
RotaryOrificeDamper crfd_orifice_damper(double phi_deg);

/// A motion given in closed form: position, velocity and acceleration at time t.
struct Motion {
  std::function<double(double)> x, v, a;
};

/// x = X·sin(2πft) with its exact velocity and acceleration.
Motion sine_motion(double amp_m, double freq_hz);

/// Force [N] of `damper` under `motion` at the times `t_s`, from f = 0 at t_s[0].
std::vector<double> mr_valve_force(const MrValveDamper& damper, const Motion& motion, std::span<const double> t_s);

/// Torque [N·m] of `damper` under the rotation `motion` at the times `t_s`, from T_o = z = 0 at t_s[0].
std::vector<double> rotary_orifice_torque(const RotaryOrificeDamper& damper, const Motion& motion,
                                          std::span<const double> t_s);

}  // namespace dampbench::synthetic
