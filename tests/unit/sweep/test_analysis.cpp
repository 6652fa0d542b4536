// Analyses and tables of a sweep's store (engine/sweep/analysis.hpp, engine/sweep/tables.hpp): statistics
// against values computed by hand, regressions recovering known coefficients, and every table kind on a
// tiny store written through the store API with chosen numbers.
#include "engine/sweep/analysis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include <nlohmann/json.hpp>

#include "engine/common/error.hpp"
#include "engine/sweep/store.hpp"
#include "engine/sweep/tables.hpp"
#include "tests/test_support.hpp"

namespace dampbench::sweep {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// ---- Mann–Whitney -----------------------------------------------------------------------------------

TEST(MannWhitney, ExactForSeparatedSamples) {
  // a all below b: U = 0; P(U <= 0) = 1 / C(6,3) = 1/20, two-sided p = 0.1.
  const std::vector<double> a{1, 2, 3}, b{4, 5, 6};
  const RankSum t = mann_whitney(a, b);
  EXPECT_TRUE(t.exact);
  EXPECT_EQ(t.U, 0);
  EXPECT_NEAR(t.p, 0.1, 1e-15);
  const RankSum u = mann_whitney(b, a);
  EXPECT_EQ(u.U, 9);
  EXPECT_NEAR(u.p, 0.1, 1e-15);
}

TEST(MannWhitney, ExactInterleaved) {
  // a = {1, 4}, b = {2, 3}: a > b pairs: (4,2), (4,3) → U = 2 = n_a n_b / 2, the median: p = 1.
  EXPECT_NEAR(mann_whitney(std::vector<double>{1, 4}, std::vector<double>{2, 3}).p, 1.0, 1e-15);
  // a = {3, 4}, b = {1, 2, 5}: U = 4 of 6; the distribution of U for (2, 3) over C(5,2) = 10 arrangements is
  // u: 0 1 2 3 4 5 6 → counts 1 1 2 2 2 1 1; P(U >= 4) = 4/10, P(U <= 4) = 8/10 → p = 0.8.
  const RankSum t = mann_whitney(std::vector<double>{3, 4}, std::vector<double>{1, 2, 5});
  EXPECT_EQ(t.U, 4);
  EXPECT_NEAR(t.p, 0.8, 1e-15);
}

TEST(MannWhitney, NormalApproximationWithTies) {
  // a = {1, 2, 2}, b = {2, 3, 4}: ranks 1, 3, 3 | 3, 5, 6 (the three 2s share rank 3). R_a = 7, U = 1.
  // Var = 9/12 · (7 − (27 − 3)/(6·5)) = 0.75 · 6.2 = 4.65; z = (1 − 4.5 + 0.5)/sqrt(4.65) = −1.391;
  // p = erfc(1.391/√2) = 0.16414.
  const RankSum t = mann_whitney(std::vector<double>{1, 2, 2}, std::vector<double>{2, 3, 4});
  EXPECT_FALSE(t.exact);
  EXPECT_EQ(t.U, 1);
  EXPECT_NEAR(t.z, -3.0 / std::sqrt(4.65), 1e-12);
  EXPECT_NEAR(t.p, std::erfc(3.0 / std::sqrt(4.65) / std::sqrt(2.0)), 1e-12);
  EXPECT_NEAR(t.p, 0.16414, 1e-4);
  // Everything tied: no evidence at all.
  EXPECT_EQ(mann_whitney(std::vector<double>{kInf, kInf}, std::vector<double>{kInf}).p, 1.0);
  EXPECT_EQ(mann_whitney(std::vector<double>{}, std::vector<double>{1}).p, 1.0);
}

// ---- bootstrap ------------------------------------------------------------------------------------

TEST(Bootstrap, KeyedAndSensible) {
  std::vector<double> v;
  for (int k = 1; k <= 10; ++k) v.push_back(std::sqrt(static_cast<double>(k)));
  double mean = 0, ss = 0;
  for (double x : v) mean += x / 10;
  for (double x : v) ss += (x - mean) * (x - mean);
  const double se = std::sqrt(ss / 9) / std::sqrt(10.0);
  const Interval a = bootstrap_mean(v, 42), b = bootstrap_mean(v, 42), c = bootstrap_mean(v, 43);
  EXPECT_DOUBLE_EQ(a.mean, mean);
  EXPECT_EQ(a.lower, b.lower);  // same key, same bits
  EXPECT_EQ(a.upper, b.upper);
  EXPECT_NE(a.lower, c.lower);  // another key, another resampling
  EXPECT_LT(a.lower, mean);
  EXPECT_GT(a.upper, mean);
  // The percentile interval is about ±1.96 standard errors (the bootstrap's is sqrt(9/10) of the sample's).
  EXPECT_NEAR(a.upper - a.lower, 2 * 1.96 * se * std::sqrt(0.9), 0.25 * se * 2 * 1.96);
  const Interval k = bootstrap_mean(std::vector<double>{2.5, 2.5, 2.5}, 1);
  EXPECT_EQ(k.lower, 2.5);
  EXPECT_EQ(k.upper, 2.5);
  EXPECT_EQ(bootstrap_mean(std::vector<double>{1, kInf}, 1).upper, kInf);
}

// ---- fixed-target runtime -----------------------------------------------------------------------------

TEST(ConvergenceBand, QuantilesOfBestSoFarOverRuns) {
  // Three runs with hand-made traces; the grid is log-spaced from 1 to 100 evaluations (3 points: 1, 10, 100).
  const std::vector<std::vector<TracePoint>> traces{
      {{1, 9.0}, {10, 3.0}, {100, 1.0}},  // at 1: 9, at 10: 3, at 100: 1
      {{1, 5.0}, {50, 2.0}},              // 5, 5, 2
      {{20, 4.0}, {60, 4.0}}};            // absent at 1 and 10 (first point at 20), 4 at 100
  const ConvergenceBand b = convergence_band(traces, 3);
  ASSERT_EQ(b.evaluations.size(), 3u);
  EXPECT_DOUBLE_EQ(b.evaluations[0], 1);
  EXPECT_NEAR(b.evaluations[1], 10, 1e-9);
  EXPECT_EQ(b.evaluations[2], 100);  // exactly the largest evaluation count
  EXPECT_EQ(b.runs, (std::vector<int>{2, 2, 3}));
  // 1 evaluation: {5, 9}: type-7 median 7, quartiles 6 and 8.
  EXPECT_DOUBLE_EQ(b.median[0], 7);
  EXPECT_DOUBLE_EQ(b.lower_quartile[0], 6);
  EXPECT_DOUBLE_EQ(b.upper_quartile[0], 8);
  // 10: {3, 5} (the first run improved at exactly 10) → 4, 3.5, 4.5.
  EXPECT_DOUBLE_EQ(b.median[1], 4);
  EXPECT_DOUBLE_EQ(b.lower_quartile[1], 3.5);
  // 100: {1, 2, 4} → 2, 1.5, 3.
  EXPECT_DOUBLE_EQ(b.median[2], 2);
  EXPECT_DOUBLE_EQ(b.lower_quartile[2], 1.5);
  EXPECT_DOUBLE_EQ(b.upper_quartile[2], 3);
  EXPECT_TRUE(convergence_band({}, 10).evaluations.empty());
}

TEST(Runtime, FirstHitErtAndEcdf) {
  const std::vector<TracePoint> trace{{10, 5.0}, {30, 2.0}, {50, 0.5}, {100, 0.5}};
  EXPECT_EQ(first_hit(trace, 2.0), 30);
  EXPECT_EQ(first_hit(trace, 0.5), 50);
  EXPECT_EQ(first_hit(trace, 0.1), -1);
  // Runs hit at 30 and 50, a third spends 100 without: ERT = (30 + 50 + 100) / 2 = 90.
  const std::vector<long long> hits{30, 50, -1}, spent{100, 100, 100};
  const TargetRuntime t = expected_runtime(hits, spent);
  EXPECT_EQ(t.successes, 2);
  EXPECT_EQ(t.runs, 3);
  EXPECT_DOUBLE_EQ(t.ert, 90.0);
  EXPECT_EQ(expected_runtime(std::vector<long long>{-1}, std::vector<long long>{7}).ert, kInf);
  const auto f = ecdf(hits, std::vector<double>{10, 30, 49, 50, 1000});
  EXPECT_EQ(f, (std::vector<double>{0.0, 1.0 / 3, 1.0 / 3, 2.0 / 3, 2.0 / 3}));
}

// ---- regressions -------------------------------------------------------------------------------

std::vector<std::map<std::string, double>> grid(const std::string& var, std::vector<double> xs) {
  std::vector<std::map<std::string, double>> out;
  for (double x : xs) out.push_back({{var, x}});
  return out;
}

TEST(Regression, CubicInAngleRecoversCoefficients) {
  // crfd Table 5's c_r law: 1.270 + 0.104 φ − 6.937e-4 φ² + 2.264e-6 φ³ at the seven angles.
  const std::vector<double> c{1.270, 0.104, -6.937e-4, 2.264e-6};
  const auto x = grid("phi", {0, 30, 60, 90, 120, 150, 180});
  std::vector<double> y;
  for (const auto& v : x) {
    const double p = v.at("phi");
    y.push_back(c[0] + c[1] * p + c[2] * p * p + c[3] * p * p * p);
  }
  const RegressionFit f = fit_law(parse_law("poly(phi,3)", "test"), "c_r", x, y);
  EXPECT_EQ(f.names, (std::vector<std::string>{"c_r_phi0", "c_r_phi1", "c_r_phi2", "c_r_phi3"}));
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(f.coefficients[k], c[k], 1e-9 * std::fabs(c[k])) << k;
  EXPECT_NEAR(f.r2, 1.0, 1e-12);
  EXPECT_LT(f.rms_residual, 1e-10);
}

TEST(Regression, LineThroughNoisyPointsByHand) {
  // y = 1, 3, 2 at x = 0, 1, 2: slope 0.5, intercept 1.5; fitted 1.5, 2, 2.5; SSE = 0.25+1+0.25 = 1.5;
  // SST = 2 → R² = 0.25; residuals −0.5, 1, −0.5.
  const RegressionFit f = fit_law(parse_law("poly(I,1)", "test"), "D", grid("I", {0, 1, 2}), std::vector<double>{1, 3, 2});
  EXPECT_NEAR(f.coefficients[0], 1.5, 1e-12);
  EXPECT_NEAR(f.coefficients[1], 0.5, 1e-12);
  EXPECT_NEAR(f.r2, 0.25, 1e-12);
  EXPECT_NEAR(f.residuals[1], 1.0, 1e-12);
  EXPECT_NEAR(f.rms_residual, std::sqrt(0.5), 1e-12);
}

TEST(Regression, ProductOfPolynomialsRecoversCoefficients) {
  // mfm eq. 10 form, scaled so the later factors have constant term 1:
  // A = (6.2 + 0.9 I − 0.2 I²)(1 + 107 amp)(1 − 17.9 f)... use a well-conditioned truth.
  const std::vector<double> pI{6.578, 0.914, -0.205}, pa{1.0, 50.0}, pf{1.0, 0.8};
  std::vector<std::map<std::string, double>> x;
  std::vector<double> y;
  for (double I : {0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0})
    for (double amp : {0.005, 0.01, 0.015, 0.02})
      for (double f : {0.5, 1.0, 1.5, 2.0}) {
        x.push_back({{"I", I}, {"amp", amp}, {"freq", f}});
        y.push_back((pI[0] + pI[1] * I + pI[2] * I * I) * (pa[0] + pa[1] * amp) * (pf[0] + pf[1] * f));
      }
  const RegressionFit fit = fit_law(parse_law("prod(poly(I,2),poly(amp,1),poly(freq,1))", "test"), "A", x, y);
  const std::vector<double> expected{pI[0], pI[1], pI[2], pa[0], pa[1], pf[0], pf[1]};
  ASSERT_EQ(fit.coefficients.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) EXPECT_NEAR(fit.coefficients[k], expected[k], 1e-7 * std::fabs(expected[k])) << k;
  EXPECT_NEAR(fit.r2, 1.0, 1e-12);
}

TEST(Regression, PowerLawRecoversCoefficients) {
  const auto x = grid("freq", {1.5, 2, 2.5, 3, 3.5, 4, 4.5, 5});
  std::vector<double> y;
  for (const auto& v : x) y.push_back(3.0 * std::pow(v.at("freq"), 1.5) + 2.0);
  const RegressionFit f = fit_law(parse_law("power(freq)", "test"), "a_c0", x, y);
  EXPECT_NEAR(f.coefficients[0], 3.0, 1e-6);
  EXPECT_NEAR(f.coefficients[1], 1.5, 1e-6);
  EXPECT_NEAR(f.coefficients[2], 2.0, 1e-5);
  EXPECT_GT(f.r2, 1 - 1e-12);
}

TEST(Regression, TwoGaussiansRecoverCoefficients) {
  // fdsp eq. 14 with the minus signs restored: 7087 G(4.282, 1.197) + 18520 G(1.783, 3.25), sampled densely.
  std::vector<double> xs;
  for (int i = 0; i <= 30; ++i) xs.push_back(0.5 + 0.25 * i);
  const auto x = grid("freq", xs);
  std::vector<double> y;
  for (double f : xs) {
    const double g1 = (f - 4.282) / 1.197, g2 = (f - 1.783) / 3.25;
    y.push_back(7087 * std::exp(-g1 * g1) + 18520 * std::exp(-g2 * g2));
  }
  const RegressionFit f = fit_law(parse_law("gauss2(freq)", "test"), "a_c1", x, y);
  // Terms ordered by centre: (a1, b1, c1) is the wide one at 1.783.
  const std::vector<double> expected{18520, 1.783, 3.25, 7087, 4.282, 1.197};
  for (std::size_t k = 0; k < expected.size(); ++k) EXPECT_NEAR(f.coefficients[k], expected[k], 1e-5 * expected[k]) << k;
}

TEST(Regression, TooFewObservationsIsAnError) {
  EXPECT_EQ(testing::error_of([] { (void)fit_law(parse_law("poly(phi,3)", "t"), "c_r", grid("phi", {0, 30}), std::vector<double>{1, 2}); }),
            "regression of c_r: 2 observations for 4 coefficients (poly(phi,3))");
  EXPECT_NE(testing::error_of([] {
              (void)fit_law(parse_law("poly(I,1)", "t"), "c0", grid("phi", {0, 30}), std::vector<double>{1, 2});
            }).find("observation 1 has no variable 'I'"),
            std::string::npos);
}

TEST(Regression, MonotoneFamiliesAreRefusedByName) {
  EXPECT_EQ(testing::error_of([] {
              (void)fit_law(parse_law("hill(I,2)", "t"), "c1", grid("I", {0, 0.5, 1, 1.5}), std::vector<double>{1, 2, 3, 4});
            }),
            "regression of c1: 'hill(I,2)' has no regression fit (regressions fit poly, prod of poly, power and gauss2 "
            "laws; fit the others as laws of the model with --laws)");
  EXPECT_NE(testing::error_of([] { check_regression_law(parse_law("prod(poly(I,1),power(freq))", "t"), "c1"); }),
            "no error");
  EXPECT_EQ(testing::error_of([] { check_regression_law(parse_law("prod(poly(I,1),poly(freq,1))", "t"), "c1"); }),
            "no error");
}

// ---- tables on a tiny store ---------------------------------------------------------------------------

/// One part, models mrd.bingham (f_c, c0, f0 in N, N·s/m, N: paper units are SI) twice (two optimizers
/// "a" and "b" for the first), three datasets d0, d1, d2 at I = 0, 1, 2, two splits: "each" (per dataset)
/// and "joint" (d0+d1 fitted together, predicting d2).
constexpr const char* kSpec = R"toml(name = "tiny"
runs = 3
metric = "rmse"
models = ["mrd.bingham", { name = "bingham2", model = "mrd.bingham" }]
[[optimizers]]
label = "a"
name = "pso"
[[optimizers]]
label = "b"
name = "de"
[[datasets]]
name = "grid"
glob = "nowhere/*.csv"
[[splits]]
name = "each"
[[splits]]
name = "joint"
by = "all"
fit = { I = [0, 1] }
predict = { I = 2 }
[[regressions]]
name = "fc"
model = "mrd.bingham"
split = "each"
optimizer = "a"
laws = "f_c=poly(I,1);c0=poly(I,2)"
)toml";

