// ga-lm (optimizers/hybrid/ga_lm.hpp): the GA phase is the ga optimizer; bounded Levenberg–Marquardt then
// fits LocalProblem::residuals with finite-difference Jacobians. The checks every optimizer passes (standard
// functions, ask/tell conformance, 1 and 2 threads, any batch split) are in test_optimizer_conformance.cpp.
#include "optimizers/hybrid/ga_lm.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "engine/common/error.hpp"
#include "engine/record/excitation.hpp"
#include "engine/model/law_model.hpp"
#include "models/fixtures.hpp"
#include "models/registry.hpp"
#include "optimizers/registry.hpp"
#include "tests/optimizer_test_support.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

using testing::FunctionProblem;

GaLmSettings ga_lm_settings(int population, int generations) { return testing::generational<GaLmSettings>(population, generations); }

testing::HybridRun<GaLm> run_hybrid(const GaLmSettings& s, const FunctionProblem& problem, std::uint64_t seed) {
  return testing::run_hybrid<GaLm>(s, problem, seed);
}

}  // namespace

// ---- the population phase is the ga -----------------------------------------------------------------

TEST(GaLm, PopulationPhaseIsTheGa) {
  const GaLmSettings s = ga_lm_settings(12, 6);
  testing::expect_same_run(testing::factory_of<GaLm>(s), testing::factory_of<Ga>(static_cast<const GaSettings&>(s)));
}

// With global = cmaes the population phase is the cmaes run of the hybrid's population, iterations and cmaes
// settings, bit for bit, and LM then refines its best; the ga's settings are then unknown keys.
TEST(GaLm, CmaesAsTheGlobalStage) {
  GaLmSettings s = ga_lm_settings(8, 6);
  s.global = GlobalStage::cmaes;
  s.cmaes.restarts = CmaesRestarts::bipop;
  s.cmaes.sigma0 = 0.2;
  CmaesSettings c = s.cmaes;
  c.population = 8;
  c.generations = 6;
  testing::expect_same_run(testing::factory_of<GaLm>(s), testing::factory_of<Cmaes>(c));
  const OptimizerFactory by_name =
      make_optimizer_factory({"ga-lm", 8, 6, {{"global", "cmaes"}, {"restarts", "bipop"}, {"sigma0", "0.2"}}});
  testing::expect_same_run(by_name, testing::factory_of<Cmaes>(c));

  const FunctionProblem problem(testing::rosenbrock_residuals, testing::box(4, -2.048, 2.048));
  const auto h = run_hybrid(s, problem, 1);
  EXPECT_GT(h.ga_best, 1e-3);  // 48 CMA-ES evaluations stop well short
  // LM ends at one of the two minima of the 4-D Rosenbrock function: the global 0 at (1, 1, 1, 1), or the local
  // one near (−0.776, 0.613, 0.382, 0.146) of value 3.7014 (Shang & Qiu 2006), whichever basin CMA-ES's best is in.
  EXPECT_LT(h.run.best_value, h.ga_best);
  EXPECT_TRUE(h.run.best_value < 1e-10 || std::fabs(h.run.best_value - 3.70143) < 1e-4) << h.run.best_value;
  EXPECT_TRUE(h.report.ran);

  EXPECT_EQ(testing::error_of([] { (void)make_optimizer_factory({"ga-lm", 8, 6, {{"global", "cmaes"}, {"pc", "0.5"}}}); }),
            "ga-lm: unknown setting 'pc' (known: global, restarts, sigma0, tolfun, tolx, lm_iterations, fd_step, "
            "ftol, xtol, gtol, lambda0, geodesic, geodesic_ratio)");
  EXPECT_EQ(testing::error_of([] { (void)make_optimizer_factory({"ga-lm", 8, 6, {{"global", "cmaes"}, {"sigma0", "2"}}}); }),
            "cmaes: sigma0 must be in (0, 1], got 2");
  EXPECT_EQ(testing::error_of([] { (void)make_optimizer_factory({"ga-lm", 8, 6, {{"global", "pso"}}}); }),
            "ga-lm: unknown global 'pso' (known: ga, cmaes)");
}

// ---- least-squares optima --------------------------------------------------------------------------

