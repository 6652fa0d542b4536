// fvd models (models/fvd.cpp): hand-computed forces, paper units, and recovery of known parameters
// from noise-free synthetic data by PSO.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/model/bounds.hpp"
#include "engine/common/error.hpp"
#include "engine/identification/identification.hpp"
#include "models/registry.hpp"
#include "optimizers/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

/// Three samples: (x, v, a) = (0.1, −0.25, 2), (−0.05, 0, −1), (0.02, 0.64, 0.5).
Signals three_samples() {
  Dataset d;
  d.name = "hand";
  d.t_s = {0, 1, 2};
  d.x_m = {0.1, -0.05, 0.02};
  d.v_m_s = {-0.25, 0.0, 0.64};
  d.a_m_s2 = {2.0, -1.0, 0.5};
  return prepare_signals(d);
}

std::vector<double> force(const std::string& id, std::vector<double> params) {
  return find_model(id).simulate(params, three_samples());
}

}  // namespace

TEST(FvdModels, LinearViscousHandValues) {
  const auto F = force("fvd.linear_viscous", {2.0, 3.0});  // m = 2 kg, C = 3 N·s/m
  EXPECT_DOUBLE_EQ(F[0], 2 * 2.0 + 3 * -0.25);  // 3.25
  EXPECT_DOUBLE_EQ(F[1], -2.0);
  EXPECT_DOUBLE_EQ(F[2], 1.0 + 3 * 0.64);
}

TEST(FvdModels, GeneralizedViscousHandValues) {
  const auto F = force("fvd.generalized_viscous", {2.0, 3.0, 0.5});
  EXPECT_NEAR(F[0], 4.0 - 3.0 * 0.5, 1e-14);       // |−0.25|^0.5 = 0.5
  EXPECT_DOUBLE_EQ(F[1], -2.0);                     // v = 0: sgn(0) = 0, no viscous force
  EXPECT_NEAR(F[2], 1.0 + 3.0 * 0.8, 1e-14);       // 0.64^0.5 = 0.8
}

TEST(FvdModels, GeneralizedViscousAtZeroVelocityIsFiniteForAlphaZero) {
  const auto F = force("fvd.generalized_viscous", {0.0, 5.0, 0.0});  // α = 0: dry friction C·sgn(v)
  EXPECT_NEAR(F[0], -5.0, 1e-13);
  EXPECT_EQ(F[1], 0.0);
  EXPECT_NEAR(F[2], 5.0, 1e-13);
}

TEST(FvdModels, GvLinearElasticHandValues) {
  const auto F = force("fvd.gv_linear_elastic", {2.0, 3.0, 0.5, 4.0});
  EXPECT_NEAR(F[0], 4.0 - 1.5 + 0.4, 1e-14);
  EXPECT_NEAR(F[1], -2.0 - 0.2, 1e-14);
  EXPECT_NEAR(F[2], 1.0 + 2.4 + 0.08, 1e-14);
}

TEST(FvdModels, GvQuadraticElasticHandValues) {
  const auto F = force("fvd.gv_quadratic_elastic", {2.0, 3.0, 0.5, 4.0, 5.0});
  EXPECT_NEAR(F[0], 4.0 - 1.5 + 0.4 + 0.05, 1e-14);  // K2·x² = 5·0.01
  EXPECT_NEAR(F[1], -2.0 - 0.2 + 0.0125, 1e-14);
  EXPECT_NEAR(F[2], 1.0 + 2.4 + 0.08 + 0.002, 1e-14);
}

TEST(FvdModels, PaperUnits) {
  // C = 1e6 N/(m/s) at α = 1 is 1 kN/(mm/s); at α = 0, 1e3 N is 1 kN; K1 1e6 N/m = 1 kN/mm; K2 1e9 N/m² = 1 kN/mm².
  const Model& q = find_model("fvd.gv_quadratic_elastic");
  const std::vector<double> a{7.0, 1e6, 1.0, 2e6, 3e9};
  const auto pa = q.to_paper_units(a);
  EXPECT_DOUBLE_EQ(pa[0], 7.0);
  EXPECT_DOUBLE_EQ(pa[1], 1.0);
  EXPECT_DOUBLE_EQ(pa[2], 1.0);
  EXPECT_DOUBLE_EQ(pa[3], 2.0);
  EXPECT_DOUBLE_EQ(pa[4], 3.0);
  EXPECT_DOUBLE_EQ(q.to_paper_units(std::vector<double>{0, 1e3, 0.0, 0, 0})[1], 1.0);
  // Design point (fvd Table 1): 406.24 kN/(mm/s)^0.1 is 406.24e3 · 1000^0.1 N/(m/s)^0.1.
  const double C_si = 406.24e3 * std::pow(1000.0, 0.1);
  EXPECT_NEAR(q.to_paper_units(std::vector<double>{0, C_si, 0.1, 0, 0})[1], 406.24, 1e-9);
  EXPECT_DOUBLE_EQ(find_model("fvd.linear_viscous").to_paper_units(std::vector<double>{0, 6.3e6})[1], 6.3);
}