std::array<double, kMetricCount> metrics_with(double rmse) {
  std::array<double, kMetricCount> m{};
  for (int i = 0; i < kMetricCount; ++i) m[i] = 100 + i;
  m[static_cast<int>(Metric::rmse)] = rmse;
  return m;
}

RunRecord run(int r, double value, std::vector<double> params, std::vector<TracePoint> trace = {}) {
  RunRecord x;
  x.run = r;
  x.best_value = value;
  x.metrics = metrics_with(value);
  x.params = std::move(params);
  x.evaluations = trace.empty() ? 100 : trace.back().evaluations;
  x.stop_reason = "iterations";
  x.trace = std::move(trace);
  return x;
}

class TinyStore : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("dampbench_analysis_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    StoreHeader h;
    h.name = "tiny";
    h.spec_hash = "0123456789abcdef";
    h.spec_path = (dir_ / "tiny.toml").string();
    h.dampbench_version = "test";
    h.build_flags = "test";
    h.parts.push_back({"tiny", "Tiny sweep", h.spec_path, kSpec, 1, 3});
    h.models = {{0, "mrd.bingham", "mrd.bingham", "", "", "", {"f_c", "c0", "f0"}},
                {0, "bingham2", "mrd.bingham", "", "", "", {"f_c", "c0", "f0"}}};
    h.optimizers = {{0, "a", "pso", 50, 100, {}}, {0, "b", "de", 50, 100, {}}};
    h.splits = {{0, "each"}, {0, "joint"}};
    for (int d = 0; d < 3; ++d)
      h.datasets.push_back({0, "d" + std::to_string(d), "grid", "d" + std::to_string(d), "", "h", "", 100,
                            {{"I", static_cast<double>(d)}}});
    h.fitsets = {{0, 0, "d0", {0}, {}}, {0, 0, "d1", {1}, {}}, {0, 0, "d2", {2}, {}}, {0, 1, "joint", {0, 1}, {2}}};
    h.groups = 10;
    h.tasks = 30;
    store_path_ = (dir_ / "tiny.sqlite").string();
    Store store = Store::create_or_resume(store_path_, h);

    // Split "each", model 0, optimizer a: per dataset d, best values {1, 2, 3} + d, f_c = 10 + 5 d (best run),
    // c0 = 2 + d², f0 over runs {−1, 0, 1}.
    for (int d = 0; d < 3; ++d) {
      GroupRecord g = group(d, 0, d, 0, 0);
      // Wall times for the runtime table's seconds: 1.5 s at d0, 1 s at d1, none kept at d2.
      if (d == 0) g.wall_time_s = 1.5;
      if (d == 2) g.wall_time_s = 0;
      for (int r = 0; r < 3; ++r)
        g.run_results.push_back(run(r, 1.0 + r + d, {10.0 + 5 * d + 10 * r, 2.0 + d * d, r - 1.0},
                                    {{10, 10.0 + r + d}, {40, 1.0 + r + d}, {100, 1.0 + r + d}}));
      // Identifiability at the best run: f_c not identifiable at d1, c0 at a bound at d2.
      Identifiability id;
      id.samples = 100;
      id.std_error = {0.1 * (d + 1), 0.2, 0.3};
      id.relative_error = {d == 1 ? 2.5 : 0.01, 0.02, 0.03};
      id.correlation = {{1, 0.5, 0}, {0.5, 1, 0}, {0, 0, 1}};
      id.flags = {{}, {}, {}};
      if (d == 1) id.flags[0] = {"not identifiable"};
      if (d == 2) id.flags[1] = {"at bound"};
      g.identifiability = id;
      store.write(g);
    }
    // Optimizer b on d0: values {4, 5, 6}; reaches 1.01 never, so it fails the target of d0 (best known 1).
    GroupRecord b = group(3, 0, 0, 0, 1);
    for (int r = 0; r < 3; ++r) b.run_results.push_back(run(r, 4.0 + r, {1, 2, 3}, {{50, 4.0 + r}, {100, 4.0 + r}}));
    store.write(b);
    // Model 1 (bingham2), optimizer a, on d0: values {0.5, 0.5, 0.5}, reached by half of the budget (converged).
    GroupRecord m1 = group(4, 0, 0, 1, 0);
    for (int r = 0; r < 3; ++r) m1.run_results.push_back(run(r, 0.5, {1, 2, 3}, {{50, 0.5}, {100, 0.5}}));
    store.write(m1);
    // Split "joint": model 0, optimizer a, fitted on d0+d1 (per-dataset rmse 7 and 8 for the best run 1),
    // predicting d2 (rmse 9).
    GroupRecord j = group(5, 1, 0, 0, 0);
    for (int r = 0; r < 3; ++r) j.run_results.push_back(run(r, r == 1 ? 0.25 : 1.0, {1, 2, 3}, {{100, 1.0}}));
    for (int r = 0; r < 3; ++r) {
      j.dataset_metrics.push_back({r, 0, false, metrics_with(r == 1 ? 7 : 70)});
      j.dataset_metrics.push_back({r, 1, false, metrics_with(r == 1 ? 8 : 80)});
      j.dataset_metrics.push_back({r, 2, true, metrics_with(r == 1 ? 9 : 90)});
    }
    store.write(j);
    // A failed group.
    GroupRecord f = group(6, 0, 1, 1, 0);
    f.failed = true;
    f.message = "dataset 'd1' has no operating variable 'I' (needed by the law of c0)";
    store.write(f);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  static GroupRecord group(long long index, int split, int fitset, int model, int optimizer) {
    GroupRecord g;
    g.index = index;
    g.split = split;
    g.fitset = fitset;
    g.model = model;
    g.optimizer = optimizer;
    g.metric = Metric::rmse;
    g.runs = 3;
    g.task_key = 1000 + static_cast<std::uint64_t>(index);
    g.wall_time_s = 1;
    g.candidate_samples = 1e6;
    g.evaluations = 300;
    return g;
  }

  std::vector<Table> tables(const std::string& kind, std::function<void(TableSpec&)> edit = {}) const {
    const Store store = Store::open(store_path_);
    const StoreResults results(store);
    TableSpec t;
    t.kind = kind;
    if (edit) edit(t);
    return make_tables(results, 0, t);
  }

  static const Table& find(const std::vector<Table>& reports, const std::string& id) {
    for (const auto& r : reports)
      if (r.id == id) return r;
    static Table none;
    ADD_FAILURE() << "no table " << id;
    return none;
  }
  static double value(const Table& r, std::size_t row, std::size_t col) {
    EXPECT_LT(row, r.rows.size());
    if (row >= r.rows.size() || col >= r.rows[row].size() || !r.rows[row][col].value) return std::nan("");
    return *r.rows[row][col].value;
  }

  std::filesystem::path dir_;
  std::string store_path_;
};

