#pragma once
// A force-driven structure with a Bouc–Wen hysteretic restoring force (Noël & Schoukens, "Hysteretic benchmark
// with a dynamic nonlinearity", eqs. 1–5; docs/models.md "System models"), stepped by the benchmark's own
// integrator: Newmark's average-acceleration rule for the structure and the trapezoid rule for the hysteretic
// force z, solved together by Newton's method at each step. The training-data generator (datasets/) and the
// model's candidate lanes (models/structure.cpp) step with this one implementation.
#include <cmath>

#include "engine/common/vector_math.hpp"

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

/// Benchmark eq. 3. With P = |z|^ν, |z|^(ν−1)·z = sgn(z)·P and ∂P/∂|z| = ν·P/|z|: one vector exp and log per call
/// (abs_pow; exact |z| at ν = 1). At z = 0 the derivative is taken at |z| = 1e−100, finite for the ν < 1 where it
/// is infinite, which only slows Newton's first iteration off zero.
inline HystereticRate hysteretic_rate(const HystereticStructure& p, double v, double z) {
  const double abs_z = std::fabs(z), sgn_z = sign(z), sgn_v = sign(v);
  const double power_any = abs_pow(z, p.nu);                      // computed in every lane: no branch around a call
  const double power = p.nu == 1.0 ? abs_z : power_any;           // |z|^ν
  const double power_1 = p.nu == 1.0 ? 1.0 : p.nu * power / (abs_z + 1e-100);  // ν|z|^(ν−1)
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

/// W structures stepped together, one per lane (candidate lanes: engine/kernels/lane_kernel.hpp): parameters and
/// states structure-of-arrays, Newton's iterations as `omp simd` loops over the lanes under a mask (1 = still
/// iterating). A lane stops when its own corrections meet the tolerance and keeps its values from then on, so its
/// bits depend on its own parameters only, whichever lanes share its block.
template <int W>
struct NewmarkLanes {
  alignas(64) double m[W], c[W], k[W], alpha[W], beta_gamma[W], beta_delta[W], nu[W];
  alignas(64) double y[W], v[W], a[W], z[W], zdot[W], previous_a[W], previous_zdot[W];
  bool failed[W] = {};    ///< the state stopped being finite; the lane is frozen from then on
  bool unsolved[W] = {};  ///< Newton missed its tolerance at the last step (the lane keeps its last iterate)
  alignas(64) double frozen[W] = {};  ///< failed as 1.0 / 0.0: the lane loops select on doubles, not bools

  void set_structure(int l, const HystereticStructure& p) {
    m[l] = p.m_kg, c[l] = p.c_N_s_m, k[l] = p.k_N_m, alpha[l] = p.alpha_N_m;
    beta_gamma[l] = p.beta_gamma, beta_delta[l] = p.beta_delta, nu[l] = p.nu;
  }
  [[nodiscard]] HystereticStructure structure(int l) const {
    return {m[l], c[l], k[l], alpha[l], beta_gamma[l], beta_delta[l], nu[l]};
  }
  void set_state(int l, const StructureState& s) {
    y[l] = s.y_m, v[l] = s.v_m_s, a[l] = s.a_m_s2, z[l] = s.z_N, zdot[l] = s.zdot_N_s;
    previous_a[l] = s.previous_a_m_s2, previous_zdot[l] = s.previous_zdot_N_s;
  }
  [[nodiscard]] StructureState state(int l) const { return {y[l], v[l], a[l], z[l], zdot[l], previous_a[l], previous_zdot[l]}; }

  /// One step of h seconds to the input u1 at its end (benchmark eqs. 4–5, Newmark's γ = 1/2, β = 1/4, the
  /// trapezoid rule for z) for every lane that has not failed.
  void step(double h, double u1_N) {
    const double half_h = 0.5 * h, quarter_h2 = 0.25 * h * h;
    alignas(64) double a1[W], z1[W], zdot1[W], active[W];
#pragma omp simd
    for (int l = 0; l < W; ++l) {  // predictor: ÿ and ż extrapolated from the last two steps
      a1[l] = 2 * a[l] - previous_a[l];
      z1[l] = z[l] + h * (1.5 * zdot[l] - 0.5 * previous_zdot[l]);
      zdot1[l] = zdot[l];
      active[l] = 1.0 - frozen[l];
    }
    double any = 1;
    for (int iteration = 0; iteration < kNewtonIterations && any > 0; ++iteration) {
#pragma omp simd
      for (int l = 0; l < W; ++l) newton_iteration(l, half_h, quarter_h2, u1_N, a1[l], z1[l], zdot1[l], active[l]);
      any = 0;
      for (int l = 0; l < W; ++l) any += active[l];
    }
#pragma omp simd
    for (int l = 0; l < W; ++l) {
      const double keep = frozen[l];
      const double v1 = v[l] + half_h * (a[l] + a1[l]);
      const double y1 = y[l] + h * v[l] + quarter_h2 * (a[l] + a1[l]);
      previous_a[l] = keep > 0 ? previous_a[l] : a[l];
      previous_zdot[l] = keep > 0 ? previous_zdot[l] : zdot[l];
      y[l] = keep > 0 ? y[l] : y1;
      v[l] = keep > 0 ? v[l] : v1;
      a[l] = keep > 0 ? a[l] : a1[l];
      z[l] = keep > 0 ? z[l] : z1[l];
      // ż at the last iterate before its correction, which the tolerance makes negligible: an exp and log less.
      zdot[l] = keep > 0 ? zdot[l] : zdot1[l];
    }
    for (int l = 0; l < W; ++l) {
      unsolved[l] = active[l] > 0;
      failed[l] = failed[l] || !std::isfinite(y[l]) || !std::isfinite(z[l]);
      frozen[l] = failed[l] ? 1.0 : 0.0;
    }
  }

 private:
  /// One Newton iteration on (ÿ₁, z₁) of lane l if it is active; sets `active` to 0 once the corrections are small.
  void newton_iteration(int l, double half_h, double quarter_h2, double u1_N, double& a1, double& z1, double& zdot1,
                        double& active) const {
    const HystereticStructure p = structure(l);
    const double v1 = v[l] + half_h * (a[l] + a1);
    const double y1 = y[l] + 2 * half_h * v[l] + quarter_h2 * (a[l] + a1);
    const HystereticRate g = hysteretic_rate(p, v1, z1);
    const double r1 = p.m_kg * a1 + p.c_N_s_m * v1 + p.k_N_m * y1 + z1 - u1_N;
    const double r2 = z1 - z[l] - half_h * (zdot[l] + g.zdot);
    const double j11 = p.m_kg + p.c_N_s_m * half_h + p.k_N_m * quarter_h2;
    const double j21 = -quarter_h2 * g.d_dv, j22 = 1.0 - half_h * g.d_dz;
    const double det = j11 * j22 - j21;  // j12 = 1
    const double da = (r1 * j22 - r2) / det, dz = (j11 * r2 - j21 * r1) / det;
    // Both tests always evaluated (& rather than &&): a short circuit is a branch the lane loop cannot vectorize.
    const bool small_z = std::fabs(dz) <= kNewtonTolerance * (1.0 + std::fabs(z1 - dz));
    const bool small_a = std::fabs(da) <= kNewtonTolerance * (1.0 + std::fabs(a1 - da));
    const double small = (small_z & small_a) ? 1.0 : 0.0;
    a1 = active > 0 ? a1 - da : a1;
    z1 = active > 0 ? z1 - dz : z1;
    zdot1 = active > 0 ? g.zdot : zdot1;
    active = small > 0 ? 0.0 : active;
  }
};

/// One structure's step (NewmarkLanes of one lane): false when Newton missed its tolerance or the state is not finite.
inline bool newmark_step(const HystereticStructure& p, double h, double u1_N, StructureState& s) {
  NewmarkLanes<1> lane;
  lane.set_structure(0, p);
  lane.set_state(0, s);
  lane.step(h, u1_N);
  s = lane.state(0);
  return !lane.failed[0] && !lane.unsolved[0];
}

}  // namespace dampbench
