// Models stepped one sample at a time (engine/model/stepper.hpp, engine/kernels/law_stepper.hpp): the stepped
// force is the batch kernel's (algebraic laws: to rounding) or converges to CVODE's (ODE laws) as the fixed
// sub-steps grow; law models re-evaluate their laws when the variables change; states save and restore.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/common/error.hpp"
#include "engine/model/law_model.hpp"
#include "engine/model/stepped_simulation.hpp"
#include "models/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

std::vector<double> named(const Model& m, const std::vector<std::pair<std::string, double>>& values) {
  std::vector<double> p(m.dim(), std::nan(""));
  for (const auto& [name, value] : values) p[m.parameter_index(name)] = value;
  return p;
}

/// The middle of each default bound.
std::vector<double> box_middle(const Model& m) {
  std::vector<double> p;
  for (const auto& info : m.parameters()) p.push_back(0.5 * (info.lower + info.upper));
  return p;
}

}  // namespace

TEST(LawStepper, LinearViscousIsItsLawAtEverySample) {
  const Model& m = find_model("fvd.linear_viscous");
  const Signals data = testing::sine_signals(0.01, 2.0, 1, 200);
  const auto force = simulate_stepped(m, named(m, {{"m", 3.0}, {"C", 5000.0}}), data, 1);
  for (std::size_t k = 0; k < data.size(); ++k)
    ASSERT_DOUBLE_EQ(force[k], 3.0 * data.a_m_s2[k] + 5000.0 * data.v_m_s[k]) << "sample " << k;
}

TEST(LawStepper, EveryAlgebraicRigModelGivesTheBatchKernelsForce) {
  const Signals data = testing::sine_signals(0.01, 1.5, 2, 400, {{"V", 1.0}});
  int checked = 0;
  for (const Model* m : all_models()) {
    if (m->is_system() || m->has_internal_states()) continue;
    auto stepper = m->stepper();
    ASSERT_TRUE(stepper) << m->id() << " has no stepper";
    const auto p = box_middle(*m);
    const double diff = testing::relative_l2(simulate_stepped(*m, p, data, 1), m->simulate(p, data));
    EXPECT_LT(diff, 1e-12) << m->id();
    ++checked;
  }
  EXPECT_GE(checked, 9);
}

TEST(LawStepper, OdeModelsConvergeToCvodeWithMoreSubsteps) {
  // mfm Table 3 at 1 A (as test_ode_models.cpp) and a gauged Bouc–Wen with |z| saturating at 1.
  const Signals data = testing::sine_signals(0.01, 1.0, 2, 500);
  const std::vector<std::pair<std::string, std::vector<std::pair<std::string, double>>>> cases{
      {"mrd.spencer",
       {{"c0", 4110.0}, {"c1", 4.542e5}, {"k0", 42.83}, {"k1", 561.2}, {"x0", -6.678e-2}, {"alpha", 166.01},
        {"beta", 6.079e3}, {"gamma", 1.083e4}, {"A", 5.021e4}, {"n", 0.9929}}},
      {"mrd.bouc_wen",
       {{"c0", 2000.0}, {"k0", 1000.0}, {"x0", 0.0}, {"alpha", 500.0}, {"A", 600.0}, {"beta", 300.0}, {"gamma", 300.0},
        {"n", 1.5}}},
      {"crfd.maxwell", {{"c_r", 10.0}, {"k_r", 50.0}, {"alpha", 0.8}, {"beta", 0.9}}}};
  for (const auto& [id, values] : cases) {
    const Model& m = find_model(id);
    const auto p = named(m, values);
    const auto reference = *m.simulate_reference(p, data);
    const double coarse = testing::relative_l2(simulate_stepped(m, p, data, 4), reference);
    const double fine = testing::relative_l2(simulate_stepped(m, p, data, 64), reference);
    EXPECT_LT(fine, 1e-6) << id;
    EXPECT_LT(fine, coarse) << id << ": more sub-steps must not be further from CVODE";
  }
}