TEST(GaLm, RosenbrockToTheLeastSquaresOptimumWhereTheGaStops) {
  for (int geodesic : {1, 0})
  for (int dim : {2, 4}) {
    SCOPED_TRACE(::testing::Message() << "geodesic " << geodesic);
    const FunctionProblem problem(testing::rosenbrock_residuals, testing::box(dim, -2.048, 2.048));
    GaLmSettings s = ga_lm_settings(20, 15);
    s.geodesic = geodesic;
    const auto h = run_hybrid(s, problem, 1);
    EXPECT_GT(h.ga_best, 1e-3) << dim;  // 300 GA evaluations stop well short
    EXPECT_LT(h.run.best_value, 1e-10) << dim;
    for (double x : h.run.best_position) EXPECT_NEAR(x, 1.0, 1e-5) << dim;
    EXPECT_TRUE(h.report.ran);
    EXPECT_EQ(h.report.residual_evaluations, problem.residual_calls);
    EXPECT_LE(h.report.iterations, 100);
    EXPECT_TRUE(testing::all_points_inside(problem)) << dim;
    EXPECT_TRUE(h.at_local_optimum) << h.report.status;  // stopped on its own test, not the cap
  }
}

TEST(GaLm, JacobianCostsOneResidualVectorPerFreeParameter) {
  // Two free parameters and one fixed: each iteration costs 2 residual vectors plus its trial steps.
  const FunctionProblem problem(
      [](std::span<const double> x) { return std::vector<double>{x[0] - 0.3, 2 * (x[1] + 0.2), x[2]}; },
      Bounds{{-1, -1, 0.5}, {1, 1, 0.5}});
  GaLmSettings s = ga_lm_settings(6, 2);
  s.lm_iterations = 1;
  const auto h = run_hybrid(s, problem, 2);
  EXPECT_EQ(h.report.iterations, 1);
  EXPECT_EQ(h.report.status, "iterations");
  EXPECT_FALSE(h.at_local_optimum);  // stopped by the cap
  // start, Jacobian (2), the geodesic-acceleration probe and the accepted trial
  EXPECT_EQ(h.report.residual_evaluations, 1 + 2 + 1 + 1);
  EXPECT_EQ(problem.residual_calls, 5);
  for (const auto& x : problem.points) EXPECT_EQ(x[2], 0.5);
  // A linear problem: one step damped by λ₀ = 1e-3 lands within 1e-3 of the distance it started from.
  const double start = std::hypot(problem.points[0][0] - 0.3, problem.points[0][1] + 0.2);
  EXPECT_LT(std::hypot(h.run.best_position[0] - 0.3, h.run.best_position[1] + 0.2), 1.1e-3 * start);
  s.lm_iterations = 100;
  const auto full = run_hybrid(s, problem, 2);
  EXPECT_NEAR(full.run.best_position[0], 0.3, 1e-9);  // ftol stops it: the fixed residual 0.5 dominates ‖r‖²
  EXPECT_NEAR(full.run.best_position[1], -0.2, 1e-9);
  EXPECT_NEAR(full.run.best_value, 0.25, 1e-15);
}

// A problem whose batches have idle lanes (a model's lane block) gets each Jacobian beside the trial that leads to it:
// the same run bit for bit and the same evaluation count, in fewer sequential rounds (one less per Jacobian taken
// from a trial's batch). A trial's points beside it count only when used.
TEST(GaLm, JacobianBesideTheTrialGivesTheSameRunInFewerRounds) {
  for (int geodesic : {1, 0}) {
    SCOPED_TRACE(::testing::Message() << "geodesic " << geodesic);
    FunctionProblem plain(testing::rosenbrock_residuals, testing::box(4, -2.048, 2.048));
    FunctionProblem ahead(testing::rosenbrock_residuals, testing::box(4, -2.048, 2.048));
    ahead.lanes_ahead = 16;
    GaLmSettings s = ga_lm_settings(20, 15);
    s.geodesic = geodesic;
    const auto a = run_hybrid(s, plain, 3);
    const auto b = run_hybrid(s, ahead, 3);
    ASSERT_TRUE(a.report.ran);
    EXPECT_GT(a.report.iterations, 5);
    ASSERT_EQ(a.run.best_position.size(), b.run.best_position.size());
    for (std::size_t j = 0; j < a.run.best_position.size(); ++j)
      EXPECT_EQ(testing::bits(a.run.best_position[j]), testing::bits(b.run.best_position[j])) << j;
    EXPECT_EQ(testing::bits(a.run.best_value), testing::bits(b.run.best_value));
    EXPECT_EQ(a.report.iterations, b.report.iterations);
    EXPECT_EQ(a.report.status, b.report.status);
    EXPECT_EQ(a.report.residual_evaluations, b.report.residual_evaluations);
    EXPECT_EQ(b.report.residual_evaluations, ahead.residual_calls + ahead.counted_ahead);  // counted when used
    // every Jacobian after the first comes from the batch of the trial accepted before it
    EXPECT_EQ(plain.rounds - ahead.rounds, b.report.iterations - 1);
    EXPECT_TRUE(testing::all_points_inside(ahead));
  }
}

