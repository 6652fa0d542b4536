// Metrics against hand-computed values (engine/model/metrics.hpp). The candidate model is fvd.linear_viscous
// with m = 0 and C = 1, so the model force is the velocity signal itself.
#include "engine/model/metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/common/error.hpp"
#include "models/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

Signals four_samples() {
  Dataset d;
  d.name = "hand";
  d.t_s = {0.0, 0.5, 1.5, 2.0};  // non-uniform: trapezoid weights 0.25, 0.75, 0.75, 0.25
  d.x_m = {0, 0, 0, 0};
  d.v_m_s = {1, -2, 0.5, 3};
  d.a_m_s2 = {0, 0, 0, 0};
  d.F_N = {2, -3, 1, 2};  // errors e = F − v = 1, −1, 0.5, −1
  return prepare_signals(d);
}

MetricRow metrics_of(const Signals& s, double m, double C) {
  const Model& model = find_model("fvd.linear_viscous");
  CandidateBatch batch(2, 1);
  batch.at(0, 0) = m;
  batch.at(0, 1) = C;
  std::vector<MetricRow> rows(1);
  BatchEvaluator(model, s).evaluate_all(batch, rows);
  return rows[0];
}

}  // namespace

TEST(Signals, TrapezoidWeightsAndForceStatistics) {
  const Signals s = four_samples();
  EXPECT_DOUBLE_EQ(s.w_trapz_s[0], 0.25);
  EXPECT_DOUBLE_EQ(s.w_trapz_s[1], 0.75);
  EXPECT_DOUBLE_EQ(s.w_trapz_s[2], 0.75);
  EXPECT_DOUBLE_EQ(s.w_trapz_s[3], 0.25);
  EXPECT_DOUBLE_EQ(s.duration_s, 2.0);
  EXPECT_DOUBLE_EQ(s.measured_std, std::sqrt(17.0 / 4.0));  // mean 0.5, Σ(F − mean)² = 17
  EXPECT_DOUBLE_EQ(s.measured_max_abs, 3.0);
}

TEST(Metrics, HandComputedValues) {
  const Signals s = four_samples();
  const auto m = metrics_of(s, 0.0, 1.0);
  const double sigma = std::sqrt(4.25);
  // Σ w|e| = 0.25 + 0.75 + 0.375 + 0.25 = 1.625; Σ w e² = 0.25 + 0.75 + 0.1875 + 0.25 = 1.4375
  EXPECT_NEAR(m[0], 1.625 / (sigma * 2.0), 1e-15);    // of_abs
  EXPECT_NEAR(m[1], 1.4375 / (4.25 * 2.0), 1e-15);    // of_sq
  EXPECT_NEAR(m[2], std::sqrt(3.25 / 4.0), 1e-15);    // rmse: Σe² = 3.25
  EXPECT_NEAR(m[3], std::sqrt(3.25 / 4.0) / 3.0, 1e-15);  // nrmse
  EXPECT_NEAR(m[4], 3.5 / 4.0, 1e-15);                // mae: Σ|e| = 3.5
  EXPECT_NEAR(m[5], std::sqrt(0.5 * 3.25 / 3.0) * 100, 1e-12);  // crfd eq. 7.6: T_max = 3
  EXPECT_NEAR(m[6], std::sqrt(3.25 / 18.0), 1e-15);             // mfm eq. 12: ΣF² = 4 + 9 + 1 + 4
  // fdsp eq. 8: ||F_m| − |F|| = |2−1|, |3−2|, |1−0.5|, |2−3| → 3.5; 100·3.5/(4·3)
  EXPECT_NEAR(m[7], 100 * 3.5 / 12.0, 1e-12);
  EXPECT_NEAR(m[8], 100 * 3.5 / 12.0, 1e-12);
}