TEST(LawStepper, LawModelsFollowTheVariablesOfEachStep) {
  const Model& base = find_model("fvd.linear_viscous");
  const LawModel law(base, parse_laws("C=poly(I,1)", "test"));
  auto stepper = law.stepper();
  ASSERT_TRUE(stepper);
  const auto c = named(law, {{"m", 0.0}, {"C_I0", 1000.0}, {"C_I1", 2000.0}});
  stepper->set_parameters(c, {{"I", 0.0}});
  EXPECT_DOUBLE_EQ(stepper->force(0.0, 0.1, 0.0), 100.0);
  stepper->set_parameters(c, {{"I", 1.0}});
  EXPECT_DOUBLE_EQ(stepper->force(0.0, 0.1, 0.0), 300.0);
  EXPECT_THROW(stepper->set_parameters(c, {{"V", 1.0}}), InputError);
}

TEST(LawStepper, DriverLagFollowsTheFirstOrderResponseToACommandStep) {
  // C = 1000 + 2000·I N·s/m with a lag of τ = 50 ms behind a current that steps from 0 to 1 A at sample 200:
  // the laws see u(t) = 1 − e^(−(t − t_step)/τ), so F = (1000 + 2000·u)·v at every sample (the exact response, as
  // a viscous law has no state of its own).
  const Model& base = find_model("fvd.linear_viscous");
  const LawModel law(base, parse_laws("C=poly(I,1);tau_I=0.05", "test"));
  ASSERT_EQ(law.dim(), 3);  // m, C_I0, C_I1: a fixed tau is no coefficient
  Signals data = testing::sine_signals(0.01, 1.0, 1, 1000, {{"I", 0.5}});
  std::vector<double> current(data.size(), 0.0);
  for (std::size_t k = 200; k < current.size(); ++k) current[k] = 1.0;
  data.operating_signals["I"] = current;
  const auto force = simulate_stepped(law, named(law, {{"m", 0.0}, {"C_I0", 1000.0}, {"C_I1", 2000.0}}), data, 4);
  for (std::size_t k = 0; k < data.size(); ++k) {
    const double u = k <= 200 ? 0.0 : 1.0 - std::exp(-(data.t_s[k] - data.t_s[200]) / 0.05);
    ASSERT_NEAR(force[k], (1000.0 + 2000.0 * u) * data.v_m_s[k], 1e-9 * 3000.0 * 0.0629) << "sample " << k;
  }
  // A free tau is a coefficient in seconds; a lag of a variable no law uses, or a negative tau, is refused.
  const LawModel free_tau(base, parse_laws("C=poly(I,1);tau_I=free", "test"));
  EXPECT_EQ(free_tau.parameters().back().name, "tau_I");
  EXPECT_EQ(free_tau.parameters().back().unit, "s");
  EXPECT_NE(testing::error_of([&] { LawModel(base, parse_laws("C=poly(I,1);tau_V=free", "test")); }).find("which no law uses"),
            std::string::npos);
  EXPECT_NE(testing::error_of([&] { LawModel(base, parse_laws("C=poly(I,1);tau_I=-1", "test")); }).find(">= 0 s"),
            std::string::npos);
}

TEST(LawStepper, SavedStatesReplayTheSameBits) {
  const Model& m = find_model("mrd.bouc_wen");
  auto stepper = m.stepper();
  stepper->set_parameters(named(m, {{"c0", 2000.0}, {"k0", 1000.0}, {"x0", 0.0}, {"alpha", 500.0}, {"A", 600.0},
                                    {"beta", 300.0}, {"gamma", 300.0}, {"n", 1.5}}),
                          {});
  stepper->reset();
  stepper->advance(0.0, 0.0, 0.001, 0.05, 0.01, 8);
  const auto saved = stepper->states();
  ASSERT_EQ(saved.size(), 1U);
  stepper->advance(0.001, 0.05, 0.002, 0.04, 0.01, 8);
  const double first = stepper->force(0.002, 0.04, 0.0);
  stepper->set_states(saved);
  stepper->advance(0.001, 0.05, 0.002, 0.04, 0.01, 8);
  EXPECT_EQ(stepper->force(0.002, 0.04, 0.0), first);
}

TEST(LawStepper, RefusesWhatCannotBeStepped) {
  const Signals data = testing::sine_signals(0.01, 1.0, 1, 100);
  const Model& m = find_model("fvd.linear_viscous");
  const std::vector<double> p{0.0, 1.0};
  EXPECT_THROW(simulate_stepped(m, p, data, 0), InputError);
  EXPECT_EQ(find_model("sys.bouc_wen").stepper(), nullptr);
}

}  // namespace dampbench
