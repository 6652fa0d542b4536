// ga-sqp (optimizers/hybrid/ga_sqp.hpp): the GA phase is the ga optimizer; SLSQP then refines within the
// bounds under the fdsp eq. 11 constraint, with finite-difference gradients evaluated as one batch.
#include "optimizers/hybrid/ga_sqp.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "engine/common/error.hpp"
#include "engine/record/excitation.hpp"
#include "models/registry.hpp"
#include "optimizers/registry.hpp"
#include "tests/optimizer_test_support.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

using testing::FunctionProblem;

GaSqpSettings settings(int population, int generations) {
  GaSqpSettings s;
  s.population = population;
  s.generations = generations;
  return s;
}

OptimizerFactory factory(const GaSqpSettings& s) { return testing::factory_of<GaSqp>(s); }

/// GA phase then SQP on a closed-form problem; also returns the GA-phase best.
struct HybridRun {
  double ga_best = 0;
  testing::Run run;
  SqpReport report;
};
HybridRun run_hybrid(const GaSqpSettings& s, const FunctionProblem& problem, std::uint64_t seed) {
  GaSqp opt(s, problem.bounds(), hash_key({seed}));
  HybridRun h;
  h.ga_best = testing::minimize(opt, [&](std::span<const double> x) { return problem.value(x); }, problem.bounds().dim()).best_value;
  opt.refine(problem);
  h.run.best_value = opt.best_value();
  h.run.best_position.assign(opt.best_position().begin(), opt.best_position().end());
  h.report = opt.report();
  return h;
}

std::vector<double> sphere_residuals(std::span<const double> x) { return {x.begin(), x.end()}; }

/// The fdsp paper's Table 2 (2.5 Hz, 0 V) for mrd.spencer_voltage; b_c0, b_c1, b_alpha and eta (no effect at
/// 0 V) at their Table 1 values, n = 2 as in the paper.
const std::vector<double> kTable2 = {3361.58, 420.0,     1176.0,    21973.50, 1803, 34622, 6515.13,
                                     38430,   87.0,      307269.41, 182842.99, 2.0,  190,   0.01225};

}  // namespace

// ---- the population phase is the ga -----------------------------------------------------------------

TEST(GaSqp, PopulationPhaseIsTheGa) {
  const GaSqpSettings s = settings(12, 6);
  const Bounds b = testing::box(3, -5, 5);
  const auto hybrid = testing::minimize(factory(s), testing::rastrigin, b, 4, true);
  const auto ga = testing::minimize(testing::factory_of<Ga>(static_cast<const GaSettings&>(s)), testing::rastrigin, b, 4, true);
  EXPECT_EQ(hybrid.history, ga.history);
  EXPECT_EQ(hybrid.best_value, ga.best_value);
}

TEST(GaSqp, ConformsToTheOptimizerInterface) {
  const OptimizerFactory make = factory(settings(10, 8));
  testing::expect_keyed_history(make);
  testing::expect_lockstep_equals_alone(make);
  testing::expect_budget(make, 10, 8);
  testing::expect_best_position_before_first_tell(make);
  testing::expect_survives_all_failures(make);
}

// ---- the SQP phase on known optima ---------------------------------------------------------------------

TEST(GaSqp, SphereToNearMachinePrecisionWhereTheGaStops) {
  const FunctionProblem problem(sphere_residuals, testing::box(4, -5.12, 5.12));
  const HybridRun h = run_hybrid(settings(20, 10), problem, 1);
  EXPECT_GT(h.ga_best, 1e-3);  // 200 evaluations of GA in 4-D: far from the optimum
  EXPECT_LT(h.run.best_value, 1e-10);
  for (double x : h.run.best_position) EXPECT_NEAR(x, 0.0, 1e-5);
  EXPECT_TRUE(h.report.ran);
  EXPECT_TRUE(h.report.feasible);  // default constraint 4
  EXPECT_TRUE(testing::all_points_inside(problem));
}