TEST_F(TinyStore, EveryRegisteredKindMakesItsTablesAndNoOtherNameDoes) {
  // The registry is the one list of kinds: each name it gives makes tables whose ids carry the kind's name (the
  // fvd set numbers its tables instead), and a name it does not give is refused with the list.
  const std::vector<std::string> kinds = table_kinds();
  ASSERT_EQ(kinds.size(), 17u);
  for (const std::string& kind : kinds) {
    std::vector<Table> made;
    EXPECT_NO_THROW(made = tables(kind)) << kind;
    for (const Table& t : made)
      EXPECT_TRUE(kind == "fvd" || t.id.starts_with(kind))
          << kind << " made " << t.id;
  }
  try {
    tables("plots");
    ADD_FAILURE() << "an unregistered kind was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown table kind 'plots' (known: runs, param-stats,"), std::string::npos)
        << e.what();
  }
}

TEST_F(TinyStore, RunStatisticsByHand) {
  const auto all = tables("runs", [](TableSpec& t) { t.splits = {"each"}; });
  // Model 0 with optimizer a: per dataset d the values {1, 2, 3} + d → mean 2 + d, max 3 + d, min 1 + d, std 1.
  const Table& r = find(all, "runs_mrd.bingham_a");
  ASSERT_EQ(r.rows.size(), 3u);
  for (int d = 0; d < 3; ++d) {
    EXPECT_EQ(r.rows[d][0].text, "d" + std::to_string(d));
    EXPECT_DOUBLE_EQ(value(r, d, 1), 2.0 + d);
    EXPECT_DOUBLE_EQ(value(r, d, 2), 3.0 + d);
    EXPECT_DOUBLE_EQ(value(r, d, 3), 1.0 + d);
    EXPECT_DOUBLE_EQ(value(r, d, 4), 1.0);
  }
  const Table& b = find(all, "runs_mrd.bingham_b");
  EXPECT_DOUBLE_EQ(value(b, 0, 1), 5.0);
}

