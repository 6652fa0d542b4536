// The two examples of docs/extending.md compile, compute what they claim and plug into the engine:
// the tanh Bingham model (docs/extending/tanh_bingham.hpp) against its formula and recovered from its own
// noise-free force by DE; the random-search optimizer (docs/extending/random_search.hpp) through the
// conformance checks every optimizer passes and on the sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "docs/extending/random_search.hpp"
#include "docs/extending/tanh_bingham.hpp"
#include "engine/identification/identification.hpp"
#include "engine/record/excitation.hpp"
#include "optimizer_test_support.hpp"
#include "optimizers/registry.hpp"

namespace dampbench::example {
namespace {

Dataset sine(double amp_m, double freq_hz) {
  SineSpec spec;
  spec.amplitude_m = amp_m;
  spec.freq_hz = freq_hz;
  spec.cycles = 3;
  spec.fs_hz = 500;
  return make_sine(spec);
}

TEST(ExtendingExamples, ModelForceIsItsFormula) {
  const AlgebraicModel<TanhBingham> model;
  EXPECT_EQ(model.id(), "example.tanh_bingham");
  const Signals s = prepare_signals(sine(0.01, 1.0));
  const std::vector<double> p{800.0, 0.01, 2000.0};
  const std::vector<double> F = model.simulate(p, s);
  ASSERT_EQ(F.size(), s.size());
  for (std::size_t k = 0; k < F.size(); ++k)
    EXPECT_NEAR(F[k], 800.0 * std::tanh(s.v_m_s[k] / 0.01) + 2000.0 * s.v_m_s[k], 1e-9 * 1000) << "sample " << k;
}

TEST(ExtendingExamples, ModelIsRecoveredFromItsOwnForce) {
  const AlgebraicModel<TanhBingham> model;
  Dataset d = sine(0.01, 1.0);
  const std::vector<double> truth{800.0, 0.01, 2000.0};
  d.F_N = model.simulate(truth, prepare_signals(d));
  const Signals s = prepare_signals(d);
  IdentificationSettings settings;
  settings.runs = 2;
  settings.metric = Metric::nrmse;
  const Identification id = identify(model, s, default_bounds(model), make_optimizer_factory({"de", 30, 200}), settings);
  const RunResult& best = id.runs[id.best_run()];
  EXPECT_LT(best.best_value, 1e-4);
  EXPECT_NEAR(best.best_params[0], truth[0], 0.01 * truth[0]);
  EXPECT_NEAR(best.best_params[2], truth[2], 0.01 * truth[2]);
}

OptimizerFactory random_search(int population, int iterations) {
  return [=](const Bounds& bounds, std::uint64_t key) {
    return std::make_unique<RandomSearch>(population, iterations, bounds, key);
  };
}

TEST(ExtendingExamples, OptimizerPassesTheGenericChecks) {
  const OptimizerFactory make = random_search(20, 30);
  testing::expect_keyed_history(make);
  testing::expect_lockstep_equals_alone(make);
  testing::expect_budget(make, 20, 30);
  testing::expect_survives_all_failures(make);
  testing::expect_best_position_before_first_tell(make);
}

TEST(ExtendingExamples, OptimizerFindsTheSphereMinimum) {
  // 5 000 uniform draws in [−5.12, 5.12]²: P(no draw within r = 0.3 of the optimum) = exp(−5000·π·0.09/104.9) ≈ 1e-6.
  const testing::Run run = testing::minimize(random_search(50, 100), testing::sphere, testing::box(2, -5.12, 5.12), 1);
  EXPECT_LT(run.best_value, 0.09);
  EXPECT_EQ(run.evaluations, 5000);
}

}  // namespace
}  // namespace dampbench::example