TEST(GaSqp, RosenbrockValley) {
  const FunctionProblem problem([](std::span<const double> x) { return std::vector<double>{10 * (x[1] - x[0] * x[0]), 1 - x[0]}; },
                                testing::box(2, -2.048, 2.048));
  GaSqpSettings s = settings(20, 10);
  s.sqp_iterations = 300;
  s.fd_step = 1e-9;  // forward differences are biased by O(step × curvature); the default 1e-7 ends near 1e-8 here
  const HybridRun h = run_hybrid(s, problem, 2);
  EXPECT_GT(h.ga_best, 1e-4);
  EXPECT_LT(h.run.best_value, 1e-10);
  EXPECT_NEAR(h.run.best_position[0], 1.0, 1e-5);
  EXPECT_NEAR(h.run.best_position[1], 1.0, 2e-5);
}

TEST(GaSqp, GradientIsOneBatchOfTheFreeParametersPlusOne) {
  // Three free parameters and one fixed (lower == upper): gradient batches have 3 + 1 candidates (or 3 when
  // the point's value is already known), line-search points 1.
  struct Recorder final : LocalProblem {
    FunctionProblem inner{sphere_residuals, Bounds{{-5, -5, 2, -5}, {5, 5, 2, 5}}};
    mutable std::vector<int> sizes;
    void evaluate(const CandidateBatch& batch, std::span<double> values) const override {
      sizes.push_back(batch.count());
      inner.evaluate(batch, values);
    }
    [[nodiscard]] std::vector<double> residuals(std::span<const double> p) const override { return inner.residuals(p); }
    [[nodiscard]] const Bounds& bounds() const override { return inner.bounds(); }
  } problem;
  GaSqp opt(settings(8, 3), problem.bounds(), 5);
  testing::minimize(opt, [&](std::span<const double> x) { return problem.inner.value(x); }, 4);
  opt.refine(problem);
  ASSERT_FALSE(problem.sizes.empty());
  EXPECT_EQ(problem.sizes.front(), 4);  // the start and its 3 perturbations
  for (int n : problem.sizes) EXPECT_TRUE(n == 1 || n == 3 || n == 4) << n;
  for (const auto& x : problem.inner.points) EXPECT_EQ(x[2], 2.0);
  EXPECT_NEAR(opt.best_value(), 4.0, 1e-9);  // the fixed parameter's share
  EXPECT_EQ(opt.report().evaluations, problem.inner.evaluations);
}

TEST(GaSqp, StaysInsideTheBoxAndEndsOnTheBound) {
  // Σ (x − 3)² over [−1, 1]³: the optimum of the box is the corner (1, 1, 1), value 12.
  const FunctionProblem problem(
      [](std::span<const double> x) {
        std::vector<double> r;
        for (double v : x) r.push_back(v - 3);
        return r;
      },
      testing::box(3, -1, 1));
  GaSqpSettings s = settings(10, 4);
  s.constraint = std::numeric_limits<double>::infinity();
  const HybridRun h = run_hybrid(s, problem, 3);
  EXPECT_TRUE(testing::all_points_inside(problem));
  for (double x : h.run.best_position) EXPECT_NEAR(x, 1.0, 1e-9);
  EXPECT_NEAR(h.run.best_value, 12.0, 1e-8);
}

TEST(GaSqp, NeverReturnsAFailureOrSomethingWorseThanTheGa) {
  // +inf for x0 < 0 (a blow-up region, as the kernels mask it), Σ (x − c)² with c0 = −1 elsewhere: the best
  // finite points hug the failure wall. SLSQP cannot see the wall (its trial points there get a large finite
  // penalty and a zero gradient), so it only backs off from it; what must hold is that no failure and nothing
  // worse than the GA best comes back.
  const FunctionProblem problem(
      [](std::span<const double> x) {
        if (x[0] < 0) return std::vector<double>{std::numeric_limits<double>::infinity()};
        return std::vector<double>{x[0] + 1, x[1] - 0.5, x[2] - 0.5};
      },
      testing::box(3, -2, 2));
  const HybridRun h = run_hybrid(settings(12, 5), problem, 4);
  ASSERT_TRUE(std::isfinite(h.ga_best));
  EXPECT_TRUE(std::isfinite(h.run.best_value));
  EXPECT_LE(h.run.best_value, h.ga_best);
  EXPECT_GE(h.run.best_position[0], 0.0);
  EXPECT_TRUE(h.report.ran);
  EXPECT_GT(h.report.evaluations, 0);
}

