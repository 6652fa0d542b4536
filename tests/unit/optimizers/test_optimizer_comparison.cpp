// Optimizer comparison (optimizers/comparison.hpp) and `dampbench compare` (engine/cli/compare_command.cpp).
#include "optimizers/comparison.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/common/error.hpp"
#include "models/registry.hpp"
#include "tests/optimizer_test_support.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// fvd.gv_linear_elastic on a two-frequency record with a friction-like force it cannot follow, so the
/// least-squares optimum has a clearly positive nrmse that every good run reaches.
struct Problem {
  const Model& model = find_model("fvd.gv_linear_elastic");
  Signals data;
  Problem() {
    Dataset d = testing::two_sine_record(400);
    d.F_N = model.simulate(std::vector<double>{300, 9e5, 0.4, 5e6}, prepare_signals(d));
    for (std::size_t k = 0; k < d.F_N.size(); ++k) d.F_N[k] += 2e4 * std::tanh(d.v_m_s[k] / 0.01);
    data = prepare_signals(d);
  }
  Comparison compare(const std::vector<std::string>& entries, std::optional<double> target = {}) const {
    std::vector<ComparisonEntry> list;
    for (const auto& e : entries) list.push_back({e, parse_optimizer_entry(e)});
    ComparisonSettings s;
    s.identification.runs = 5;
    s.identification.seed = 2;
    s.identification.metric = Metric::nrmse;
    s.data_name = "two_sine";
    s.target = target;
    return compare_optimizers(model, {&data}, default_bounds(model), list, s);
  }
};

const Problem& problem() {
  static const Problem p;
  return p;
}

const Comparison& three_way() {
  static const Comparison c = problem().compare(
      {"pso:population=20,iterations=15", "ga:population=20,iterations=15", "ga-lm:population=20,iterations=15"});
  return c;
}

}  // namespace

// ---- parsing -----------------------------------------------------------------------------------------

TEST(OptimizerComparison, ParsesOptimizerEntries) {
  const OptimizerSpec pso = parse_optimizer_entry("pso");
  EXPECT_EQ(pso.name, "pso");
  EXPECT_EQ(pso.population, 50);
  EXPECT_EQ(pso.iterations, 100);
  EXPECT_TRUE(pso.settings.empty());
  const OptimizerSpec sqp = parse_optimizer_entry(" ga-sqp:population=240, iterations=30,constraint=0.04 ");
  EXPECT_EQ(sqp.name, "ga-sqp");
  EXPECT_EQ(sqp.population, 240);
  EXPECT_EQ(sqp.iterations, 30);
  EXPECT_EQ(sqp.settings, (std::map<std::string, std::string>{{"constraint", "0.04"}}));
  EXPECT_EQ(parse_optimizer_entry("de:F=0.7", 10, 20).population, 10);
}

TEST(OptimizerComparison, RejectsBadEntries) {
  using testing::error_of;
  EXPECT_EQ(error_of([] { parse_optimizer_entry("ga:population=x"); }),
            "--optimizer 'ga:population=x': population: expected a number, got 'x'");
  EXPECT_EQ(error_of([] { parse_optimizer_entry("ga:iterations=2.5"); }),
            "--optimizer 'ga:iterations=2.5': iterations: expected a whole number, got '2.5'");
  EXPECT_EQ(error_of([] { parse_optimizer_entry(":pc=1"); }), "--optimizer ':pc=1': expected NAME or NAME:key=value,...");
  EXPECT_NE(error_of([] { parse_optimizer_entry("ga:pc"); }).find("--optimizer 'ga:pc'"), std::string::npos);

  const Problem& p = problem();
  EXPECT_EQ(error_of([&] { p.compare({"ga:population=2"}); }),
            "--optimizer 'ga:population=2': ga: population must be at least 4, got 2");
  EXPECT_EQ(error_of([&] { p.compare({"ga:pc=1.5"}); }), "--optimizer 'ga:pc=1.5': ga: pc must be in [0, 1], got 1.5");
  EXPECT_EQ(error_of([&] { p.compare({"sa"}); }),
            "--optimizer 'sa': unknown optimizer 'sa' (known: pso, ga, aga, de, cmaes, ga-sqp, ga-lm)");
  EXPECT_EQ(error_of([&] { p.compare({"pso:population=8", "pso:population=8"}); }),
            "--optimizer 'pso:population=8' is given twice");
  EXPECT_EQ(error_of([&] { p.compare({}); }), "compare: give at least one --optimizer");
  EXPECT_EQ(error_of([&] { p.compare({"pso:population=8"}, kInf); }), "--target: expected a finite number, got inf");
}

