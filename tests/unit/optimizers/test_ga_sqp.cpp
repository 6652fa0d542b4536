// ga-sqp (optimizers/hybrid/ga_sqp.hpp): the GA phase is the ga optimizer; SLSQP then refines within the
// bounds under the fdsp eq. 11 constraint, with finite-difference gradients evaluated as one batch. The
// checks every optimizer passes (standard functions, ask/tell conformance, 1 and 2 threads, any batch
// split) are in test_optimizer_conformance.cpp.
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
using testing::sphere_residuals;

GaSqpSettings ga_sqp_settings(int population, int generations) {
  return testing::generational<GaSqpSettings>(population, generations);
}

testing::HybridRun<GaSqp> run_hybrid(const GaSqpSettings& s, const FunctionProblem& problem, std::uint64_t seed) {
  return testing::run_hybrid<GaSqp>(s, problem, seed);
}

/// The fdsp paper's Table 2 (2.5 Hz, 0 V) for mrd.spencer_voltage; b_c0, b_c1, b_alpha and eta (no effect at
/// 0 V) at their Table 1 values, n = 2 as in the paper.
const std::vector<double> kTable2 = {3361.58, 420.0,     1176.0,    21973.50, 1803, 34622, 6515.13,
                                     38430,   87.0,      307269.41, 182842.99, 2.0,  190,   0.01225};

}  // namespace

// ---- the population phase is the ga -----------------------------------------------------------------

TEST(GaSqp, PopulationPhaseIsTheGa) {
  const GaSqpSettings s = ga_sqp_settings(12, 6);
  testing::expect_same_run(testing::factory_of<GaSqp>(s), testing::factory_of<Ga>(static_cast<const GaSettings&>(s)));
}

// ---- the SQP phase on known optima ---------------------------------------------------------------------

TEST(GaSqp, SphereToNearMachinePrecisionWhereTheGaStops) {
  const FunctionProblem problem(sphere_residuals, testing::box(4, -5.12, 5.12));
  const auto h = run_hybrid(ga_sqp_settings(20, 10), problem, 1);
  EXPECT_GT(h.ga_best, 1e-3);  // 200 evaluations of GA in 4-D: far from the optimum
  EXPECT_LT(h.run.best_value, 1e-10);
  for (double x : h.run.best_position) EXPECT_NEAR(x, 0.0, 1e-5);
  EXPECT_TRUE(h.report.ran);
  EXPECT_TRUE(h.report.feasible);  // default constraint 4
  EXPECT_TRUE(testing::all_points_inside(problem));
  EXPECT_TRUE(h.at_local_optimum) << h.report.status;  // SLSQP's own tolerance stopped it
}

TEST(GaSqp, RosenbrockValley) {
  const FunctionProblem problem(testing::rosenbrock_residuals, testing::box(2, -2.048, 2.048));
  GaSqpSettings s = ga_sqp_settings(20, 10);
  s.sqp_iterations = 300;
  s.fd_step = 1e-9;  // forward differences are biased by O(step × curvature); the default 1e-7 ends near 1e-8 here
  const auto h = run_hybrid(s, problem, 2);
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
  GaSqp opt(ga_sqp_settings(8, 3), problem.bounds(), 5);
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
  GaSqpSettings s = ga_sqp_settings(10, 4);
  s.constraint = std::numeric_limits<double>::infinity();
  const auto h = run_hybrid(s, problem, 3);
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
  const auto h = run_hybrid(ga_sqp_settings(12, 5), problem, 4);
  testing::expect_refine_avoids_failures(h);
  EXPECT_TRUE(h.report.ran);
  EXPECT_GT(h.report.evaluations, 0);
}

// The rest of such a run (best +inf, no point evaluated) is Conformance.SurvivesAllCandidatesFailing.
TEST(GaSqp, NothingToRefineWhenEveryCandidateFailed) {
  const FunctionProblem problem([](std::span<const double>) { return std::vector<double>{std::nan("")}; },
                                testing::box(2, -1, 1));
  const auto h = run_hybrid(ga_sqp_settings(6, 2), problem, 5);
  EXPECT_FALSE(h.report.ran);
  EXPECT_FALSE(h.report.feasible);
  EXPECT_FALSE(h.at_local_optimum);
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
  GaSqpSettings s = ga_sqp_settings(4, 1);  // one random generation: the start is far from feasible
  s.constraint = 2;
  const auto h = run_hybrid(s, offset_sphere(), 6);
  ASSERT_GT(h.ga_best, 2.0) << "the GA start should violate the constraint";
  EXPECT_TRUE(h.report.feasible);
  EXPECT_LE(h.run.best_value, 2.0);
  EXPECT_LT(h.run.best_value, 1.0 + 1e-9);
}

TEST(GaSqp, UnreachableConstraintIsReportedInfeasible) {
  GaSqpSettings s = ga_sqp_settings(8, 3);
  s.constraint = 0.5;  // below the lowest value 1
  const auto h = run_hybrid(s, offset_sphere(), 7);
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
  const IdentificationSettings s = testing::nrmse_runs(2, 11);
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

// ---- settings ---------------------------------------------------------------------------------------

// A zero constraint through the class (the registry's messages are checked in
// test_optimizer_conformance.cpp).
TEST(GaSqp, ConstructorRejectsAZeroConstraint) {
  GaSqpSettings s = ga_sqp_settings(20, 10);
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