TEST_F(TinyStore, ParameterStatisticsAndVariabilityByHand) {
  const auto ps = tables("param-stats", [](TableSpec& t) { t.splits = {"each"}; t.optimizers = {"a"}; t.models = {"mrd.bingham"}; });
  const Table& p = find(ps, "param-stats_mrd.bingham");
  // Rows: f_c(mean|max|min|std), c0(...), f0(...); columns d0, d1, d2. f_c over runs at d: 10+5d + {0,10,20}.
  EXPECT_EQ(p.rows[0][0].text, "f_c(mean) [N]");
  EXPECT_DOUBLE_EQ(value(p, 0, 1), 20.0);   // mean at d0
  EXPECT_DOUBLE_EQ(value(p, 0, 3), 30.0);   // mean at d2
  EXPECT_DOUBLE_EQ(value(p, 1, 2), 35.0);   // max at d1
  EXPECT_DOUBLE_EQ(value(p, 3, 1), 10.0);   // std
  EXPECT_DOUBLE_EQ(value(p, 8, 1), 0.0);    // f0 over runs {−1, 0, 1}: mean 0, max 1, min −1, std 1
  EXPECT_DOUBLE_EQ(value(p, 10, 1), -1.0);
  EXPECT_DOUBLE_EQ(value(p, 11, 1), 1.0);
  const auto vs = tables("variability", [](TableSpec& t) { t.splits = {"each"}; t.optimizers = {"a"}; t.models = {"mrd.bingham"}; });
  const Table& v = find(vs, "variability_mrd.bingham");
  // f_c means per condition 20, 25, 30: p̄ = 25, Δp̄ = 10, Δp̄/p̄ = 0.4. c0: 2, 3, 6 → 11/3, 4, 12/11.
  EXPECT_DOUBLE_EQ(value(v, 0, 1), 25.0);
  EXPECT_DOUBLE_EQ(value(v, 0, 2), 10.0);
  EXPECT_DOUBLE_EQ(value(v, 0, 3), 0.4);
  EXPECT_DOUBLE_EQ(value(v, 1, 1), 11.0 / 3);
  EXPECT_DOUBLE_EQ(value(v, 1, 3), 4.0 / (11.0 / 3));
  EXPECT_EQ(v.rows[2][3].text, "-");  // f0 mean 0: no ratio
}

