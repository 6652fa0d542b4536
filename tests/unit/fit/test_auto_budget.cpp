// The automatic budget (engine/fit/auto_budget.hpp): chains of restarts judged by the convergence verdict and a
// confirming restart, a cap that is flagged when it starves the fit, round 0 equal to the fixed budget, and fit's
// rules for when it applies.
#include "engine/fit/auto_budget.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <tbb/global_control.h>

#include "engine/common/error.hpp"
#include "engine/fit/prepared_fit.hpp"
#include "engine/identification/convergence.hpp"
#include "models/registry.hpp"
#include "engine/record/signals.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

RunResult run_of(double best, std::vector<double> trace, std::vector<long long> at, long long evaluations,
                 std::vector<double> params) {
  RunResult r;
  r.best_value = best;
  r.trace = std::move(trace);
  r.trace_evaluations = std::move(at);
  r.evaluations = evaluations;
  r.best_params = std::move(params);
  r.stop_reason = "iterations";
  return r;
}

// Hand-made rounds: the chain's history continues where it ended (evaluations offset by what it had spent,
// values never above its best so far), a local phase's gain at the end of a round is kept as a point, and the
// chain's best is the better round's.
TEST(AutoBudget, AppendRoundChainsEachRunsHistory) {
  Identification chains, round0, round1;
  // Run 0: population phase to 5 at 100 evaluations, then a local phase to 4 at 130.
  round0.runs.push_back(run_of(4.0, {9, 5}, {50, 100}, 130, {1.0}));
  round0.runs.push_back(run_of(3.0, {6, 3}, {50, 100}, 100, {2.0}));
  round1.runs.push_back(run_of(2.0, {7, 2}, {100, 200}, 200, {3.0}));  // better than round 0
  round1.runs.push_back(run_of(8.0, {9, 8}, {100, 200}, 200, {4.0}));  // worse than round 0
  round0.wall_time_s = 1.5;
  round1.wall_time_s = 2.5;
  append_round(chains, round0);
  append_round(chains, round1);
  ASSERT_EQ(chains.runs.size(), 2u);
  const RunResult& a = chains.runs[0];
  EXPECT_EQ(a.trace, (std::vector<double>{9, 5, 4, 4, 2}));
  EXPECT_EQ(a.trace_evaluations, (std::vector<long long>{50, 100, 130, 230, 330}));
  EXPECT_EQ(a.evaluations, 330);
  EXPECT_EQ(a.best_value, 2.0);
  EXPECT_EQ(a.best_params, std::vector<double>{3.0});
  const RunResult& b = chains.runs[1];
  EXPECT_EQ(b.trace, (std::vector<double>{6, 3, 3, 3}));
  EXPECT_EQ(b.trace_evaluations, (std::vector<long long>{50, 100, 200, 300}));
  EXPECT_EQ(b.best_value, 3.0);
  EXPECT_EQ(b.best_params, std::vector<double>{2.0});
  EXPECT_DOUBLE_EQ(chains.wall_time_s, 4.0);
}

// A restart confirms the best only by landing on it again: not above it (not found again), not below it (a new
// best, found once).
TEST(AutoBudget, ARestartConfirmsByFindingTheBestAgain) {
  EXPECT_TRUE(restart_confirms(2.0, 2.0));
  EXPECT_TRUE(restart_confirms(2.0, 2.0 * (1 + 0.9e-3)));
  EXPECT_TRUE(restart_confirms(2.0, 2.0 * (1 - 0.9e-3)));
  EXPECT_FALSE(restart_confirms(2.0, 2.0 * (1 + 1.1e-3)));  // ended above: the best was not found again
  EXPECT_FALSE(restart_confirms(2.0, 2.0 * (1 - 1.1e-3)));  // ended below: a better best, found once
  EXPECT_FALSE(restart_confirms(std::numeric_limits<double>::infinity(), 2.0));  // nothing to confirm before
  EXPECT_FALSE(restart_confirms(2.0, std::numeric_limits<double>::quiet_NaN()));
  EXPECT_TRUE(restart_confirms(0.0, 1e-10));  // values no metric can tell apart (ConvergenceRule::abs_tol)
}

