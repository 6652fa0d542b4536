// crfd models (models/crfd.cpp) against the paper's equations evaluated by hand (std::pow, not the
// kernel's exp/log form) at crfd Table 2 parameters (90°, 1 Hz–1 mm).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "models/registry.hpp"

namespace dampbench {
namespace {

/// Two samples: (θ, θ̇, θ̈) = (0.01, −0.2, 3) and (−0.004, 0.05, −1).
Signals two_samples() {
  Dataset d;
  d.name = "hand";
  d.t_s = {0, 1};
  d.x_m = {0.01, -0.004};
  d.v_m_s = {-0.2, 0.05};
  d.a_m_s2 = {3.0, -1.0};
  return prepare_signals(d);
}

double sgn(double v) { return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0); }

}  // namespace

TEST(CrfdModels, GvnemEquation36) {
  const double J = 0.011, c_r = 7.321, alpha = 0.925, k_r = 8.360, beta = 0.87, T_f = 0.047, eta = 0.592,
               mu = 7.678, xi = 46.105;  // crfd Table 2, 90°
  const auto T = find_model("crfd.gvnem").simulate(std::vector<double>{J, c_r, alpha, k_r, beta, T_f, eta, mu, xi},
                                                   two_samples());
  const double th[] = {0.01, -0.004}, dth[] = {-0.2, 0.05}, ddth[] = {3.0, -1.0};
  for (int k = 0; k < 2; ++k) {
    const double expected = J * ddth[k] + c_r * sgn(dth[k]) * std::pow(std::fabs(dth[k]), alpha) +
                            k_r * sgn(th[k]) * std::pow(std::fabs(th[k]), beta) + T_f * sgn(dth[k]) +
                            eta * std::tanh(0.5 * (mu * dth[k] + xi * th[k]));
    EXPECT_NEAR(T[k], expected, 1e-13) << k;
  }
}

TEST(CrfdModels, ModifiedGvnemEquation44FixesFiveParameters) {
  const double c_r = 7.0, k_r = 20.0, eta = 0.8, mu = 8.0;
  const auto T = find_model("crfd.gvnem_modified").simulate(std::vector<double>{c_r, k_r, eta, mu}, two_samples());
  const auto full = find_model("crfd.gvnem").simulate(
      std::vector<double>{0.011, c_r, 0.867, k_r, 0.880, 0.024, eta, mu, 48.786}, two_samples());
  const double th = 0.01, dth = -0.2;
  EXPECT_NEAR(T[0], 0.011 * 3.0 - c_r * std::pow(0.2, 0.867) + k_r * std::pow(0.01, 0.880) - 0.024 +
                        eta * std::tanh(0.5 * (mu * dth + 48.786 * th)),
              1e-13);
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(T[k], full[k], 1e-13);
}

TEST(CrfdModels, KwokEquation71) {
  const double c_r = 3.0, k_r = 25.0, eta = 0.5, mu = 6.0, xi = 0.8, T_r = 0.011;
  const auto T = find_model("crfd.kwok").simulate(std::vector<double>{c_r, k_r, eta, mu, xi, T_r}, two_samples());
  EXPECT_NEAR(T[0], c_r * -0.2 + k_r * 0.01 + eta * std::tanh(mu * (-0.2 + xi * 1.0)) + T_r, 1e-14);
  EXPECT_NEAR(T[1], c_r * 0.05 + k_r * -0.004 + eta * std::tanh(mu * (0.05 + xi * -1.0)) + T_r, 1e-14);
}

TEST(CrfdModels, MaxwellStartsRelaxedAndFollowsASlowRamp) {
  // On a slow ramp θ = ω t the dashpot carries the motion once the spring has loaded: at steady state
  // c_r·θ̇^α = k_r·θ_k^β, so the torque tends to c_r·ω^α. Hand value: c_r = 2, α = 0.5, ω = 0.04 → 0.4 N·m.
  Dataset d;
  d.name = "ramp";
  for (int k = 0; k <= 2000; ++k) {
    d.t_s.push_back(k * 0.005);
    d.x_m.push_back(0.04 * k * 0.005);
    d.v_m_s.push_back(0.04);
    d.a_m_s2.push_back(0.0);
  }
  const auto T = find_model("crfd.maxwell").simulate(std::vector<double>{2.0, 50.0, 0.5, 0.8}, prepare_signals(d));
  EXPECT_EQ(T.front(), 0.0);  // θ_k(0) = 0
  EXPECT_NEAR(T.back(), 2.0 * std::sqrt(0.04), 1e-6);
}

}  // namespace dampbench