TEST_F(TinyStore, IdentifiedParametersAndRanking) {
  const auto ps = tables("params", [](TableSpec& t) { t.splits = {"each"}; t.optimizers = {"a"}; t.models = {"mrd.bingham"}; });
  const Table& p = find(ps, "params_mrd.bingham");
  // Best run is run 0 everywhere: f_c = 10 + 5d, c0 = 2 + d², last row the metric 1 + d.
  EXPECT_EQ(p.columns, (std::vector<std::string>{"Parameter", "unit", "d0", "d1", "d2"}));
  EXPECT_DOUBLE_EQ(value(p, 0, 4), 20.0);
  EXPECT_DOUBLE_EQ(value(p, 1, 4), 6.0);
  EXPECT_DOUBLE_EQ(value(p, 3, 3), 2.0);
  const auto rk = tables("ranking", [](TableSpec& t) { t.splits = {"each"}; });
  const Table& r = find(rk, "ranking");
  // Rows: (mrd.bingham, a), (mrd.bingham, b), (bingham2, a); best per condition and their mean.
  ASSERT_EQ(r.rows.size(), 3u);
  EXPECT_DOUBLE_EQ(value(r, 0, 4), 2.0);      // mean of 1, 2, 3
  EXPECT_DOUBLE_EQ(value(r, 1, 1), 4.0);
  EXPECT_EQ(r.rows[1][2].text, "-");          // b never ran on d1
  EXPECT_DOUBLE_EQ(value(r, 2, 4), 0.5);
}

