#include "engine/kernels/cvode_integrator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace dampbench {

TEST(Cvode, ExponentialDecayMatchesClosedForm) {
  const double k = 3.0;
  std::vector<double> times;
  for (int i = 0; i <= 20; ++i) times.push_back(0.1 * i);
  const auto y = integrate_cvode([k](double, std::span<const double> s, std::span<double> d) { d[0] = -k * s[0]; },
                                 {2.0}, times);
  ASSERT_EQ(y.size(), times.size());
  for (std::size_t i = 0; i < times.size(); ++i) EXPECT_NEAR(y[i][0], 2.0 * std::exp(-k * times[i]), 1e-8);
}

TEST(Cvode, HarmonicOscillatorMatchesClosedForm) {
  const double w = 5.0;
  std::vector<double> times;
  for (int i = 0; i <= 50; ++i) times.push_back(0.05 * i);
  const auto y = integrate_cvode(
      [w](double, std::span<const double> s, std::span<double> d) {
        d[0] = s[1];
        d[1] = -w * w * s[0];
      },
      {1.0, 0.0}, times);
  for (std::size_t i = 0; i < times.size(); ++i) {
    EXPECT_NEAR(y[i][0], std::cos(w * times[i]), 1e-7);
    EXPECT_NEAR(y[i][1], -w * std::sin(w * times[i]), 1e-6);
  }
}

TEST(Cvode, StiffProblemIsSolved) {
  // y' = -1000 (y - cos t): BDF handles the stiffness; y tracks cos t after the transient.
  std::vector<double> times{0.0, 1.0, 2.0};
  const auto y = integrate_cvode(
      [](double t, std::span<const double> s, std::span<double> d) { d[0] = -1000.0 * (s[0] - std::cos(t)); }, {0.0},
      times);
  // Exact: y = (1000²cos t + 1000 sin t)/(1000²+1) + C e^{-1000t}; the transient is gone by t = 1.
  for (double t : {1.0, 2.0}) {
    const double exact = (1e6 * std::cos(t) + 1e3 * std::sin(t)) / (1e6 + 1);
    EXPECT_NEAR(y[t == 1.0 ? 1 : 2][0], exact, 1e-8);
  }
}

}  // namespace dampbench