// ---- statistics helpers ------------------------------------------------------------------------------

TEST(OptimizerComparison, QuantilesInterpolateAndKeepInfinities) {
  EXPECT_EQ(sorted_quantile({1, 2, 3, 4}, 0.5), 2.5);
  EXPECT_EQ(sorted_quantile({1, 2, 3, 4}, 0.25), 1.75);
  EXPECT_EQ(sorted_quantile({1, 2, 3, 4}, 1.0), 4);
  EXPECT_EQ(sorted_quantile({1, 2, kInf, kInf}, 0.5), kInf);
  EXPECT_EQ(sorted_quantile({1, 2, kInf, kInf}, 0.25), 1.75);
  EXPECT_EQ(sorted_quantile({kInf, kInf}, 0.5), kInf);
  EXPECT_TRUE(std::isnan(sorted_quantile({}, 0.5)));
}

TEST(OptimizerComparison, TraceGetsTheLocalPhaseEndPoint) {
  RunResult r;
  r.trace = {5, 3};
  r.trace_evaluations = {10, 20};
  r.evaluations = 35;
  r.best_value = 1;
  std::vector<long long> e;
  std::vector<double> v;
  completed_trace(r, e, v);
  EXPECT_EQ(e, (std::vector<long long>{10, 20, 35}));
  EXPECT_EQ(v, (std::vector<double>{5, 3, 1}));
  r.evaluations = 20;  // a population-only run: nothing to add
  r.best_value = 3;
  completed_trace(r, e, v);
  EXPECT_EQ(e, (std::vector<long long>{10, 20}));
  EXPECT_EQ(v, (std::vector<double>{5, 3}));
}

// ---- the comparison ----------------------------------------------------------------------------------