TEST(FvdModels, ListedWithParametersAndCitations) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> expected{
      {"fvd.linear_viscous", {"m", "C"}},
      {"fvd.generalized_viscous", {"m", "C", "alpha"}},
      {"fvd.gv_linear_elastic", {"m", "C", "alpha", "K1"}},
      {"fvd.gv_quadratic_elastic", {"m", "C", "alpha", "K1", "K2"}}};
  for (const auto& [id, names] : expected) {
    const Model& m = find_model(id);
    ASSERT_EQ(m.dim(), static_cast<int>(names.size())) << id;
    for (int j = 0; j < m.dim(); ++j) {
      EXPECT_EQ(m.parameters()[j].name, names[j]);
      EXPECT_LT(m.parameters()[j].lower, m.parameters()[j].upper);
      EXPECT_FALSE(m.parameters()[j].unit.empty());
    }
    EXPECT_EQ(m.citation().substr(0, 8), "fvd eq. ");
  }
}

TEST(FvdModels, UnknownModelAndParameterAreNamed) {
  EXPECT_NE(testing::error_of([] { find_model("fvd.maxwell"); }).find("unknown model 'fvd.maxwell' (known: fvd.linear_viscous"),
            std::string::npos);
  EXPECT_EQ(testing::error_of([] { (void)find_model("fvd.linear_viscous").parameter_index("K1"); }),
            "model fvd.linear_viscous has no parameter 'K1' (parameters: m, C)");
}

// Recovery: force from known parameters on a two-frequency record (noise-free), then PSO
// (N = 50, L = 200, 8 runs). Done when the best run has OF < 1e-3 and every parameter within 1 %.
struct RecoveryCase {
  std::string model;
  std::vector<double> truth;
};

/// Names the case in test listings instead of dumping its bytes.
void PrintTo(const RecoveryCase& c, std::ostream* os) { *os << c.model; }

class FvdRecovery : public ::testing::TestWithParam<RecoveryCase> {};

TEST_P(FvdRecovery, PsoRecoversKnownParameters) {
  const auto& c = GetParam();
  const Model& model = find_model(c.model);
  Dataset d = testing::two_sine_record();
  const Signals input = prepare_signals(d);
  d.F_N = model.simulate(c.truth, input);
  const Signals data = prepare_signals(d);

  IdentificationSettings settings;
  settings.runs = 8;
  settings.seed = 11;
  settings.task_key = task_key(c.model, "two_sine", "pso");
  const auto result = identify(model, data, default_bounds(model), make_optimizer_factory({"pso", 50, 200}), settings);
  const RunResult& best = result.runs[result.best_run()];
  EXPECT_LT(best.best_value, 1e-3);
  for (int j = 0; j < model.dim(); ++j)
    EXPECT_NEAR(best.best_params[j], c.truth[j], 0.01 * std::fabs(c.truth[j])) << model.parameters()[j].name;
}

INSTANTIATE_TEST_SUITE_P(
    AllFvdModels, FvdRecovery,
    ::testing::Values(RecoveryCase{"fvd.linear_viscous", {500.0, 3e6}},
                      RecoveryCase{"fvd.generalized_viscous", {500.0, 8e5, 0.3}},
                      RecoveryCase{"fvd.gv_linear_elastic", {500.0, 8e5, 0.3, 4e6}},
                      RecoveryCase{"fvd.gv_quadratic_elastic", {500.0, 8e5, 0.3, 4e6, 3e7}}),
    [](const auto& p) { return p.param.model.substr(4); });

}  // namespace dampbench
