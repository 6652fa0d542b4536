// Identifiability evidence (engine/identification/identifiability.cpp): the closed-form covariance of a
// linear least-squares fit, an exact trade-off flagged (fvd m against K1 on one sine, where a = −ω²x), the
// same model on a two-frequency record not flagged, parameters at a bound and held by their bounds.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "engine/common/random.hpp"
#include "engine/identification/identifiability.hpp"
#include "engine/record/excitation.hpp"
#include "models/registry.hpp"
#include "test_support.hpp"

namespace dampbench {
namespace {

/// The model's force at `truth` plus Gaussian noise of `relative` × RMS from a keyed stream.
Signals noisy(const Model& model, Dataset d, const std::vector<double>& truth, double relative) {
  d.F_N = model.simulate(truth, prepare_signals(d));
  testing::add_force_noise(d, relative, 42);
  return prepare_signals(d);
}

Dataset one_sine() {
  SineSpec spec;
  spec.amplitude_m = 0.02;
  spec.freq_hz = 1.0;
  spec.cycles = 3;
  spec.fs_hz = 500;
  return make_sine(spec);
}

bool has_flag(const Identifiability& id, int j, const std::string& start) {
  for (const auto& f : id.flags[j])
    if (f.rfind(start, 0) == 0) return true;
  return false;
}

TEST(Identifiability, LinearModelMatchesTheClosedFormCovariance) {
  // fvd.linear_viscous, F = m·a + C·v, is linear in (m, C): cov = SSR/(N − 2)·(XᵀX)⁻¹ with X = [a v].
  const Model& model = find_model("fvd.linear_viscous");
  const Signals s = noisy(model, testing::two_sine_record(), {300.0, 2e5}, 0.02);
  const int n = static_cast<int>(s.size());
  Eigen::MatrixXd X(n, 2);
  Eigen::VectorXd F(n);
  for (int k = 0; k < n; ++k) {
    X(k, 0) = s.a_m_s2[k];
    X(k, 1) = s.v_m_s[k];
    F[k] = s.F_N[k];
  }
  const Eigen::VectorXd beta = X.colPivHouseholderQr().solve(F);
  const double ssr = (F - X * beta).squaredNorm();
  const Eigen::MatrixXd cov = ssr / (n - 2) * (X.transpose() * X).inverse();

  const Signals* data[] = {&s};
  const Bounds box{{0.0, 0.0}, {2000.0, 2e7}};
  const Identifiability id = assess_identifiability(model, data, box, std::vector<double>{beta[0], beta[1]});
  EXPECT_NEAR(id.std_error[0], std::sqrt(cov(0, 0)), 1e-4 * std::sqrt(cov(0, 0)));
  EXPECT_NEAR(id.std_error[1], std::sqrt(cov(1, 1)), 1e-4 * std::sqrt(cov(1, 1)));
  EXPECT_NEAR(id.correlation[0][1], cov(0, 1) / std::sqrt(cov(0, 0) * cov(1, 1)), 1e-4);
  EXPECT_EQ(id.samples, n);
  EXPECT_TRUE(id.all_identifiable()) << id.summary(model);
}

TEST(Identifiability, MassAndStiffnessTradeOffExactlyOnOneSine) {
  // On x = X sin ωt the inertia term m·a = −mω²x is a stiffness: only K1 − mω² is determined.
  const Model& model = find_model("fvd.gv_linear_elastic");
  const std::vector<double> truth{300.0, 8.2e5, 0.3, 4e6};
  const Signals s = noisy(model, one_sine(), truth, 0.01);
  const Signals* data[] = {&s};
  const Identifiability id = assess_identifiability(model, data, default_bounds(model), truth);
  EXPECT_TRUE(has_flag(id, 0, "correlated with K1")) << id.summary(model);
  EXPECT_TRUE(has_flag(id, 3, "correlated with m")) << id.summary(model);
  EXPECT_TRUE(has_flag(id, 0, "not identifiable")) << id.summary(model);
  EXPECT_FALSE(id.all_identifiable());
  EXPECT_NEAR(id.correlation[0][3], 1.0, 1e-6);  // m up, K1 up: K1 − mω² unchanged
  EXPECT_TRUE(id.flags[1].empty()) << id.summary(model);  // C and α stay determined
  EXPECT_TRUE(id.flags[2].empty()) << id.summary(model);
}

TEST(Identifiability, TwoFrequenciesSeparateMassAndStiffness) {
  const Model& model = find_model("fvd.gv_linear_elastic");
  const std::vector<double> truth{300.0, 8.2e5, 0.3, 4e6};
  const Signals s = noisy(model, testing::two_sine_record(), truth, 0.01);
  const Signals* data[] = {&s};
  const Identifiability id = assess_identifiability(model, data, default_bounds(model), truth);
  EXPECT_TRUE(id.all_identifiable()) << id.summary(model);
  EXPECT_EQ(id.summary(model), "ok");
  for (int j = 0; j < 4; ++j) EXPECT_LT(id.relative_error[j], 0.2) << j;
}

TEST(Identifiability, BoundsAreReported) {
  const Model& model = find_model("fvd.gv_linear_elastic");
  const std::vector<double> truth{300.0, 8.2e5, 0.3, 4e6};
  const Signals s = noisy(model, testing::two_sine_record(), truth, 0.01);
  const Signals* data[] = {&s};
  Bounds box = default_bounds(model);
  box.upper[2] = 0.3;                    // α at its upper bound
  box.lower[0] = box.upper[0] = 300.0;  // m held by its bounds: not estimated, not flagged
  const Identifiability id = assess_identifiability(model, data, box, truth);
  EXPECT_TRUE(has_flag(id, 2, "at bound")) << id.summary(model);
  EXPECT_TRUE(id.flags[0].empty()) << id.summary(model);
  EXPECT_EQ(id.std_error[0], 0.0);
  EXPECT_TRUE(id.flags[3].empty()) << id.summary(model);
}

}  // namespace
}  // namespace dampbench