TEST_F(TinyStore, ErrorsOfJointFitAndPrediction) {
  const auto all = tables("errors", [](TableSpec& t) { t.splits = {"joint"}; });
  const Table& e = find(all, "errors");
  // Best run of the joint group is run 1 (0.25): rmse 7 on d0, 8 on d1 (fitted), 9 on d2 (predicted).
  ASSERT_EQ(e.rows.size(), 4u);
  EXPECT_DOUBLE_EQ(value(e, 0, 1), 7.0);
  EXPECT_DOUBLE_EQ(value(e, 1, 1), 8.0);
  // The joint group's runs end at 1.0, 0.25, 1.0: they disagree, so its values carry the unconverged mark.
  EXPECT_EQ(e.rows[2][1].text, "9*†");
  EXPECT_NE(e.note.find("† not converged"), std::string::npos) << e.note;
  EXPECT_DOUBLE_EQ(value(e, 2, 1), 9.0);
  EXPECT_DOUBLE_EQ(value(e, 3, 1), 8.0);  // mean
  EXPECT_NE(e.note.find("predicted"), std::string::npos);
  // Another shown metric: of_abs is 100 in metrics_with().
  const auto shown = tables("errors", [](TableSpec& t) { t.splits = {"joint"}; t.metric = "of_abs"; t.role = "fit"; });
  EXPECT_EQ(find(shown, "errors").rows.size(), 3u);
  EXPECT_DOUBLE_EQ(value(find(shown, "errors"), 0, 1), 100.0);
  // `where` picks rows, fitted or predicted: only d2 (I = 2), predicted by the joint fit.
  const auto at2 = tables("errors", [](TableSpec& t) {
    t.splits = {"joint"};
    t.where.any.push_back(Condition{{{"I", {2.0}}}, {}});
  });
  ASSERT_EQ(find(at2, "errors").rows.size(), 1u);
  EXPECT_EQ(find(at2, "errors").rows[0][1].text, "9*†");
  // Per-dataset fits: the best run's metric, one column per (model, optimizer).
  const auto each = tables("errors", [](TableSpec& t) { t.splits = {"each"}; });
  const Table& x = find(each, "errors");
  EXPECT_EQ(x.columns.size(), 4u);
  EXPECT_DOUBLE_EQ(value(x, 2, 1), 3.0);
}

TEST_F(TinyStore, HeldOutBesideEachRecordsOwnFit) {
  // The joint group (fitted on d0+d1, predicting d2; best run 1: rmse 7, 8 and 9) beside each record's own fit of
  // mrd.bingham: the lowest best of the single-record groups of that model without laws, over both model entries
  // and both optimizers: d0 min(1, 4, 0.5) = 0.5, d1 2, d2 3. The per-dataset groups fit one record each and
  // predict none, so they get no table.
  const auto all = tables("held-out");
  ASSERT_EQ(all.size(), 1u);
  const Table& h = all[0];
  EXPECT_TRUE(h.id.starts_with("held-out")) << h.id;
  ASSERT_EQ(h.rows.size(), 5u);
  EXPECT_EQ(h.rows[0][0].text, "d0");
  EXPECT_EQ(h.rows[0][1].text, "fitted");
  EXPECT_DOUBLE_EQ(value(h, 0, 2), 7.0);
  EXPECT_DOUBLE_EQ(value(h, 0, 3), 0.5);
  EXPECT_DOUBLE_EQ(value(h, 0, 4), 14.0);
  EXPECT_DOUBLE_EQ(value(h, 1, 4), 4.0);
  // An own fit whose runs disagree carries the unconverged mark: d1's (runs 2, 3, 4), not d0's (0.5 three times).
  EXPECT_EQ(h.rows[0][3].text, "0.5");
  EXPECT_EQ(h.rows[1][3].text, "2†");
  // The fitted mean row: (7 + 8)/2 = 7.5 against (0.5 + 2)/2 = 1.25, the ratio of the means 6 (not the mean ratio 9).
  EXPECT_EQ(h.rows[2][0].text, "mean of 2");
  EXPECT_DOUBLE_EQ(value(h, 2, 2), 7.5);
  EXPECT_DOUBLE_EQ(value(h, 2, 3), 1.25);
  EXPECT_DOUBLE_EQ(value(h, 2, 4), 6.0);
  EXPECT_EQ(h.rows[3][1].text, "held out");
  EXPECT_DOUBLE_EQ(value(h, 3, 4), 3.0);
  EXPECT_NE(h.note.find("Worst fitted: d0 (14)"), std::string::npos) << h.note;
  EXPECT_NE(h.note.find("Worst held out: d2 (3)"), std::string::npos) << h.note;
  // role = predict keeps only the held-out rows.
  const auto predicted = tables("held-out", [](TableSpec& t) { t.role = "predict"; });
  ASSERT_EQ(predicted.size(), 1u);
  ASSERT_EQ(predicted[0].rows.size(), 2u);
  EXPECT_EQ(predicted[0].rows[0][0].text, "d2");
}