TEST(AutoBudget, RoundIterationsDouble) {
  EXPECT_EQ(round_iterations({"ga", 50, 100}, 0), 100);
  EXPECT_EQ(round_iterations({"ga", 50, 100}, 3), 800);
  EXPECT_EQ(round_iterations({"cmaes", 0, 30}, 2), 120);
  EXPECT_EQ(default_cap(4LL * 50 * 100, 0), 64LL * 4 * 50 * 100);
  EXPECT_EQ(default_cap(20'000 + 1'234, 250'000), 64LL * 21'234 + 250'000);
}

/// The noisy Kwok rotary-damper record of the optimizer tests: 6 parameters, 0.5 % noise.
struct KwokProblem {
  const Model& model = find_model("crfd.kwok");
  Signals data;
  KwokProblem() {
    Dataset d = testing::two_sine_record(300, 250.0);
    d.F_N = model.simulate(std::vector<double>{3.0, 25.0, 0.5, 6.0, 0.8, 0.011}, prepare_signals(d));
    testing::add_force_noise(d, 0.005, 13);
    data = prepare_signals(d);
  }
  IdentificationSettings settings(int runs) const {
    IdentificationSettings s;
    s.runs = runs;
    s.seed = 3;
    s.metric = Metric::rmse;
    s.task_key = task_key("crfd.kwok", "two_sine", "ga");
    return s;
  }
  Identification fixed(const OptimizerSpec& optimizer, int runs) const {
    return identify(model, {&data}, default_bounds(model), make_optimizer_factory(optimizer), settings(runs));
  }
  Identification run(const AutoBudget& budget, int runs, AutoBudgetReport& report,
                     const BudgetProgress& progress = {}) const {
    return identify_until_converged(model, {&data}, default_bounds(model), budget, settings(runs), report, progress);
  }
};

// GA at its defaults (50 × 100) does not converge on this record in 10 runs: longer restarts make its runs agree
// and a restart confirms the best within the default cap, and the report says so; a cap too small for round 0
// cuts it and is flagged.
TEST(AutoBudget, GenerousCapConvergesStarvedCapIsFlagged) {
  const KwokProblem p;
  const OptimizerSpec ga{"ga", 50, 100};
  const Identification fixed = p.fixed(ga, 10);
  ASSERT_FALSE(assess_convergence(fixed).converged) << "the fixed budget converges: the case tests nothing";

  AutoBudgetReport generous;
  std::vector<std::string> told;
  const Identification chains = p.run({ga, 0, 0}, 10, generous, [&](const std::string& l) { told.push_back(l); });
  EXPECT_EQ(generous.stop, "converged") << generous.summary();
  // One progress line per round, and one for the second opinion after the round that asked for it.
  ASSERT_EQ(told.size(), generous.iterations.size() + 1);
  EXPECT_EQ(told[0].rfind("automatic budget: round 0 (100 iterations): best ", 0), 0u) << told[0];
  // The default cap: 64 × round 0 (10 × 50 × 100, ga has no local stage) until the second opinion, then its
  // evaluations on top.
  EXPECT_NE(told[1].find(fmt::format("of {} evaluations", 64LL * 10 * 50 * 100)), std::string::npos) << told[1];
  EXPECT_EQ(generous.cap, 64LL * 10 * 50 * 100 + generous.second_opinion_evaluations);
  int opinions = 0;
  for (const std::string& line : told)
    opinions += line.rfind("automatic budget: second opinion (de, 50 runs): best ", 0) == 0 ? 1 : 0;
  EXPECT_EQ(opinions, 1);
  EXPECT_EQ(told.front().find("second opinion"), std::string::npos);
  EXPECT_TRUE(assess_convergence(chains).converged);
  ASSERT_GT(generous.iterations.size(), 1u);
  EXPECT_EQ(generous.iterations[1], 200);
  EXPECT_LE(std::abs(generous.last_restart_rel), kRestartRel);
  EXPECT_LE(generous.evaluations, generous.cap);
  long long spent = 0;
  for (const RunResult& r : chains.runs) spent += r.evaluations;
  EXPECT_EQ(generous.second_opinion_label(), "de");
  EXPECT_GT(generous.second_opinion_evaluations, 0);
  EXPECT_EQ(spent + generous.second_opinion_evaluations, generous.evaluations);
  EXPECT_LE(chains.runs[chains.best_run()].best_value, fixed.runs[fixed.best_run()].best_value);

  AutoBudgetReport starved;
  const Identification cut = p.run({ga, 300, 0}, 10, starved);
  EXPECT_EQ(starved.stop, "cap");
  EXPECT_EQ(starved.iterations.size(), 1u);
  // Each run stops at the end of the iteration (50 evaluations) that reaches its share of 30.
  EXPECT_EQ(starved.evaluations, 10 * 50);
  EXPECT_FALSE(assess_convergence(cut).converged);
  EXPECT_NE(starved.summary().find("stopped at the cap before converging; no restart yet"), std::string::npos)
      << starved.summary();
}

// Runs that agree are not enough: PSO's 50 runs of 50 × 100 all end on the record's higher basin (the μ–ξ
// plateau, where the verdict holds), and only the longer restarts find the lower one. The automatic budget goes
// on until a restart finds nothing better, and ends below the fixed budget's best by more than the tolerance.
TEST(AutoBudget, AgreeingRunsWaitForARestartToConfirmTheBest) {
  const KwokProblem p;
  const OptimizerSpec pso{"pso", 50, 100};
  const Identification fixed = p.fixed(pso, 50);
  ASSERT_TRUE(assess_convergence(fixed).converged) << "pso's runs disagree: the case tests nothing";
  AutoBudgetReport report;
  const Identification chains = p.run({pso, 0, 0}, 50, report);
  EXPECT_EQ(report.stop, "converged") << report.summary();
  ASSERT_GE(report.iterations.size(), 3u) << report.summary();
  EXPECT_EQ(report.iterations[2], 400);
  const double fixed_best = fixed.runs[fixed.best_run()].best_value;
  const double best = chains.runs[chains.best_run()].best_value;
  EXPECT_LT(best, fixed_best * (1 - kRestartRel)) << report.summary();
  EXPECT_LE(std::abs(report.last_restart_rel), kRestartRel);
}

// Every CMA-ES run and restart on this record lands on the μ–ξ plateau, where the runs agree and a restart
// confirms the best: only another optimizer shows a lower basin. The second opinion (de) finds it, so the fit is
// not called converged; the rounds go on to the cap, and the result stays cmaes's own.
TEST(AutoBudget, ASecondOpinionKeepsASharedHigherBasinFromPassingAsConverged) {
  const KwokProblem p;
  const OptimizerSpec cmaes{"cmaes", 50, 100};
  const int runs = 50;  // fit's default for an algebraic model
  const Identification fixed = p.fixed(cmaes, runs);
  ASSERT_TRUE(assess_convergence(fixed).converged) << "cmaes's runs disagree: the case tests nothing";
  AutoBudgetReport report;
  const long long round0 = 1LL * runs * 50 * 100;
  const Identification chains = p.run({cmaes, 8 * round0, 0}, runs, report);
  ASSERT_EQ(report.second_opinion_label(), "de") << report.summary();
  const double best = chains.runs[chains.best_run()].best_value;
  EXPECT_LT(report.second_opinion_best, best * (1 - kRestartRel)) << report.summary();
  EXPECT_LT(report.second_opinion_rel, -kRestartRel);
  EXPECT_EQ(report.stop, "cap") << report.summary();
  EXPECT_GE(report.iterations.size(), 3u) << "the rounds stopped at the second opinion: " << report.summary();
  EXPECT_NE(report.summary().find("a second opinion (de) found"), std::string::npos) << report.summary();
  EXPECT_FALSE(assess_convergence(chains, {}, report.stop != "converged").converged);
}

// The default cap leaves room for five restarts whatever the second opinion costs: beside a fit of 10 cmaes runs it
// takes 50 de runs (5 of the fit's round 0s), which under a cap of 64 round 0s alone would leave no room for the
// sixth round (1 + 2 + 4 + 8 + 16 round 0s + 5 spent, 32 more needed). cmaes never converges on this record (its
// runs share the plateau the second opinion sees below), so the fit runs every round the cap allows.
TEST(AutoBudget, TheDefaultCapLeavesRoomForFiveRestartsBesideTheSecondOpinion) {
  const KwokProblem p;
  const OptimizerSpec cmaes{"cmaes", 50, 100};
  AutoBudgetReport report;
  (void)p.run({cmaes, 0, 0}, 10, report);
  ASSERT_GT(report.second_opinion_evaluations, 4 * 10LL * 50 * 100) << "no second opinion: the case tests nothing; "
                                                                    << report.summary();
  EXPECT_EQ(report.stop, "cap") << report.summary();
  EXPECT_EQ(report.iterations, (std::vector<int>{100, 200, 400, 800, 1600, 3200})) << report.summary();
  EXPECT_EQ(report.cap, 64LL * 10 * 50 * 100 + report.second_opinion_evaluations);
  EXPECT_LE(report.evaluations, report.cap);
}

// The second opinion is another optimizer at fit's defaults for the model: de on an algebraic model (ga-lm for de
// itself), ga-lm on a model with internal states (ga-lm with a CMA-ES global stage for ga-lm itself), with at
// least fit's default run count.
TEST(AutoBudget, TheSecondOpinionIsAnotherOptimizer) {
  const Model& kwok = find_model("crfd.kwok");
  const Model& bouc_wen = find_model("mrd.bouc_wen");
  const OptimizerSpec of_pso = second_opinion(kwok, {"pso", 20, 30});
  EXPECT_EQ(of_pso.name, "de");
  EXPECT_TRUE(of_pso.settings.empty());
  EXPECT_EQ(of_pso.population, 50);
  EXPECT_EQ(of_pso.iterations, 100);
  EXPECT_EQ(second_opinion(kwok, {"de", 50, 100}).name, "ga-lm");
  EXPECT_EQ(second_opinion(kwok, {"ga-lm", 50, 100}).name, "de");
  EXPECT_TRUE(second_opinion(kwok, {"ga-lm", 50, 100}).settings.empty());
  const OptimizerSpec of_pso_ode = second_opinion(bouc_wen, {"pso", 50, 100});
  EXPECT_EQ(of_pso_ode.name, "ga-lm");
  EXPECT_TRUE(of_pso_ode.settings.empty());
  EXPECT_EQ(of_pso_ode.population, 24);
  EXPECT_EQ(of_pso_ode.iterations, 30);
  const OptimizerSpec of_ga_lm = second_opinion(bouc_wen, {"ga-lm", 24, 30});
  EXPECT_EQ(of_ga_lm.name, "ga-lm");
  EXPECT_EQ(of_ga_lm.settings, (std::map<std::string, std::string>{{"global", "cmaes"}}));
  EXPECT_TRUE(second_opinion(bouc_wen, {"ga-lm", 24, 30, {{"global", "cmaes"}}}).settings.empty());
  // Its runs: the fit's, at least fit's default for the model.
  EXPECT_EQ(second_opinion_runs(kwok, 10), 50);
  EXPECT_EQ(second_opinion_runs(kwok, 80), 80);
  EXPECT_EQ(second_opinion_runs(bouc_wen, 4), 4);
  EXPECT_EQ(second_opinion_runs(bouc_wen, 2), 4);
}

// Round 0 is the fixed budget, with the same bits; with no room for a restart the fit stops there at the cap,
// unconfirmed even where the runs agree.
TEST(AutoBudget, RoundZeroIsTheFixedBudget) {
  const KwokProblem p;
  const OptimizerSpec de{"de", 30, 100};
  const Identification fixed = p.fixed(de, 4);
  ASSERT_TRUE(assess_convergence(fixed).converged) << "de at 30 x 100 does not converge: the case tests nothing";
  AutoBudgetReport report;
  const Identification chains = p.run({de, 2LL * 4 * 30 * 100, 0}, 4, report);
  EXPECT_EQ(report.iterations, std::vector<int>{100});
  EXPECT_EQ(report.stop, "cap");
  EXPECT_NE(report.summary().find("no restart yet"), std::string::npos) << report.summary();
  for (std::size_t r = 0; r < chains.runs.size(); ++r) {
    EXPECT_EQ(chains.runs[r].best_value, fixed.runs[r].best_value);
    EXPECT_EQ(chains.runs[r].best_params, fixed.runs[r].best_params);
  }
}

// Same bits on one and two threads, through every round.
TEST(AutoBudget, SameBitsForAnyThreadCount) {
  const KwokProblem p;
  const AutoBudget budget{{"ga", 10, 15}, 0, 0};
  AutoBudgetReport one, two;
  Identification a, b;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    a = p.run(budget, 6, one);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    b = p.run(budget, 6, two);
  }
  EXPECT_EQ(one.iterations, two.iterations);
  EXPECT_EQ(one.stop, two.stop);
  ASSERT_EQ(a.runs.size(), b.runs.size());
  for (std::size_t r = 0; r < a.runs.size(); ++r) {
    EXPECT_EQ(a.runs[r].best_params, b.runs[r].best_params);
    EXPECT_EQ(a.runs[r].trace, b.runs[r].trace);
  }
}

TEST(AutoBudget, OneRunIsRefused) {
  const KwokProblem p;
  AutoBudgetReport report;
  const std::string e = testing::error_of([&] { p.run({{"ga", 10, 15}, 0, 0}, 1, report); });
  EXPECT_NE(e.find("at least 2 runs"), std::string::npos) << e;
}

// fit's rules: auto unless --pop, --iters or --runs is given; --budget says which explicitly; the caps belong to
// the automatic budget only.
TEST(AutoBudget, FitChoosesTheBudgetFromItsOptions) {
  const auto dir = testing::test_temp_dir("auto_budget");
  const std::string path = (dir / "r.csv").string();
  {
    std::ofstream f(path);
    f << "t,x,v,F\n";
    for (int i = 0; i < 50; ++i) f << i * 0.01 << "," << std::sin(i * 0.1) << "," << std::cos(i * 0.1) << "," << i << "\n";
  }
  const auto spec = [&](auto&& edit) {
    FitSpec s;
    s.model.model = "fvd.linear_viscous";
    s.model.option_prefix = "--";
    s.paths = {path};
    edit(s);
    return s;
  };
  EXPECT_TRUE(prepare_fit(spec([](FitSpec&) {})).auto_budget.has_value());
  EXPECT_FALSE(prepare_fit(spec([](FitSpec& s) { s.population = 20; })).auto_budget.has_value());
  EXPECT_FALSE(prepare_fit(spec([](FitSpec& s) { s.runs = 5; })).auto_budget.has_value());
  EXPECT_FALSE(prepare_fit(spec([](FitSpec& s) { s.budget = "fixed"; })).auto_budget.has_value());
  const PreparedFit with_pop = prepare_fit(spec([](FitSpec& s) {
    s.budget = "auto";
    s.population = 20;
    s.max_evaluations = 12345;
  }));
  ASSERT_TRUE(with_pop.auto_budget.has_value());
  EXPECT_EQ(with_pop.auto_budget->optimizer.population, 20);
  EXPECT_EQ(with_pop.auto_budget->max_evaluations, 12345);
  EXPECT_NE(testing::error_of([&] { prepare_fit(spec([](FitSpec& s) { s.budget = "some"; })); })
                .find("--budget: expected auto or fixed, got 'some'"),
            std::string::npos);
  // --precision: the search's lanes (identification.hpp, search_precision)
  EXPECT_EQ(prepare_fit(spec([](FitSpec&) {})).request().settings.search_precision, Precision::float32);
  EXPECT_EQ(prepare_fit(spec([](FitSpec& s) { s.precision = "double"; })).request().settings.search_precision,
            Precision::float64);
  EXPECT_NE(testing::error_of([&] { prepare_fit(spec([](FitSpec& s) { s.precision = "single"; })); })
                .find("--precision: expected double or mixed, got 'single'"),
            std::string::npos);
  EXPECT_NE(testing::error_of([&] { prepare_fit(spec([](FitSpec& s) {
              s.iterations = 10;
              s.max_evaluations = 1000;
            })); }).find("add --budget auto"),
            std::string::npos);
  // --laws auto fits many models at the fixed budget.
  EXPECT_FALSE(prepare_fit(spec([](FitSpec& s) { s.model.laws = "auto"; })).auto_budget.has_value());
  EXPECT_NE(testing::error_of([&] { prepare_fit(spec([](FitSpec& s) {
              s.model.laws = "auto";
              s.budget = "auto";
            })); }).find("do not apply to --laws auto"),
            std::string::npos);
  EXPECT_NE(testing::error_of([&] { prepare_fit(spec([](FitSpec& s) { s.max_evaluations = 0; })); })
                .find("--max-evals: expected a whole number >= 1, got 0"),
            std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace dampbench
