// Reconstructions of an input between its samples (engine/record/bandlimited.hpp), against functions they must
// reproduce exactly: trigonometric polynomials below the Nyquist rate, and cubic polynomials.
#include "engine/record/bandlimited.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

namespace dampbench {
namespace {

constexpr double kPi = std::numbers::pi;

double trig(double t_periods) {  // lines 1, 3 and 7 of a period
  return 1.5 + std::cos(2 * kPi * t_periods + 0.3) - 0.7 * std::sin(2 * kPi * 3 * t_periods) +
         0.2 * std::cos(2 * kPi * 7 * t_periods + 2);
}

class Periodic : public ::testing::TestWithParam<int> {};

TEST_P(Periodic, ReproducesATrigonometricPolynomialBelowNyquist) {
  const int n = GetParam(), factor = 5;
  std::vector<double> x(n);
  for (int k = 0; k < n; ++k) x[k] = trig(static_cast<double>(k) / n);
  const std::vector<double> fine = upsample_periodic(x, factor);
  ASSERT_EQ(fine.size(), static_cast<std::size_t>(n * factor));
  for (int i = 0; i < n * factor; ++i) EXPECT_NEAR(fine[i], trig(static_cast<double>(i) / (n * factor)), 1e-12) << i;
  EXPECT_EQ(upsample_periodic(x, 1), x);
}

INSTANTIATE_TEST_SUITE_P(OddAndEven, Periodic, ::testing::Values(16, 17, 30));

TEST(Spline, ReproducesCubicsAndPassesThroughTheSamples) {
  const auto cubic = [](double t) { return 2 - 0.5 * t + 0.25 * t * t - 0.03 * t * t * t; };
  std::vector<double> x(11);
  for (int k = 0; k < 11; ++k) x[k] = cubic(k);
  const int factor = 4;
  const std::vector<double> fine = upsample_spline(x, factor);
  ASSERT_EQ(fine.size(), 10u * factor + 1);
  for (std::size_t i = 0; i < fine.size(); ++i)
    EXPECT_NEAR(fine[i], cubic(static_cast<double>(i) / factor), 1e-12 * 30) << i;
  for (int k = 0; k < 11; ++k) EXPECT_DOUBLE_EQ(fine[static_cast<std::size_t>(k * factor)], x[k]);
}

TEST(Spline, ConvergesAsTheFourthPowerOfTheStep) {
  const auto max_error = [](int n) {
    std::vector<double> x(n + 1);
    for (int k = 0; k <= n; ++k) x[k] = std::sin(2 * kPi * k / n);
    const std::vector<double> fine = upsample_spline(x, 10);
    double worst = 0;
    for (std::size_t i = 0; i < fine.size(); ++i)
      worst = std::max(worst, std::fabs(fine[i] - std::sin(2 * kPi * static_cast<double>(i) / (10.0 * n))));
    return worst;
  };
  const double ratio = max_error(80) / max_error(160);  // asymptotic from about 80 samples per period
  EXPECT_GT(ratio, 14);
  EXPECT_LT(ratio, 18);
}

}  // namespace
}  // namespace dampbench