TEST(GaLm, AtItsCapAnLmThatStillGainsIsNotAtItsOptimumAndOneThatCreepsIs) {
  // Cubic residuals (x − 0.3)³, (y − 0.3)³: Gauss–Newton closes a third of the distance per step, so ‖r‖ falls by
  // ~70 % per Jacobian and 3 Jacobians stop on the cap while still gaining. Add a fixed residual 1 and the same
  // steps change ‖r‖ by < 1e-7: the LM only creeps, and at the cap it counts as at its optimum (ftol is off so
  // that the cap, not the relative-decrease test, stops both).
  for (const double fixed : {0.0, 1.0}) {
    SCOPED_TRACE(::testing::Message() << "fixed residual " << fixed);
    const FunctionProblem problem(
        [fixed](std::span<const double> x) {
          return std::vector<double>{std::pow(x[0] - 0.3, 3), std::pow(x[1] - 0.3, 3), fixed};
        },
        testing::box(2, 0.25, 0.36));
    GaLmSettings s = ga_lm_settings(6, 2);
    s.lm_iterations = 3;
    s.ftol = 0;
    const auto h = run_hybrid(s, problem, 5);
    ASSERT_EQ(h.report.status, "iterations");
    if (fixed == 0) {
      EXPECT_GT(h.report.late_decrease, 0.3);
      EXPECT_FALSE(h.at_local_optimum);
    } else {
      EXPECT_GE(h.report.late_decrease, 0.0);
      EXPECT_LT(h.report.late_decrease, 1e-7);
      EXPECT_TRUE(h.at_local_optimum);
    }
  }
}

TEST(GaLm, OptimumOutsideTheBoxEndsOnTheBound) {
  // r = x − (3, 0.25, −4) over [−1, 1]³: the box's optimum is (1, 0.25, −1), value 4 + 9 = 13.
  const FunctionProblem problem(
      [](std::span<const double> x) { return std::vector<double>{x[0] - 3, x[1] - 0.25, x[2] + 4}; },
      testing::box(3, -1, 1));
  const auto h = run_hybrid(ga_lm_settings(8, 3), problem, 3);
  EXPECT_TRUE(testing::all_points_inside(problem));
  EXPECT_EQ(h.run.best_position[0], 1.0);
  EXPECT_NEAR(h.run.best_position[1], 0.25, 1e-8);
  EXPECT_EQ(h.run.best_position[2], -1.0);
  EXPECT_NEAR(h.run.best_value, 13.0, 1e-12);
}

TEST(GaLm, BacksOffFromAFailureRegion) {
  // Non-finite residuals for x0 < 0 (a blow-up region); elsewhere r = (x0 + 1, x1 − 0.5): the best finite
  // point is on the wall x0 = 0, value 1.
  const FunctionProblem problem(
      [](std::span<const double> x) {
        if (x[0] < 0) return std::vector<double>{std::nan(""), 0.0};
        return std::vector<double>{x[0] + 1, x[1] - 0.5};
      },
      testing::box(2, -2, 2));
  const auto h = run_hybrid(ga_lm_settings(12, 5), problem, 4);
  testing::expect_refine_avoids_failures(h);
  EXPECT_LT(h.run.best_value, h.ga_best);
  // Rejected steps shrink towards the wall: x0 ends on it. x1 is not driven to 0.5 as well: after the
  // rejections λ is large, the step scales both coordinates alike and the run stops on xtol (known limit
  // of LM against an implicit wall: over seeds 1–6 the end value is 1.001–1.19 with either GA's defaults;
  // this test asserted < 1.01 at one seed until the GA defaults changed).
  EXPECT_GE(h.run.best_position[0], 0.0);
  EXPECT_LT(h.run.best_position[0], 1e-9);
}

// The rest of such a run (best +inf, no point evaluated) is Conformance.SurvivesAllCandidatesFailing.
TEST(GaLm, NothingToRefineWhenEveryCandidateFailed) {
  const FunctionProblem problem([](std::span<const double>) { return std::vector<double>{std::nan("")}; },
                                testing::box(2, -1, 1));
  const auto h = run_hybrid(ga_lm_settings(6, 2), problem, 5);
  EXPECT_FALSE(h.report.ran);
  EXPECT_FALSE(h.at_local_optimum);
}