TEST(GaSqp, NothingToRefineWhenEveryCandidateFailed) {
  const FunctionProblem problem([](std::span<const double>) { return std::vector<double>{std::nan("")}; },
                                testing::box(2, -1, 1));
  const HybridRun h = run_hybrid(settings(6, 2), problem, 5);
  EXPECT_EQ(h.run.best_value, std::numeric_limits<double>::infinity());
  EXPECT_FALSE(h.report.ran);
  EXPECT_FALSE(h.report.feasible);
  ASSERT_EQ(h.run.best_position.size(), 2u);
  EXPECT_EQ(problem.evaluations, 0);  // refine evaluated nothing
}

// ---- the constraint (fdsp eq. 11) -------------------------------------------------------------------

/// 1 + Σ x² over [−5, 5]⁴: the lowest value is 1.
const FunctionProblem& offset_sphere() {
  static const FunctionProblem p(
      [](std::span<const double> x) {
        std::vector<double> r{1.0};
        r.insert(r.end(), x.begin(), x.end());
        return r;
      },
      testing::box(4, -5, 5));
  return p;
}

TEST(GaSqp, ConstraintIsHonouredFromAnInfeasibleStart) {
  GaSqpSettings s = settings(4, 1);  // one random generation: the start is far from feasible
  s.constraint = 2;
  const HybridRun h = run_hybrid(s, offset_sphere(), 6);
  ASSERT_GT(h.ga_best, 2.0) << "the GA start should violate the constraint";
  EXPECT_TRUE(h.report.feasible);
  EXPECT_LE(h.run.best_value, 2.0);
  EXPECT_LT(h.run.best_value, 1.0 + 1e-9);
}

TEST(GaSqp, UnreachableConstraintIsReportedInfeasible) {
  GaSqpSettings s = settings(8, 3);
  s.constraint = 0.5;  // below the lowest value 1
  const HybridRun h = run_hybrid(s, offset_sphere(), 7);
  EXPECT_FALSE(h.report.feasible);
  EXPECT_TRUE(h.report.ran);
  EXPECT_FALSE(h.report.status.empty());
  EXPECT_TRUE(std::isfinite(h.run.best_value));
  EXPECT_LT(h.run.best_value, 1.0 + 1e-6);  // the least infeasible point is still found
  EXPECT_GT(h.run.best_value, s.constraint);
}

// ---- the fdsp pairing: mrd.spencer_voltage, Table 2 as truth --------------------------------------------

struct FdspProblem {
  const Model& model = find_model("mrd.spencer_voltage");
  Signals data;
  Bounds bounds;
  FdspProblem() {
    Dataset d = make_sine({0.00635, 2.5, 0, 1.5, 500});  // 6.35 mm at 2.5 Hz (fdsp §3), 1.5 cycles
    d.operating["V"] = 0;
    d.F_N = model.simulate(kTable2, prepare_signals(d));
    data = prepare_signals(d);
    bounds = default_bounds(model);  // fdsp Table 1 ±50 %: five Table 2 values sit on this box's faces
    for (const char* fixed : {"b_c0", "b_c1", "b_alpha", "n", "eta"}) {
      const int j = model.parameter_index(fixed);
      bounds.lower[j] = bounds.upper[j] = kTable2[j];
    }
  }
};

TEST(GaSqp, RecoversFdspTable2OnNoiseFreeData) {
  const FdspProblem p;
  IdentificationSettings s;
  s.runs = 2;
  s.seed = 11;
  s.metric = Metric::nrmse;
  const Identification id = identify(p.model, p.data, p.bounds,
                                     make_optimizer_factory({"ga-sqp", 40, 30, {{"constraint", "0.04"}, {"sqp_iterations", "200"}}}), s);
  const RunResult& best = id.runs[id.best_run()];
  EXPECT_LT(best.best_value, 1e-5);  // the GA phase alone ends near 1e-2
  EXPECT_LT(best.trace.back(), 0.04 * 2);
  for (int j = 0; j < p.model.dim(); ++j)
    EXPECT_NEAR(best.best_params[j], kTable2[j], 0.01 * std::abs(kTable2[j])) << p.model.parameters()[j].name;
  for (const RunResult& r : id.runs) {
    EXPECT_LE(r.best_value, 0.04);  // feasible: RunResult::best_value ≤ constraint
    EXPECT_LE(r.best_value, r.trace.back());
    EXPECT_GT(r.evaluations, 40 * 30);  // the SQP phase's evaluations are counted
  }
}

