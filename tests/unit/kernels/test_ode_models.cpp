// ODE models (engine/kernels/ode_kernel.hpp) against SUNDIALS CVODE at published parameters: the fixed-step
// RK4 force must be within a relative L2 difference of 1e-4 of the CVODE force (BDF, rtol 1e-10) on the
// same piecewise-linear inputs. Also: blown-up candidates are masked, n < 1 starting at z = 0 is finite.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/record/excitation.hpp"
#include "models/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

Signals sine(double amp_m, double freq_hz, double cycles, double fs_hz, double V = 0) {
  return testing::sine_signals(amp_m, freq_hz, cycles, fs_hz, {{"V", V}});
}

/// Parameters by name, in the model's order.
std::vector<double> params(const Model& m, const std::vector<std::pair<std::string, double>>& named) {
  std::vector<double> p(m.dim(), std::nan(""));
  for (const auto& [name, value] : named) p[m.parameter_index(name)] = value;
  for (double v : p) EXPECT_FALSE(std::isnan(v)) << "parameter missing in the test";
  return p;
}

void expect_matches_cvode(const std::string& id, const std::vector<double>& p, const Signals& data) {
  const Model& model = find_model(id);
  const auto fixed_step = model.simulate(p, data);
  const auto reference = model.simulate_reference(p, data);
  ASSERT_TRUE(reference.has_value()) << id << " has no CVODE reference";
  const double diff = testing::relative_l2(fixed_step, *reference);
  EXPECT_LT(diff, 1e-4) << id;
  ::testing::Test::RecordProperty(id + "_rel_l2_vs_cvode", std::to_string(diff));
  std::printf("%s: relative L2 difference to CVODE %.3g\n", id.c_str(), diff);
}

// mfm Table 3 laws evaluated at I = 1 A: c0 = (1.870 + 2.240)e3, c1 = (1.727 + 2.815)e5, α = 71.44 + 94.57,
// A = (4.731 + 0.29)e4.
std::vector<std::pair<std::string, double>> mfm_spencer_1A() {
  return {{"c0", 4110.0},   {"c1", 4.542e5},  {"k0", 42.83},     {"k1", 561.2}, {"x0", -6.678e-2},
          {"alpha", 166.01}, {"beta", 6.079e3}, {"gamma", 1.083e4}, {"A", 5.021e4}, {"n", 0.9929}};
}

// fdsp Table 2 (2.5 Hz, 0 V) with the b-coefficients and η of Table 1 (no effect at 0 V).
std::vector<std::pair<std::string, double>> fdsp_table2() {
  return {{"K0", 3361.58},  {"K1", 420.0},      {"a_c0", 1176.0},     {"a_c1", 21973.50}, {"b_c0", 1803.0},
          {"b_c1", 34622.0}, {"a_alpha", 6515.13}, {"b_alpha", 38430.0}, {"A", 87.0},        {"beta", 307269.41},
          {"gamma", 182842.99}, {"n", 2.0},       {"eta", 190.0},       {"Z0", 0.01225}};
}

}  // namespace

TEST(OdeModels, SpencerMatchesCvodeAtMfmTable3) {
  expect_matches_cvode("mrd.spencer", params(find_model("mrd.spencer"), mfm_spencer_1A()), sine(0.01, 1.0, 2, 500));
}

TEST(OdeModels, BoucWenMatchesCvode) {
  // Bouc–Wen with the hysteretic constants of mfm Table 3 at 1 A and a viscous and elastic part.
  const Model& m = find_model("mrd.bouc_wen");
  const auto p = params(m, {{"c0", 3000}, {"k0", 500}, {"x0", 0.0}, {"alpha", 4e4}, {"beta", 6.079e3},
                            {"gamma", 1.083e4}, {"A", 120.0}, {"n", 0.9929}});
  expect_matches_cvode("mrd.bouc_wen", p, sine(0.01, 1.0, 2, 500));
}