TEST(OptimizerComparison, StatisticsFollowTheirDefinitions) {
  const Comparison& c = three_way();
  ASSERT_EQ(c.optimizers.size(), 3u);
  double best = kInf;
  for (const auto& o : c.optimizers)
    for (const auto& r : o.runs) best = std::min(best, r.best_value);
  EXPECT_EQ(c.best_found, best);
  EXPECT_GT(c.best_found, 1e-3);  // the structural error keeps the optimum well above zero
  EXPECT_EQ(c.success_threshold, best + 0.01 * best);
  EXPECT_EQ(c.target, c.success_threshold);
  EXPECT_FALSE(c.target_given);
  for (const auto& o : c.optimizers) {
    SCOPED_TRACE(o.label);
    ASSERT_EQ(o.runs.size(), 5u);
    std::vector<double> values, to_target;
    int successes = 0;
    for (const auto& r : o.runs) {
      values.push_back(r.best_value);
      successes += r.best_value <= c.success_threshold;
      std::vector<long long> e;
      std::vector<double> v;
      completed_trace(r, e, v);
      double reached = kInf;
      for (std::size_t k = 0; k < v.size() && !std::isfinite(reached); ++k)
        if (v[k] <= c.target) reached = static_cast<double>(e[k]);
      to_target.push_back(reached);
    }
    const Summary s = summarize(values);
    EXPECT_EQ(o.summary.min, s.min);
    EXPECT_EQ(o.summary.max, s.max);
    EXPECT_EQ(o.summary.mean, s.mean);
    EXPECT_EQ(o.summary.std, s.std);
    EXPECT_EQ(o.successes, successes);
    EXPECT_DOUBLE_EQ(o.success_rate, successes / 5.0);
    std::sort(to_target.begin(), to_target.end());
    EXPECT_EQ(o.median_evaluations_to_target, to_target[2]);
    EXPECT_FALSE(o.feasible_runs.has_value());
    // Curves: quartiles ordered, the median never rises, and the last point is the longest run's end.
    ASSERT_FALSE(o.curve.empty());
    long long longest = 0;
    for (const auto& r : o.runs) longest = std::max(longest, r.evaluations);
    EXPECT_EQ(o.curve.back().evaluations, longest);
    for (std::size_t k = 0; k < o.curve.size(); ++k) {
      EXPECT_LE(o.curve[k].q25, o.curve[k].median);
      EXPECT_LE(o.curve[k].median, o.curve[k].q75);
      if (k > 0) {
        EXPECT_LE(o.curve[k].median, o.curve[k - 1].median);
        EXPECT_GT(o.curve[k].evaluations, o.curve[k - 1].evaluations);
      }
    }
  }
  // The least-squares hybrid finds the optimum in every run; the GA alone in none, at this budget.
  const OptimizerComparison& lm = c.optimizers[2];
  EXPECT_EQ(lm.successes, 5);
  EXPECT_EQ(lm.reached_target, 5);
  EXPECT_EQ(c.optimizers[1].successes, 0);
  EXPECT_EQ(c.optimizers[1].median_evaluations_to_target, kInf);
  EXPECT_GT(lm.mean_evaluations, 20.0 * 15);                  // LM evaluations counted
  EXPECT_GT(lm.median_evaluations_to_target, 20.0 * 15);      // reached in the LM phase
  EXPECT_LE(lm.curve.back().q75, c.success_threshold);  // the hybrid's curve ends at the optimum
}

TEST(OptimizerComparison, EntriesDoNotInfluenceEachOther) {
  const Comparison alone = problem().compare({"ga:population=20,iterations=15"});
  const auto& a = alone.optimizers[0].runs;
  const auto& b = three_way().optimizers[1].runs;
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t r = 0; r < a.size(); ++r) {
    EXPECT_EQ(a[r].best_params, b[r].best_params);
    EXPECT_EQ(a[r].trace, b[r].trace);
  }
}

TEST(OptimizerComparison, GivenTargetAndGaSqpFeasibility) {
  const Comparison c = problem().compare({"ga-sqp:population=12,iterations=5,constraint=1e-9",
                                          "ga-sqp:population=12,iterations=5,sqp_iterations=20"},
                                         0.5);
  EXPECT_TRUE(c.target_given);
  EXPECT_EQ(c.target, 0.5);
  ASSERT_TRUE(c.optimizers[0].feasible_runs.has_value());
  EXPECT_EQ(*c.optimizers[0].feasible_runs, 0);  // nothing reaches nrmse 1e-9 with a structural error
  EXPECT_EQ(*c.optimizers[0].constraint, 1e-9);
  EXPECT_EQ(*c.optimizers[1].feasible_runs, 5);  // default constraint 4, far above any nrmse here
  EXPECT_EQ(*c.optimizers[1].constraint, 4.0);
  for (const auto& o : c.optimizers) {
    int reached = 0;
    for (const auto& r : o.runs) reached += r.best_value <= 0.5;
    EXPECT_EQ(o.reached_target, reached);
  }
}