TEST(GaSqp, SameBitsForAnyThreadCountBatchSplitAndOneByOne) {
  const FdspProblem p;
  const OptimizerFactory make = make_optimizer_factory({"ga-sqp", 16, 4, {{"sqp_iterations", "15"}}});
  IdentificationSettings s;
  s.runs = 3;
  s.seed = 5;
  s.metric = Metric::nrmse;
  const std::vector<const Signals*> data{&p.data};
  const auto one = testing::identify_with(p.model, data, p.bounds, make, s, 1, 1);
  testing::expect_identical(one, testing::identify_with(p.model, data, p.bounds, make, s, 2, 1));
  testing::expect_identical(one, testing::identify_with(p.model, data, p.bounds, make, s, 2, 3));
  EXPECT_GT(one.runs[0].evaluations, 16 * 4);
  s.seed = 6;
  EXPECT_NE(one.runs[0].best_params, testing::identify_with(p.model, data, p.bounds, make, s, 2, 1).runs[0].best_params);

  const BatchEvaluator evaluator(p.model, p.data);
  EXPECT_EQ(testing::run_on_model(make, evaluator, Metric::nrmse, p.bounds, 9, false),
            testing::run_on_model(make, evaluator, Metric::nrmse, p.bounds, 9, true));
}

// ---- settings ---------------------------------------------------------------------------------------

TEST(GaSqp, RejectsBadSettings) {
  auto error = [](std::map<std::string, std::string> settings, int population = 20) {
    return testing::error_of([&] { make_optimizer_factory({"ga-sqp", population, 10, std::move(settings)}); });
  };
  EXPECT_EQ(error({}, 3), "ga-sqp: population must be at least 4, got 3");
  EXPECT_EQ(error({{"pc", "1.5"}}), "ga-sqp: pc must be in [0, 1], got 1.5");
  EXPECT_EQ(error({{"pm", "-0.1"}}), "ga-sqp: pm must be in [0, 1], got -0.1");
  EXPECT_EQ(error({{"constraint", "-1"}}), "ga-sqp: constraint must be a number > 0 or off, got -1");
  EXPECT_EQ(error({{"constraint", "four"}}), "ga-sqp: setting 'constraint': expected a number, got 'four'");
  EXPECT_EQ(error({{"sqp_iterations", "0"}}), "ga-sqp: sqp_iterations must be at least 1, got 0");
  EXPECT_EQ(error({{"sqp_iterations", "2.5"}}), "ga-sqp: setting 'sqp_iterations': expected a whole number, got '2.5'");
  EXPECT_EQ(error({{"fd_step", "0"}}), "ga-sqp: fd_step must be in (0, 0.1], got 0");
  EXPECT_EQ(error({{"xtol", "-1"}}), "ga-sqp: xtol must be a finite number >= 0, got -1");
  EXPECT_EQ(error({{"preset", "lssvm"}}).substr(0, 38), "ga-sqp: unknown setting 'preset' (know");
  EXPECT_EQ(error({{"constraint", "off"}}), "no error");
  GaSqpSettings s = settings(20, 10);
  s.constraint = 0;
  EXPECT_EQ(testing::error_of([&] { GaSqp(s, testing::box(2, -1, 1), 1); }),
            "ga-sqp: constraint must be a number > 0 or off, got 0");
}

TEST(GaSqp, ConstraintOffLeavesBoundsOnly) {
  const auto make = make_optimizer_factory({"ga-sqp", 8, 3, {{"constraint", "off"}}});
  const auto opt = make(testing::box(4, -5, 5), 3);
  const testing::Run run = testing::minimize_and_refine(*opt, offset_sphere());
  EXPECT_LT(run.best_value, 1 + 1e-9);
  EXPECT_TRUE(dynamic_cast<GaSqp&>(*opt).report().feasible);  // any value is feasible without a constraint
}

}  // namespace dampbench