TEST(Metrics, FdspEquation8ComparesMagnitudesOnly) {
  // Model force = −measured force: every magnitude agrees (eq. 8 gives 0) while the signed variant sees
  // |e| = 2|F|: Σ|e| = 2·(1 + 1 + 2 + 2) = 12, 100·12/(4·2) = 150.
  Dataset d;
  d.name = "mirror";
  d.t_s = {0, 1, 2, 3};
  d.x_m = {0, 0, 0, 0};
  d.v_m_s = {-1, 1, -2, 2};
  d.a_m_s2 = {0, 0, 0, 0};
  d.F_N = {1, -1, 2, -2};
  const auto m = metrics_of(prepare_signals(d), 0.0, 1.0);
  EXPECT_EQ(m[static_cast<int>(Metric::fdsp_pct)], 0.0);
  EXPECT_NEAR(m[static_cast<int>(Metric::fdsp_signed_pct)], 150.0, 1e-12);
}

TEST(Metrics, OfAbsOfASineIsItsMeanAbsoluteValueOverSigma) {
  // Measured F = sin(t) over one period, model force 0: ∫|sin| = 4, T = 2π. σ is that of the n samples
  // (both ends included, mean 0): σ² = Σsin²/n = ((n − 1)/2)/n.
  Dataset d;
  d.name = "sine";
  const int n = 20001;
  for (int k = 0; k < n; ++k) {
    const double t = 2 * std::numbers::pi * k / (n - 1);
    d.t_s.push_back(t);
    d.x_m.push_back(0);
    d.v_m_s.push_back(0);
    d.a_m_s2.push_back(0);
    d.F_N.push_back(std::sin(t));
  }
  const Signals s = prepare_signals(d);
  const auto m = metrics_of(s, 0.0, 0.0);
  const double var = 0.5 * (n - 1) / n;
  EXPECT_NEAR(m[0], 4.0 / (std::sqrt(var) * 2 * std::numbers::pi), 1e-7);
  EXPECT_NEAR(m[1], std::numbers::pi / (var * 2 * std::numbers::pi), 1e-7);  // ∫sin² = π
  EXPECT_NEAR(m[2], std::sqrt(0.5), 1e-4);
  EXPECT_NEAR(m[4], 2 / std::numbers::pi, 1e-4);
}

TEST(Metrics, NonFiniteForceGivesPlusInfinityNeverNaN) {
  const Signals s = four_samples();
  for (double C : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 1e308 * 10}) {
    for (double v : metrics_of(s, 0.0, C)) {
      EXPECT_TRUE(std::isinf(v)) << "C = " << C;
      EXPECT_GT(v, 0);
    }
  }
  // Finite parameters whose force overflows: 1e308 · v with |v| = 3 is +inf.
  for (double v : metrics_of(s, 0.0, 1e308)) EXPECT_EQ(v, std::numeric_limits<double>::infinity());
}

TEST(Metrics, SeveralDatasetsAverageTheirMetrics) {
  // The same record twice with the force doubled on the second: of_abs is scale-free (1.625/(σ·2) on
  // both), rmse doubles on the second, so the mean is 1.5 × the single-record value.
  const Signals a = four_samples();
  Dataset d;
  d.name = "double";
  d.t_s = a.t_s;
  d.x_m = a.x_m;
  d.v_m_s = {2, -4, 1, 6};
  d.a_m_s2 = a.a_m_s2;
  d.F_N = {4, -6, 2, 4};
  const Signals b = prepare_signals(d);
  const Model& model = find_model("fvd.linear_viscous");
  CandidateBatch batch(2, 1);
  batch.at(0, 1) = 1.0;
  std::vector<MetricRow> rows(1);
  BatchEvaluator(model, {&a, &b}).evaluate_all(batch, rows);
  EXPECT_NEAR(rows[0][0], 1.625 / (std::sqrt(4.25) * 2.0), 1e-15);
  EXPECT_NEAR(rows[0][2], 1.5 * std::sqrt(3.25 / 4.0), 1e-14);
  std::vector<double> one(1);
  BatchEvaluator(model, {&a, &b}).evaluate(batch, Metric::rmse, one);
  EXPECT_EQ(one[0], rows[0][2]);
}

TEST(Metrics, NamesRoundTripAndUnknownNameIsRejected) {
  for (Metric m : kAllMetrics) EXPECT_EQ(parse_metric(metric_name(m)), m);
  EXPECT_EQ(testing::error_of([] { parse_metric("r2"); }),
            "unknown metric 'r2' (known: of_abs, of_sq, rmse, nrmse, mae, crfd_eps, mfm_E, fdsp_pct, fdsp_signed_pct)");
}

}  // namespace dampbench