TEST(GaLm, KeepsTheGaBestWhenTheLeastSquaresOptimumIsWorseInTheRunMetric) {
  // The run metric is |r0| + |r1| (what evaluate returns) while LM minimizes r0² + r1²: with r = (x − 1, x + 1)
  // every x in [−1, 1] has metric 2 but LM moves to x = 0 — never below the GA best's metric.
  struct L1Problem final : LocalProblem {
    Bounds b = testing::box(1, -3, 3);
    void evaluate(const CandidateBatch& batch, std::span<double> values) const override {
      for (int i = 0; i < batch.count(); ++i) {
        const double x = batch.at(i, 0);
        values[i] = std::abs(x - 1) + std::abs(x + 1) + (std::abs(x) < 0.5 ? 1.0 : 0.0);
      }
    }
    [[nodiscard]] std::vector<double> residuals(std::span<const double> p) const override { return {p[0] - 1, p[0] + 1}; }
    [[nodiscard]] const Bounds& bounds() const override { return b; }
  } problem;
  GaLm opt(ga_lm_settings(8, 4), problem.bounds(), 6);
  CandidateBatch batch;
  std::vector<double> values;
  while (!opt.finished()) {
    batch.resize(1, opt.batch_size());
    values.resize(opt.batch_size());
    opt.ask(batch, 0);
    problem.evaluate(batch, values);
    opt.tell(values);
  }
  const double ga_best = opt.best_value();
  const std::vector<double> ga_position(opt.best_position().begin(), opt.best_position().end());
  opt.refine(problem);
  EXPECT_NEAR(opt.report().end_metric, 3.0, 1e-6);  // LM went to x ≈ 0, where the metric is 3
  EXPECT_EQ(opt.best_value(), ga_best);
  EXPECT_EQ(std::vector<double>(opt.best_position().begin(), opt.best_position().end()), ga_position);
}

// ---- the mfm pairing: mrd.magic_formula on noise-free data --------------------------------------------

struct MfmProblem {
  const Model& model = find_model("mrd.magic_formula");
  std::vector<double> truth;
  Signals data;
  MfmProblem() {
    // Truth: mfm eqs. 4–11 at I = 1 A, Amp = 0.01 m, f = 1 Hz (the paper's base condition).
    Dataset d = make_sine({0.01, 1.0, 0, 1.5, 200});
    d.operating = {{"I", 1.0}, {"amp", 0.01}, {"freq", 1.0}};
    const FixtureModel fixture = make_fixture_model(find_fixture("mfm.eqs4_11"));
    truth = fixture.model->base_parameters(fixture.coefficients, prepare_signals(d));
    d.F_N = model.simulate(truth, prepare_signals(d));
    data = prepare_signals(d);
  }
};

TEST(GaLm, RecoversMagicFormulaParametersOnNoiseFreeData) {
  const MfmProblem p;
  const IdentificationSettings s = testing::nrmse_runs(4, 3);
  const Identification ga = identify(p.model, p.data, default_bounds(p.model), make_optimizer_factory({"ga", 40, 40}), s);
  const Identification id =
      identify(p.model, p.data, default_bounds(p.model), make_optimizer_factory({"ga-lm", 40, 40}), s);
  const RunResult& best = id.runs[id.best_run()];
  EXPECT_GT(ga.runs[ga.best_run()].best_value, 1e-4);  // the GA alone
  EXPECT_LT(best.best_value, 1e-10);
  for (int j = 0; j < p.model.dim(); ++j)
    EXPECT_NEAR(best.best_params[j], p.truth[j], 1e-6 * (std::abs(p.truth[j]) + 1)) << p.model.parameters()[j].name;
  for (std::size_t r = 0; r < id.runs.size(); ++r) {
    EXPECT_EQ(id.runs[r].trace, ga.runs[r].trace);  // same GA phase, run for run
    EXPECT_LE(id.runs[r].best_value, ga.runs[r].best_value);
    EXPECT_GT(id.runs[r].evaluations, ga.runs[r].evaluations);  // the LM residual vectors are counted
  }
}

// ---- settings ---------------------------------------------------------------------------------------

// The class validates its settings too (the registry's messages are checked in
// test_optimizer_conformance.cpp).
TEST(GaLm, ConstructorRejectsBadSettings) {
  GaLmSettings s = ga_lm_settings(20, 10);
  s.tournament = 30;
  EXPECT_EQ(testing::error_of([&] { GaLm(s, testing::box(2, -1, 1), 1); }),
            "ga-lm: tournament must be in [2, population = 20], got 30");
}

}  // namespace dampbench
