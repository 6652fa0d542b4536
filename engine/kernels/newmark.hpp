#pragma once
// A force-driven structure with a Bouc–Wen hysteretic restoring force (Noël & Schoukens, "Hysteretic benchmark
// with a dynamic nonlinearity", eqs. 1–5; docs/models.md "System models"), stepped by the benchmark's own
// integrator: Newmark's average-acceleration rule for the structure and the trapezoid rule for the hysteretic
// force z, solved together by Newton's method at each step. The training-data generator (datasets/) and the
// model's candidate lanes (models/structure.cpp) step with this one implementation.
#include <algorithm>
#include <cmath>

namespace dampbench {

/// m·ÿ + c·ẏ + k·y + z = u, ż = α·ẏ − βγ·|ẏ|·|z|^(ν−1)·z − βδ·ẏ·|z|^ν (benchmark eqs. 1–3). β enters only as the
/// products βγ and βδ, which are what the data determine.
struct HystereticStructure {
  double m_kg = 0, c_N_s_m = 0, k_N_m = 0;
  double alpha_N_m = 0, beta_gamma = 0, beta_delta = 0, nu = 1;
};

/// The state after a step: displacement, velocity, acceleration, hysteretic force and its rate.
struct StructureState {
  double y_m = 0, v_m_s = 0, a_m_s2 = 0, z_N = 0, zdot_N_s = 0;
  double previous_a_m_s2 = 0, previous_zdot_N_s = 0;  ///< of the step before, for Newton's predictor
};

/// ż and its derivatives with respect to ẏ and z.
struct HystereticRate {
  double zdot = 0, d_dv = 0, d_dz = 0;
};

/// Benchmark eq. 3. With P = |z|^ν, |z|^(ν−1)·z = sgn(z)·P and ∂P/∂|z| = ν·P/|z| (one pow per call). At z = 0 with
/// ν < 1 that derivative is infinite; it is taken at |z| = kFloor instead, which only slows Newton's first iteration
/// off zero.
inline HystereticRate hysteretic_rate(const HystereticStructure& p, double v, double z) {
  constexpr double kFloor = 1e-300;
  const double abs_z = std::fabs(z), sgn_z = (z > 0) - (z < 0), sgn_v = (v > 0) - (v < 0);
  double power = abs_z, power_1 = 1.0;  // |z|^ν and ν|z|^(ν−1); exact at ν = 1
  if (p.nu != 1.0) {
    power = abs_z > 0 ? std::pow(abs_z, p.nu) : 0.0;
    power_1 = abs_z > 0 ? p.nu * power / abs_z : (p.nu < 1 ? p.nu * std::pow(kFloor, p.nu - 1.0) : 0.0);
  }
  HystereticRate r;
  r.zdot = p.alpha_N_m * v - p.beta_gamma * std::fabs(v) * sgn_z * power - p.beta_delta * v * power;
  r.d_dv = p.alpha_N_m - p.beta_gamma * sgn_v * sgn_z * power - p.beta_delta * power;
  r.d_dz = -p.beta_gamma * std::fabs(v) * power_1 - p.beta_delta * v * sgn_z * power_1;
  return r;
}

/// The state at rest under the input u0: ÿ = u0/m, nothing else moves.
inline StructureState structure_at_rest(const HystereticStructure& p, double u0_N) {
  StructureState s;
  s.a_m_s2 = s.previous_a_m_s2 = u0_N / p.m_kg;
  return s;
}

/// Newton's stopping rule: a step is solved when the last correction of z is below kNewtonTolerance·(1 + |z|) N and
/// that of ÿ below kNewtonTolerance·(1 + |ÿ|) m/s²; kNewtonIterations at most. Newton converges quadratically, so
/// the state after that correction is exact to rounding; the ż kept for the next step is the one of the iterate
/// before it, off by the correction's order, and 1e−12 keeps the scheme within 1e−13 of an exact solve
/// (tests/unit/kernels/test_newmark.cpp) for a quarter fewer iterations than 1e−14. Each step's iterations depend
/// on its own state only, so a candidate's bits do not depend on the other lanes of its block.
inline constexpr double kNewtonTolerance = 1e-12;
inline constexpr int kNewtonIterations = 30;

/// One step of h seconds from `s` to the input u1 at its end (benchmark eqs. 4–5 with Newmark's γ = 1/2, β = 1/4 and
/// the trapezoid rule for z). Returns false when Newton did not meet its tolerance (the step keeps its last
/// iterate) or the state is not finite.
inline bool newmark_step(const HystereticStructure& p, double h, double u1_N, StructureState& s) {
  const StructureState s0 = s;
  const double half_h = 0.5 * h, quarter_h2 = 0.25 * h * h;
  const double j11 = p.m_kg + p.c_N_s_m * half_h + p.k_N_m * quarter_h2;
  // Predictor: ÿ and ż extrapolated linearly from the last two steps, which starts Newton an order of h closer than
  // holding them constant and saves it an iteration.
  double a1 = 2 * s0.a_m_s2 - s0.previous_a_m_s2, z1 = s0.z_N + h * (1.5 * s0.zdot_N_s - 0.5 * s0.previous_zdot_N_s);
  bool solved = false;
  double zdot1 = 0;
  for (int iteration = 0; iteration < kNewtonIterations && !solved; ++iteration) {
    const double v1 = s0.v_m_s + half_h * (s0.a_m_s2 + a1);
    const double y1 = s0.y_m + h * s0.v_m_s + quarter_h2 * (s0.a_m_s2 + a1);
    const HystereticRate g = hysteretic_rate(p, v1, z1);
    zdot1 = g.zdot;
    const double r1 = p.m_kg * a1 + p.c_N_s_m * v1 + p.k_N_m * y1 + z1 - u1_N;
    const double r2 = z1 - s0.z_N - half_h * (s0.zdot_N_s + g.zdot);
    const double j21 = -quarter_h2 * g.d_dv, j22 = 1.0 - half_h * g.d_dz;
    const double det = j11 * j22 - j21;  // j12 = 1
    const double da = (r1 * j22 - r2) / det, dz = (j11 * r2 - j21 * r1) / det;
    a1 -= da;
    z1 -= dz;
    solved = std::fabs(dz) <= kNewtonTolerance * (1.0 + std::fabs(z1)) &&
             std::fabs(da) <= kNewtonTolerance * (1.0 + std::fabs(a1));
  }
  s.previous_a_m_s2 = s0.a_m_s2;
  s.previous_zdot_N_s = s0.zdot_N_s;
  s.a_m_s2 = a1;
  s.v_m_s = s0.v_m_s + half_h * (s0.a_m_s2 + a1);
  s.y_m = s0.y_m + h * s0.v_m_s + quarter_h2 * (s0.a_m_s2 + a1);
  s.z_N = z1;
  // ż at the last iterate before its correction, which the tolerance makes negligible: a pow less per step.
  s.zdot_N_s = zdot1;
  return solved && std::isfinite(s.y_m) && std::isfinite(s.z_N);
}

}  // namespace dampbench