TEST_F(TinyStore, RegressionOfPerConditionFits) {
  const auto all = tables("regression");
  const Table& r = find(all, "regression_fc");
  // Laws in name order: c0 = 2 + I² exactly as a quadratic, then f_c = 10 + 5 I exactly (R² 1).
  ASSERT_EQ(r.rows.size(), 5u);
  EXPECT_EQ(r.rows[0][2].text, "c0_I0");
  EXPECT_NEAR(value(r, 0, 3), 2.0, 1e-12);
  EXPECT_NEAR(value(r, 1, 3), 0.0, 1e-12);
  EXPECT_NEAR(value(r, 2, 3), 1.0, 1e-12);
  EXPECT_NEAR(value(r, 0, 4), 1.0, 1e-12);
  EXPECT_EQ(r.rows[3][2].text, "f_c_I0");
  EXPECT_NEAR(value(r, 3, 3), 10.0, 1e-12);
  EXPECT_NEAR(value(r, 4, 3), 5.0, 1e-12);
  // f_c was not identifiable at d1: the law says on how many conditions, the residuals mark the point; a bound
  // (c0 at d2) does not make a parameter undetermined.
  EXPECT_EQ(r.rows[3][6].text, "‡ 1 of 3");
  EXPECT_EQ(r.rows[0][6].text, "none");
  EXPECT_NE(r.note.find("Not identifiable at"), std::string::npos) << r.note;
  const Table& res = find(all, "regression_fc_residuals");
  ASSERT_EQ(res.rows.size(), 3u);
  EXPECT_DOUBLE_EQ(value(res, 2, 1), 6.0);   // observed c0 at I = 2
  EXPECT_DOUBLE_EQ(value(res, 2, 4), 20.0);  // observed f_c at I = 2
  EXPECT_NEAR(value(res, 2, 6), 0.0, 1e-12);
  EXPECT_EQ(res.rows[1][4].text, "15‡");  // observed f_c at I = 1
  EXPECT_EQ(res.rows[2][4].text, "20");
}

TEST_F(TinyStore, ParamsMarkUndeterminedAndBoundParameters) {
  const auto all = tables("params", [](TableSpec& t) {
    t.splits = {"each"};
    t.optimizers = {"a"};
    t.models = {"mrd.bingham"};
  });
  const Table& p = find(all, "params_mrd.bingham");
  // Rows f_c, c0, f0, metric; columns Parameter, unit, d0, d1, d2.
  EXPECT_EQ(p.rows[0][3].text, "15‡");
  EXPECT_EQ(p.rows[0][2].text, "10");
  EXPECT_EQ(p.rows[1][4].text, "6⊥");
  EXPECT_NE(p.note.find("‡ not identifiable"), std::string::npos) << p.note;
  const Table& se = find(all, "params_mrd.bingham_se");
  EXPECT_EQ(se.rows[0][2].text, "250 (not identifiable)");
  EXPECT_DOUBLE_EQ(value(se, 0, 1), 1.0);
  EXPECT_EQ(se.rows[1][3].text, "2 (at bound)");
}