TEST(OdeModels, SpencerVoltageMatchesCvodeAtFdspTable2) {
  expect_matches_cvode("mrd.spencer_voltage", params(find_model("mrd.spencer_voltage"), fdsp_table2()),
                       sine(0.00635, 2.5, 3, 1000));
}

TEST(OdeModels, SpencerVoltageWithVoltageMatchesCvode) {
  expect_matches_cvode("mrd.spencer_voltage", params(find_model("mrd.spencer_voltage"), fdsp_table2()),
                       sine(0.00635, 2.5, 3, 1000, 1.5));
}

TEST(OdeModels, MaxwellMatchesCvodeAtCrfdTable7At90Degrees) {
  // crfd Table 7 cubic laws at φ = 90°: c_r = 2.184 + 0.103·90 − 1.938e-4·90² + 8.497e-8·90³, etc.
  const double phi = 90;
  const double c_r = 2.184 + 0.103 * phi - 1.938e-4 * phi * phi + 8.497e-8 * phi * phi * phi;
  const double k_r = 53.24 - 0.367 * phi + 6.789e-3 * phi * phi - 2.822e-5 * phi * phi * phi;
  const double alpha = 0.843 + 1.288e-4 * phi + 1.688e-5 * phi * phi - 8.569e-8 * phi * phi * phi;
  const double beta = 0.943 - 1.471e-2 * phi + 1.546e-4 * phi * phi - 5.089e-7 * phi * phi * phi;
  const Model& m = find_model("crfd.maxwell");
  // Rotation of about ±0.02 rad at 3 Hz (an MTS stroke of ±3 mm on the 80 mm arm).
  expect_matches_cvode("crfd.maxwell", params(m, {{"c_r", c_r}, {"k_r", k_r}, {"alpha", alpha}, {"beta", beta}}),
                       sine(0.02, 3.0, 3, 1000));
}

TEST(OdeModels, StartAtZeroWithExponentBelowOneIsFinite) {
  // docs/models.md §6: z|z|^(n−1) at z = 0 with n < 1 must not give NaN.
  const Model& m = find_model("mrd.spencer");
  auto p = params(m, mfm_spencer_1A());
  p[m.parameter_index("n")] = 0.6;
  for (double f : m.simulate(p, sine(0.01, 1.0, 1, 200))) ASSERT_TRUE(std::isfinite(f));
}

TEST(OdeModels, BlownUpCandidateIsMaskedWithoutTouchingNeighbours) {
  const Model& m = find_model("mrd.bouc_wen");
  SineSpec spec;
  spec.amplitude_m = 0.01;
  spec.freq_hz = 1;
  spec.cycles = 1;
  spec.fs_hz = 200;
  Dataset d = make_sine(spec);
  const Signals input = prepare_signals(d);
  const auto good = params(m, {{"c0", 3000}, {"k0", 500}, {"x0", 0.0}, {"alpha", 4e4}, {"beta", 6e3},
                               {"gamma", 1e4}, {"A", 120.0}, {"n", 1.0}});
  d.F_N = m.simulate(good, input);
  const Signals data = prepare_signals(d);
  CandidateBatch batch(m.dim(), 3);
  batch.set_candidate(0, good);
  auto wild = good;  // negative β and γ: z grows without bound
  wild[m.parameter_index("beta")] = -1e8;
  wild[m.parameter_index("gamma")] = -1e8;
  wild[m.parameter_index("A")] = 1e6;
  batch.set_candidate(1, wild);
  batch.set_candidate(2, good);
  std::vector<double> out(3);
  BatchEvaluator(m, data).evaluate(batch, Metric::nrmse, out);
  EXPECT_EQ(out[1], std::numeric_limits<double>::infinity());
  EXPECT_LT(out[0], 1e-12);
  EXPECT_EQ(out[0], out[2]);
}

}  // namespace dampbench