TEST(OptimizerComparison, TableAndConvergenceCsv) {
  const Comparison& c = three_way();
  const Table t = comparison_table(c, "nrmse");
  ASSERT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(t.columns.front(), "optimizer");
  EXPECT_EQ(t.rows[2][0].text, "ga-lm:population=20,iterations=15");
  EXPECT_EQ(t.rows[2][6].text, "5/5 (100 %)");
  EXPECT_EQ(t.rows[1][7].text, "—");  // the GA's median evaluations to target: not reached by half the runs
  const std::string csv = convergence_csv(c);
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "optimizer,evaluations,q25,median,q75");
  std::size_t rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    EXPECT_EQ(line.front(), '"');  // labels with commas are quoted
  }
  std::size_t points = 0;
  for (const auto& o : c.optimizers) points += o.curve.size();
  EXPECT_EQ(rows, points);
}

// ---- the command line --------------------------------------------------------------------------------

namespace {

std::string record_file() {
  static const std::string path = [] {
    // named by the test that writes it: ctest runs the tests of this file in parallel processes
    const auto file = std::filesystem::temp_directory_path() /
                      (std::string("dampbench_compare_record_") +
                       ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".csv");
    std::ofstream out(file);
    out << "t,x,v,a,F\n";
    const Signals& d = problem().data;
    for (std::size_t k = 0; k < d.size(); ++k)
      out << fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", d.t_s[k], d.x_m[k], d.v_m_s[k], d.a_m_s2[k], d.F_N[k]);
    return file.string();
  }();
  return path;
}

}  // namespace

TEST(OptimizerComparison, CommandPrintsTheTableAndWritesCurves) {
  const auto dir = testing::test_temp_dir("compare");
  const auto r = testing::run_dampbench("compare --model fvd.gv_linear_elastic --data " + record_file() +
                                        " --metric nrmse --runs 3 --seed 4 --optimizer pso:population=10,iterations=6"
                                        " --optimizer ga-lm:population=10,iterations=6 -o " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("| optimizer | runs | best | worst | mean | std | success |"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("| ga-lm:population=10,iterations=6 | 3 |"), std::string::npos) << r.output;
  std::ifstream curves(dir / "convergence.csv");
  std::string header;
  std::getline(curves, header);
  EXPECT_EQ(header, "optimizer,evaluations,q25,median,q75");
  EXPECT_TRUE(std::filesystem::exists(dir / "comparison.md"));

  const auto j = testing::run_dampbench("compare --model fvd.gv_linear_elastic --data " + record_file() +
                                        " --metric nrmse --runs 2 --optimizer ga:population=8,iterations=3"
                                        " --target 0.5 --format json");
  ASSERT_EQ(j.exit_code, 0) << j.output;
  const auto json = nlohmann::json::parse(j.output);
  EXPECT_EQ(json.at("target").get<double>(), 0.5);
  EXPECT_EQ(json.at("optimizers").at(0).at("optimizer"), "ga:population=8,iterations=3");
  EXPECT_EQ(json.at("optimizers").at(0).at("run_values").size(), 2u);
}

TEST(OptimizerComparison, CommandRejectsBadInput) {
  const std::string base = "compare --model fvd.gv_linear_elastic --data " + record_file();
  const auto expect_error = [](const std::string& args, const std::string& message) {
    const auto r = testing::run_dampbench(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
  };
  expect_error(base + " --optimizer ga:population=2", "dampbench: error: --optimizer 'ga:population=2': ga: population must be at least 4, got 2");
  expect_error(base + " --optimizer ga-sqp:pc=2", "ga-sqp: pc must be in [0, 1], got 2");
  expect_error(base + " --optimizer ga-lm:lm_iterations=0", "ga-lm: lm_iterations must be at least 1, got 0");
  expect_error(base + " --optimizer pso --format xml", "--format: expected md, csv or json, got 'xml'");
  expect_error(base + " --optimizer pso --runs 0", "--runs: expected a whole number >= 1, got 0");
  expect_error(base + " --optimizer pso --target abc", "--target: expected a number, got 'abc'");
  expect_error(base + " --optimizer pso --metric r2", "unknown metric 'r2'");
  const auto missing = testing::run_dampbench(base);
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.output.find("--optimizer is required"), std::string::npos) << missing.output;
}

}  // namespace dampbench
