// The neutral truths (datasets/synthetic/neutral_truths.hpp) against their physics, computed by hand: at a constant
// velocity the valve passes the piston's flow (the steady force solves the flow balance), the oil column is the
// stiffness before yield, and the rotary damper's torque is its orifice's, friction's and spring's sum.
#include "datasets/synthetic/neutral_truths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace dampbench::synthetic {
namespace {

/// Times 0, dt, ..., t_end.
std::vector<double> times(double t_end, int n) {
  std::vector<double> t;
  for (int k = 0; k <= n; ++k) t.push_back(t_end * k / n);
  return t;
}

/// The root f of g on [lo, hi] by bisection (g increasing).
template <class G>
double bisect(G g, double lo, double hi) {
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) > 0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(NeutralTruths, TheValveDamperPassesThePistonsFlowAtAConstantVelocity) {
  const MrValveDamper d = mfm_valve_damper(1.0);
  EXPECT_NEAR(d.yield_N, 60 + 900 * std::tanh(1 / 1.2), 1e-9);
  const double v = 0.1;  // m/s, from x = 0
  const Motion motion{[=](double t) { return v * t; }, [=](double) { return v; }, [](double) { return 0.0; }};
  const auto t = times(0.2, 400);
  const auto F = mr_valve_force(d, motion, t);
  // Steady flow: v = ((f − F_y)/c)^(1/m) + f/c_l, solved by bisection; the other terms at x = v·t_end.
  const double f = bisect([&](double g) { return std::pow((g - d.yield_N) / d.viscous_N, 1 / d.flow_exponent) +
                                                 g / d.leak_N_s_m - v; },
                          d.yield_N, d.yield_N + 10 * d.viscous_N);
  const double x = v * t.back();
  const double expected = f + d.seal_friction_N * std::tanh(v / d.seal_velocity_m_s) +
                          d.gas_N * (std::pow(1 - x / d.gas_length_m, -1.4) - 1);
  EXPECT_NEAR(F.back(), expected, 1e-6 * expected);
  // Before yield (f ≪ F_y) the column is the spring: f grows by k·v·dt (less the bypass, below 1 % this early).
  const double dt = t[1];
  const double column = F[1] - d.seal_friction_N * std::tanh(v / d.seal_velocity_m_s) -
                        d.gas_N * (std::pow(1 - v * dt / d.gas_length_m, -1.4) - 1);
  EXPECT_NEAR(column, d.column_N_m * v * dt, 0.01 * d.column_N_m * v * dt);
}

TEST(NeutralTruths, TheCurrentRaisesTheYieldForceAndSaturates) {
  EXPECT_LT(mfm_valve_damper(0).yield_N, mfm_valve_damper(1).yield_N);
  EXPECT_LT(mfm_valve_damper(2.5).yield_N - mfm_valve_damper(2).yield_N,
            0.25 * (mfm_valve_damper(0.5).yield_N - mfm_valve_damper(0).yield_N));
}

TEST(NeutralTruths, TheFdspDampersEquivalentViscosityFallsWithFrequency) {
  // The property the fdsp-neutral grid is for: at the fdsp tests' 6.35 mm the energy a cycle dissipates, over
  // π·ω·X² (a linear dashpot's), falls as the frequency rises (the valve thins by (ω)^(m−1) = (5/1.5)^−0.4 = 0.62
  // between 1.5 and 5 Hz; seal friction's share falls as 1/ω). A frequency-independent Spencer model fitted at one
  // frequency cannot follow it.
  const MrValveDamper d = fdsp_valve_damper();
  constexpr double X = 0.00635;
  auto equivalent_viscosity = [&](double f) {
    const auto t = times(3 / f, 6000);
    const Motion motion = sine_motion(X, f);
    const auto F = mr_valve_force(d, motion, t);
    double energy = 0;  // the third cycle, by the trapezoid rule on F·v
    for (std::size_t k = 4001; k < t.size(); ++k)
      energy += 0.5 * (t[k] - t[k - 1]) * (F[k] * motion.v(t[k]) + F[k - 1] * motion.v(t[k - 1]));
    const double w = 2 * std::numbers::pi * f;
    return energy / (std::numbers::pi * w * X * X);
  };
  const double low = equivalent_viscosity(1.5), high = equivalent_viscosity(5);
  EXPECT_GT(low, 0);
  EXPECT_LT(high, 0.8 * low) << "1.5 Hz: " << low << " N*s/m, 5 Hz: " << high << " N*s/m";
}

TEST(NeutralTruths, TheRotaryDampersTorqueIsItsPartsSumAtAConstantRate) {
  const RotaryOrificeDamper d = crfd_orifice_damper(90);
  // The opening at 90 degrees is 0.2 + 0.8·cos²(45°) = 0.6 of the open valve's.
  EXPECT_NEAR(d.laminar_N_m_s * 0.6, crfd_orifice_damper(0).laminar_N_m_s, 1e-12);
  EXPECT_NEAR(d.turbulent_N_m_s2 * 0.6 * 0.6, crfd_orifice_damper(0).turbulent_N_m_s2, 1e-12);
  const double w = 0.5, th0 = -0.1;  // rad/s, rad
  const Motion motion{[=](double t) { return th0 + w * t; }, [=](double) { return w; }, [](double) { return 0.0; }};
  const auto t = times(2.0, 400);
  const auto T = rotary_orifice_torque(d, motion, t);
  // Steady: the orifice torque is c_l·ω + c_t·ω², the Dahl state 1.
  const double th = th0 + w * t.back();
  const double expected = d.laminar_N_m_s * w + d.turbulent_N_m_s2 * w * w + d.friction_N_m + d.spring_N_m_rad * th +
                          d.spring3_N_m_rad3 * th * th * th;
  EXPECT_NEAR(T.back(), expected, 1e-6 * std::fabs(expected));
}

}  // namespace
}  // namespace dampbench::synthetic
