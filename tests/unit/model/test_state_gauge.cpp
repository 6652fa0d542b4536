// The gauge of the Bouc–Wen state (engine/model/model.hpp StateGauge, applied by engine/model/law_model.cpp):
// z → s·z with A → s·A, α → α/s, β, γ → β·s^(1−n), γ·s^(1−n) leaves the force unchanged, so a law model that ties
// A = β + γ (s = ((β+γ)/A)^(1/n), |z| saturating at 1) loses nothing and makes α the hysteretic force.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/model/law_model.hpp"
#include "models/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

/// The gauged coefficients of base parameters `p` (order of the base model) for a law model with no laws.
std::vector<double> gauged(const Model& base, const LawModel& law, std::vector<double> p) {
  const auto at = [&](const char* n) -> double& { return p[static_cast<std::size_t>(base.parameter_index(n))]; };
  const double n = at("n"), s = std::pow((at("beta") + at("gamma")) / at("A"), 1.0 / n);
  at("alpha") /= s;
  at("beta") *= std::pow(s, 1.0 - n);
  at("gamma") *= std::pow(s, 1.0 - n);
  std::vector<double> c;
  for (const auto& info : law.parameters()) c.push_back(at(info.name.c_str()));
  return c;
}

TEST(StateGauge, SpencerUnderTheGaugeGivesTheUngaugedForce) {
  const Model& base = find_model("mrd.spencer");
  const LawModel law(base, {});
  ASSERT_TRUE(law.applied_gauge().has_value());
  EXPECT_EQ(law.dim(), base.dim() - 1);  // A has no coefficient
  const auto data = testing::sine_signals(0.01, 1.0, 2, 2000, {});
  // c0, c1, k0, k1, x0, alpha, beta, gamma, A, n: A = 50 and β + γ = 4e4 put |z| at its bound 0.0724 m
  const std::vector<double> p{1500, 9000, 1200, 100, 0.001, 3000, -2e4, 6e4, 50, 1.5};
  const auto reference = base.simulate_reference(p, data);
  ASSERT_TRUE(reference.has_value());
  const auto c = gauged(base, law, p);
  // the gauged α is the hysteretic force: 3000 N/m × 0.0724 m = 217 N
  EXPECT_NEAR(c[static_cast<std::size_t>(law.parameter_index("alpha"))], 3000 * std::pow(50.0 / 4e4, 1 / 1.5), 1e-9);
  EXPECT_LT(testing::relative_l2(*law.simulate_reference(c, data), *reference), 1e-6);
  EXPECT_LT(testing::relative_l2(law.simulate(c, data), *reference), 1e-4);  // the lane kernel, against CVODE
  // a scale that is not the gauge's changes the force: the test can fail
  auto wrong = c;
  wrong[static_cast<std::size_t>(law.parameter_index("alpha"))] *= 1.1;
  EXPECT_GT(testing::relative_l2(law.simulate(wrong, data), *reference), 1e-3);
}

TEST(StateGauge, BoucWenTiesAToBetaPlusGammaAndChangesUnits) {
  const Model& base = find_model("mrd.bouc_wen");
  const LawModel law(base, {});
  const auto data = testing::sine_signals(0.01, 1.0, 1, 500, {});
  std::vector<double> c(static_cast<std::size_t>(law.dim()), 0.0);
  for (int j = 0; j < law.dim(); ++j) c[static_cast<std::size_t>(j)] = 1.0 + j;
  const auto p = law.base_parameters(c, data);
  const auto at = [&](const char* n) { return p[static_cast<std::size_t>(base.parameter_index(n))]; };
  EXPECT_EQ(at("A"), at("beta") + at("gamma"));
  EXPECT_EQ(law.parameters()[static_cast<std::size_t>(law.parameter_index("alpha"))].unit, "N");
  EXPECT_EQ(std::string(law.id()), "mrd.bouc_wen[]");
}

TEST(StateGauge, ALawOnTheTiedParameterTurnsTheGaugeOff) {
  const Model& base = find_model("mrd.spencer");
  const LawModel law(base, parse_laws("A=free", "test"));
  EXPECT_FALSE(law.applied_gauge().has_value());
  EXPECT_EQ(law.dim(), base.dim());
  EXPECT_EQ(law.parameters()[static_cast<std::size_t>(law.parameter_index("alpha"))].unit, "N/m");
}

TEST(StateGauge, ModelsWithoutAScaleSymmetryHaveNoGauge) {
  EXPECT_FALSE(find_model("mrd.magic_formula").state_gauge().has_value());
  EXPECT_FALSE(find_model("mrd.spencer_voltage").state_gauge().has_value());  // fdsp's A is a published value
}

}  // namespace
}  // namespace dampbench
