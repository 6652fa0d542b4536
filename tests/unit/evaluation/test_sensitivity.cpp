// Differential sensitivity (engine/evaluation/sensitivity.cpp, crfd eqs. 4.1–4.3) on a law where f is known in
// closed form: fvd.linear_viscous with m = 0 has f(C) = C·RMS(v), so every point sensitivity is RMS(v).
#include "engine/evaluation/sensitivity.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/record/excitation.hpp"
#include "models/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

Signals record() { return testing::sine_signals(0.02, 1.0, 1, 400); }

double rms(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return std::sqrt(s / static_cast<double>(v.size()));
}

}  // namespace

TEST(Sensitivity, LinearLawHasConstantSensitivity) {
  const Signals data = record();
  const std::vector<double> p{0.0, 3000.0};  // m = 0 kg, C = 3000 N·s/m
  const auto s = differential_sensitivity(find_model("fvd.linear_viscous"), p, data);
  EXPECT_EQ(s.S[0], 0.0);  // m = 0: its ±50 % grid is a single point, no sensitivity
  EXPECT_NEAR(s.S[1], rms(data.v_m_s), 1e-9 * rms(data.v_m_s));
  EXPECT_DOUBLE_EQ(s.SP[1], 100.0);
  SensitivitySettings normalized;
  normalized.normalized = true;
  EXPECT_NEAR(differential_sensitivity(find_model("fvd.linear_viscous"), p, data, normalized).S[1],
              3000.0 * rms(data.v_m_s), 1e-6);
}

TEST(Sensitivity, PercentagesSumTo100AndFollowTheEndpointRule) {
  // generalized viscous: f depends on C linearly and on α through |v|^α; SP sums to 100.
  const auto s = differential_sensitivity(find_model("fvd.generalized_viscous"), std::vector<double>{100.0, 5e5, 0.4},
                                          record());
  EXPECT_NEAR(s.SP[0] + s.SP[1] + s.SP[2], 100.0, 1e-9);
  EXPECT_GT(s.S[2], 0.0);
}

TEST(Sensitivity, BadSettingsAreRejected) {
  SensitivitySettings bad;
  bad.points = 2;
  EXPECT_EQ(testing::error_of([&] {
              differential_sensitivity(find_model("fvd.linear_viscous"), std::vector<double>{0.0, 1.0}, record(), bad);
            }),
            "sensitivity: --points must be at least 3, got 2");
  SensitivitySettings metric;
  metric.metric = Metric::rmse;
  EXPECT_EQ(testing::error_of([&] {
              differential_sensitivity(find_model("fvd.linear_viscous"), std::vector<double>{0.0, 1.0}, record(), metric);
            }),
            "sensitivity: a metric objective needs a record with measured force F");
}

}  // namespace dampbench