TEST_F(TinyStore, RanksumBootstrapRuntimeFailuresOverview) {
  const auto rs = tables("ranksum", [](TableSpec& t) { t.splits = {"each"}; });
  // d0: optimizer a {1,2,3} vs b {4,5,6}: U = 0, exact p = 0.1; models: bingham {1,2,3} vs bingham2 {.5,.5,.5}.
  const Table& o = find(rs, "ranksum_optimizers");
  ASSERT_EQ(o.rows.size(), 1u);
  EXPECT_DOUBLE_EQ(value(o, 0, 6), 0.0);
  EXPECT_NEAR(value(o, 0, 7), 0.1, 1e-15);
  const Table& m = find(rs, "ranksum_models");
  // bingham2's three 0.5 are tied: normal approximation, U = 9, Var = 4.65, z = (9 − 4.5 − 0.5)/sqrt(4.65).
  EXPECT_DOUBLE_EQ(value(m, 0, 6), 9.0);
  EXPECT_NEAR(value(m, 0, 7), std::erfc(4.0 / std::sqrt(4.65) / std::sqrt(2.0)), 1e-12);

  const auto bs = tables("bootstrap", [](TableSpec& t) { t.splits = {"each"}; t.models = {"bingham2"}; });
  const Table& b = find(bs, "bootstrap_bingham2");
  EXPECT_DOUBLE_EQ(value(b, 0, 1), 0.5);
  EXPECT_DOUBLE_EQ(value(b, 0, 2), 0.5);
  EXPECT_DOUBLE_EQ(value(b, 0, 3), 0.5);

  const auto rt = tables("runtime", [](TableSpec& t) { t.splits = {"each"}; t.models = {"mrd.bingham"}; });
  const Table& r = find(rt, "runtime");
  // d0: best known 1 → target 1.01. Optimizer a: run 0 reaches 1 at 40, runs 1 and 2 never (2, 3):
  // ERT = (40 + 100 + 100)/1 = 240; b never (4, 5, 6): 0/3, ERT inf.
  EXPECT_EQ(r.rows[0][0].text, "d0");
  EXPECT_DOUBLE_EQ(value(r, 0, 2), 1.01);
  EXPECT_EQ(r.columns, (std::vector<std::string>{"Condition", "Model", "target", "a success", "a ERT", "a ERT s",
                                                 "b success", "b ERT", "b ERT s"}));
  EXPECT_EQ(r.rows[0][3].text, "1/3");
  EXPECT_DOUBLE_EQ(value(r, 0, 4), 240.0);
  // Seconds: ERT × the group's wall seconds per evaluation, 240 × 1.5 s / 300 = 1.2 s at d0; at d1 (ERT 240 again,
  // run 0 reaches its best 2 at 40) 240 × 1 s / 300 = 0.8 s; at d2 the group kept no wall time: no seconds.
  EXPECT_DOUBLE_EQ(value(r, 0, 5), 1.2);
  EXPECT_DOUBLE_EQ(value(r, 1, 4), 240.0);
  EXPECT_DOUBLE_EQ(value(r, 1, 5), 0.8);
  EXPECT_DOUBLE_EQ(value(r, 2, 4), 240.0);
  EXPECT_EQ(r.rows[2][5].text, "-");
  EXPECT_EQ(r.rows[0][6].text, "0/3");
  EXPECT_EQ(value(r, 0, 7), kInf);
  EXPECT_EQ(value(r, 0, 8), kInf);  // never at the target: infinite seconds too
  EXPECT_EQ(r.rows[1][6].text, "-");  // b did not run d1
  EXPECT_NE(r.title.find("depend on the machine"), std::string::npos) << r.title;
  // Several splits: each table's title names its split, as its id does.
  const auto both = tables("runtime", [](TableSpec& t) { t.models = {"mrd.bingham"}; });
  EXPECT_TRUE(find(both, "runtime_each").title.starts_with("Split each: Fixed-target runtime")) << find(both, "runtime_each").title;
  EXPECT_TRUE(find(both, "runtime_ecdf_joint").title.starts_with("Split joint: ECDF")) << find(both, "runtime_ecdf_joint").title;
  const Table& e = find(rt, "runtime_ecdf");
  // Budgets from 10 (first trace point) to 100; a solves 3 of 9 (problem, run) pairs (one per condition) by 40.
  EXPECT_DOUBLE_EQ(value(e, 0, 0), 10.0);
  EXPECT_DOUBLE_EQ(value(e, 11, 0), 100.0);
  EXPECT_DOUBLE_EQ(value(e, 11, 1), 3.0 / 9);
  EXPECT_DOUBLE_EQ(value(e, 11, 2), 0.0);

  const auto fl = tables("failures");
  ASSERT_EQ(find(fl, "failures").rows.size(), 1u);
  EXPECT_NE(find(fl, "failures").rows[0][1].text.find("no operating variable 'I'"), std::string::npos);
  const auto ov = tables("overview");
  EXPECT_DOUBLE_EQ(value(find(ov, "overview"), 0, 1), 7.0);   // groups stored
  EXPECT_DOUBLE_EQ(value(find(ov, "overview"), 2, 1), 1.0);   // failed
}

TEST_F(TinyStore, FormatsAndSweepTables) {
  const auto all = tables("runs", [](TableSpec& t) { t.splits = {"each"}; t.optimizers = {"a"}; t.models = {"mrd.bingham"}; });
  ASSERT_EQ(all.size(), 1u);
  const std::string md = format_tables(all, "md");
  EXPECT_NE(md.find("| d1 | 3 | 4 | 2 | 1 | 3 |"), std::string::npos) << md;
  const std::string csv = format_tables(all, "csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "Condition,Mean,Max,Min,Std,Runs,Converged");
  const std::string tex = format_tables(all, "latex");
  EXPECT_NE(tex.find("\\begin{tabular}{lrrrrrr}"), std::string::npos);
  EXPECT_NE(tex.find("\\label{tab:runs\\_mrd.bingham}"), std::string::npos) << tex;
  const auto j = nlohmann::json::parse(format_tables(all, "json"));
  EXPECT_EQ(j.at("tables")[0].at("rows")[1][1].get<double>(), 3.0);
  EXPECT_EQ(j.at("tables")[0].at("rows")[1][0].get<std::string>(), "d1");
  EXPECT_NE(testing::error_of([&] { (void)format_tables(all, "xml"); }).find("expected md, csv, latex or json"), std::string::npos);
  // The sweep's own tables: the default set (fvd), its regression and the failures.
  const Store store = Store::open(store_path_);
  const StoreResults results(store);
  const auto sweep = sweep_tables(results, 0);
  bool regression = false, failures = false;
  for (const auto& r : sweep) {
    regression |= r.id == "regression_fc";
    failures |= r.id == "failures";
  }
  EXPECT_TRUE(regression);
  EXPECT_TRUE(failures);
}

}  // namespace
}  // namespace dampbench::sweep
