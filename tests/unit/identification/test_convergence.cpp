// Convergence evidence (engine/identification/convergence.cpp): the rule on hand-made histories with known
// verdicts, then real identifications where a starved budget must be flagged and a generous one not.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "engine/identification/convergence.hpp"
#include "engine/model/bounds.hpp"
#include "models/registry.hpp"
#include "optimizers/registry.hpp"
#include "test_support.hpp"

namespace dampbench {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// A run whose best-so-far falls to `best` at `improved_at` evaluations and ends at 1000 evaluations.
RunHistory run(double best, long long improved_at = 100) {
  return {best, {{10, 10 * best + 1}, {improved_at, best}, {1000, best}}};
}

TEST(Convergence, AgreeingStalledRunsConverge) {
  const std::vector<RunHistory> runs{run(1.00), run(1.01), run(1.015), run(1.5)};  // median 1.015: 1.5 % above
  const Convergence c = assess_convergence(runs);
  EXPECT_TRUE(c.runs_agree);
  EXPECT_TRUE(c.stalled);
  EXPECT_TRUE(c.converged);
  EXPECT_EQ(c.verdict(), "converged");
  EXPECT_NEAR(c.median_above_best_rel, 0.015, 1e-12);
  EXPECT_NEAR(c.worst_above_best_rel, 0.5, 1e-12);
  EXPECT_EQ(c.late_gain_rel, 0.0);
}

TEST(Convergence, RunsThatDisagreeAreFlagged) {
  // The Spencer example: best 0.047, worst 0.219 over 4 runs; the upper median 0.15 is 219 % above.
  const std::vector<RunHistory> runs{run(0.047), run(0.12), run(0.15), run(0.219)};
  const Convergence c = assess_convergence(runs);
  EXPECT_FALSE(c.runs_agree);
  EXPECT_TRUE(c.stalled);
  EXPECT_FALSE(c.converged);
  EXPECT_EQ(c.verdict(), "runs disagree");
  EXPECT_NEAR(c.median_above_best_rel, 0.15 / 0.047 - 1, 1e-12);
}

TEST(Convergence, ABestStillImprovingLateIsFlagged) {
  // Best run: 2.0 until 900 of 1000 evaluations, then 1.0: at 800 evaluations it stood at 2.0, a 100 % gain.
  const std::vector<RunHistory> runs{{1.0, {{10, 5.0}, {900, 1.0}, {1000, 1.0}}}, run(1.0), run(1.0)};
  const Convergence c = assess_convergence(runs);
  EXPECT_TRUE(c.runs_agree);
  EXPECT_FALSE(c.stalled);
  EXPECT_EQ(c.verdict(), "still improving");
  // The best run is the first of the equal ones.
  EXPECT_NEAR(c.late_gain_rel, 4.0, 1e-12);
  // An improvement just before the last fifth does not count.
  const std::vector<RunHistory> early{{1.0, {{10, 5.0}, {800, 1.0}, {1000, 1.0}}}, run(1.0)};
  EXPECT_TRUE(assess_convergence(early).stalled);
}

// A hybrid's local stage (LM, SLSQP) improves late by design: a best run that ended at a local optimum
// (Optimizer::at_local_optimum) is not asked to stall; the runs must still agree.
TEST(Convergence, ALocalOptimumEndsTheLateImprovementCheck) {
  std::vector<RunHistory> runs{{1.0, {{10, 5.0}, {900, 1.0}, {1000, 1.0}}, true}, run(1.0), run(1.0)};
  EXPECT_TRUE(assess_convergence(runs).stalled);
  EXPECT_EQ(assess_convergence(runs).verdict(), "converged");
  runs[0].at_local_optimum = false;  // the same history from an LM that hit its iteration cap
  EXPECT_EQ(assess_convergence(runs).verdict(), "still improving");
  const std::vector<RunHistory> disagree{{1.0, {{10, 5.0}, {900, 1.0}}, true}, run(2.0), run(2.0)};
  EXPECT_EQ(assess_convergence(disagree).verdict(), "runs disagree");
}

TEST(Convergence, OneRunIsNeverCalledConverged) {
  // The utfsm preset's single Spencer run: stuck at 0.22, stalled, but nothing shows it is the optimum.
  const std::vector<RunHistory> one{run(0.22)};
  const Convergence c = assess_convergence(one);
  EXPECT_TRUE(c.stalled);
  EXPECT_FALSE(c.runs_agree);
  EXPECT_FALSE(c.converged);
  EXPECT_EQ(c.verdict(), "one run");
}

TEST(Convergence, NoiseFreeFitsAgreeWithinTheAbsoluteTolerance) {
  const std::vector<RunHistory> runs{run(1e-12), run(1e-11), run(3e-10)};
  const Convergence c = assess_convergence(runs);
  EXPECT_TRUE(c.runs_agree);  // 1e-11 − 1e-12 is far below abs_tol = 1e-9
  EXPECT_TRUE(c.converged);
}

// A best of exactly 0 (an exact fit) or within abs_tol of it has no relative figure: the text gives the differences in
// the metric's units, never "inf %" or 5e+298 %; away from 0 it gives percentages.
TEST(Convergence, AnExactFitIsDescribedInTheMetricsUnits) {
  const ConvergenceRule rule;
  const std::vector<RunHistory> exact{run(0.0), run(2e-12), run(4e-12)};
  const Convergence c = assess_convergence(exact);
  EXPECT_FALSE(c.relative_figures);
  EXPECT_EQ(c.median_above_best, 2e-12);
  EXPECT_EQ(c.worst_above_best, 4e-12);
  const std::string text = c.spread_text(rule);
  EXPECT_EQ(text, "the best is 0, within 1e-09 of 0, so the differences are in the metric's units: the median run ends "
                  "2e-12 above the best, the worst 4e-12; the best run improved 0 over its last 20 % of evaluations");
  const std::vector<RunHistory> tiny{run(1e-300), run(2e-12)};  // relative: 2e+288, meaningless
  EXPECT_NE(assess_convergence(tiny).spread_text(rule).find("metric's units: the median run ends 2e-12 above"), std::string::npos);
  const std::vector<RunHistory> plain{run(0.5), run(0.51), run(0.6)};  // median 0.51: 2 % above, worst 20 %
  EXPECT_EQ(assess_convergence(plain).spread_text(rule),
            "the median run ends 2 % above the best, the worst 20 %; the best run improved 0 % over its last 20 % of "
            "evaluations");
}

TEST(Convergence, FailedRunsAndEmptyInput) {
  const std::vector<RunHistory> failed{{kInf, {{1000, kInf}}}, {std::nan(""), {{1000, kInf}}}};
  const Convergence c = assess_convergence(failed);
  EXPECT_TRUE(c.all_failed);
  EXPECT_FALSE(c.converged);
  EXPECT_EQ(c.verdict(), "every run failed");
  EXPECT_EQ(assess_convergence(std::vector<RunHistory>{}).verdict(), "every run failed");
  // A store without traces cannot show stalling: said so, never counted as converged.
  const std::vector<RunHistory> bare{{1.0, {}}, {1.0, {}}};
  EXPECT_FALSE(assess_convergence(bare).converged);
  EXPECT_EQ(assess_convergence(bare).verdict(), "no history");
  // Half of the runs failed: the median is +inf, so they do not agree.
  const std::vector<RunHistory> half{run(1.0), run(1.0), {kInf, {{1000, kInf}}}, {kInf, {{1000, kInf}}}};
  EXPECT_FALSE(assess_convergence(half).runs_agree);
}

TEST(Convergence, ImprovementPointsKeepEveryImprovementAndTheEnd) {
  RunResult r;
  r.trace = {5, 5, 3, 3, 2, 2};
  r.trace_evaluations = {10, 20, 30, 40, 50, 60};
  r.best_value = 1.5;  // a local phase improved on the population phase with 7 more evaluations
  r.evaluations = 67;
  const std::vector<TracePoint> p = improvement_points(r);
  ASSERT_EQ(p.size(), 5u);
  EXPECT_EQ(p[0].evaluations, 10);
  EXPECT_EQ(p[1].evaluations, 30);
  EXPECT_EQ(p[2].evaluations, 50);
  EXPECT_EQ(p[3].evaluations, 60);
  EXPECT_EQ(p[4].evaluations, 67);
  EXPECT_EQ(p[4].value, 1.5);
}

/// Identification of fvd.generalized_viscous on its own noise-free force (3 parameters).
Identification fit_generalized_viscous(int population, int generations, int runs) {
  const Model& model = find_model("fvd.generalized_viscous");
  Dataset d = testing::two_sine_record();
  d.F_N = model.simulate(std::vector<double>{50.0, 4e5, 0.3}, prepare_signals(d));
  static Signals s;
  s = prepare_signals(d);
  IdentificationSettings settings;
  settings.runs = runs;
  settings.metric = Metric::nrmse;
  return identify(model, s, default_bounds(model), make_optimizer_factory({"de", population, generations}), settings);
}

TEST(Convergence, StarvedBudgetIsFlaggedGenerousIsNot) {
  const Convergence starved = assess_convergence(fit_generalized_viscous(8, 4, 6));
  EXPECT_FALSE(starved.converged) << starved.verdict() << ", median +" << starved.median_above_best_rel;
  const Convergence generous = assess_convergence(fit_generalized_viscous(30, 300, 6));
  EXPECT_TRUE(generous.converged) << generous.verdict() << ", median +" << generous.median_above_best_rel
                                  << ", late gain " << generous.late_gain_rel;
}

}  // namespace
}  // namespace dampbench
