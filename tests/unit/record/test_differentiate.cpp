// Tests for engine/differentiate: convergence order on a sine, exactness on cubics, known stencil weights.
#include "engine/record/differentiate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace dampbench {
namespace {

constexpr double kOmega = 2 * std::numbers::pi;  // 1 Hz
constexpr double kPhase = 0.7;                   // rad, so that no endpoint sits on a zero of sin or cos

/// Max |d^order x/dt^order - exact| for x = sin(ωt + φ) over one period sampled with n intervals,
/// skipping `skip` points at each end. order 2 applies differentiate_3rd_order twice.
double max_error(int n, int order, int skip) {
  std::vector<double> t(n + 1), x(n + 1);
  for (int k = 0; k <= n; ++k) {
    t[k] = static_cast<double>(k) / n;
    x[k] = std::sin(kOmega * t[k] + kPhase);
  }
  std::vector<double> derivative = differentiate_3rd_order(t, x);
  if (order == 2) derivative = differentiate_3rd_order(t, derivative);
  double worst = 0;
  for (int k = skip; k <= n - skip; ++k) {
    const double phase = kOmega * t[k] + kPhase;
    const double exact = order == 1 ? kOmega * std::cos(phase) : -kOmega * kOmega * std::sin(phase);
    worst = std::max(worst, std::abs(derivative[k] - exact));
  }
  return worst;
}

/// Observed orders log2(err(h) / err(h/2)) for h = T/50 → T/100 and h = T/100 → T/200.
std::vector<double> observed_orders(int order, int skip) {
  const double e50 = max_error(50, order, skip), e100 = max_error(100, order, skip);
  const double e200 = max_error(200, order, skip);
  std::printf("derivative %d, %d end points skipped: max error %.3g, %.3g, %.3g; observed orders %.2f, %.2f\n", order,
              skip, e50, e100, e200, std::log2(e50 / e100), std::log2(e100 / e200));
  return {std::log2(e50 / e100), std::log2(e100 / e200)};
}

// Observed: 3.10 and 3.06 over the whole record (one-sided end stencils), 4.00 in the interior.
TEST(Differentiate, FirstDerivativeIsThirdOrderAtEndsAndFourthInside) {
  for (double order : observed_orders(1, 0)) EXPECT_GE(order, 2.8);
  for (double order : observed_orders(1, 2)) EXPECT_GE(order, 3.8);
}

// Observed: 2.08 and 2.04 over the whole record — the O(h³) velocity errors of the two end points are
// differenced once more (÷h) — and 4.00 once the 4 points at each end that see them are skipped.
TEST(Differentiate, SecondDerivativeByTwoPassesIsSecondOrderAtEndsAndFourthInside) {
  for (double order : observed_orders(2, 0)) EXPECT_GE(order, 1.8);
  for (double order : observed_orders(2, 4)) EXPECT_GE(order, 3.8);
}

TEST(Differentiate, ExactForCubicOnNonUniformGrid) {
  // y = 2 - t + 0.5 t² - 0.25 t³, y' = -1 + t - 0.75 t²
  std::vector<double> t, y;
  for (int k = 0; k < 12; ++k) {
    const double tk = 0.3 * k + 0.1 * std::sin(1.7 * k);  // strictly increasing, uneven steps
    t.push_back(tk);
    y.push_back(2 - tk + 0.5 * tk * tk - 0.25 * tk * tk * tk);
  }
  const std::vector<double> dy = differentiate_3rd_order(t, y);
  ASSERT_EQ(dy.size(), t.size());
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double exact = -1 + t[k] - 0.75 * t[k] * t[k];
    EXPECT_NEAR(dy[k], exact, 1e-9 * std::max(1.0, std::abs(exact))) << "k = " << k;
  }
}

TEST(Differentiate, TwoPassesExactForQuadraticOnNonUniformGrid) {
  // y = 3 t² - t, y'' = 6
  std::vector<double> t, y;
  for (int k = 0; k < 9; ++k) {
    t.push_back(0.05 * k * k + 0.2 * k);
    y.push_back(3 * t.back() * t.back() - t.back());
  }
  const std::vector<double> d2y = differentiate_3rd_order(t, differentiate_3rd_order(t, y));
  for (double value : d2y) EXPECT_NEAR(value, 6.0, 1e-8);
}

TEST(Differentiate, UniformGridUsesKnownStencils) {
  // y = exp(t) on a uniform grid, h = 0.1: compare with the textbook formulas.
  const double h = 0.1;
  std::vector<double> t, y;
  for (int k = 0; k < 8; ++k) {
    t.push_back(h * k);
    y.push_back(std::exp(h * k));
  }
  const std::vector<double> dy = differentiate_3rd_order(t, y);
  const std::size_t n = y.size();
  // forward 4-point, at the first and second node
  EXPECT_NEAR(dy[0], (-11 * y[0] + 18 * y[1] - 9 * y[2] + 2 * y[3]) / (6 * h), 1e-12);
  EXPECT_NEAR(dy[1], (-2 * y[0] - 3 * y[1] + 6 * y[2] - y[3]) / (6 * h), 1e-12);
  // central 5-point (4th order) inside
  for (std::size_t i = 2; i + 2 < n; ++i)
    EXPECT_NEAR(dy[i], (y[i - 2] - 8 * y[i - 1] + 8 * y[i + 1] - y[i + 2]) / (12 * h), 1e-12) << "i = " << i;
  // backward 4-point, at the last and second-to-last node
  EXPECT_NEAR(dy[n - 1], (11 * y[n - 1] - 18 * y[n - 2] + 9 * y[n - 3] - 2 * y[n - 4]) / (6 * h), 1e-12);
  EXPECT_NEAR(dy[n - 2], (2 * y[n - 1] + 3 * y[n - 2] - 6 * y[n - 3] + y[n - 4]) / (6 * h), 1e-12);
}

TEST(Differentiate, FourSamplesAreEnough) {
  const std::vector<double> t{0, 1, 3, 4}, y{0, 1, 9, 16};  // y = t²
  const std::vector<double> dy = differentiate_3rd_order(t, y);
  for (std::size_t k = 0; k < t.size(); ++k) EXPECT_NEAR(dy[k], 2 * t[k], 1e-12);
}

TEST(Differentiate, RejectsTooFewSamplesAndSizeMismatch) {
  EXPECT_THROW(differentiate_3rd_order({0, 1, 2}, {0, 1, 2}), std::invalid_argument);
  EXPECT_THROW(differentiate_3rd_order({}, {}), std::invalid_argument);
  EXPECT_THROW(differentiate_3rd_order({0, 1, 2, 3}, {0, 1, 2}), std::invalid_argument);
}

}  // namespace
}  // namespace dampbench
