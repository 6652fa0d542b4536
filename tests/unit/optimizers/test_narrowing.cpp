// Bound narrowing over conditions (optimizers/narrowing/narrowing.hpp, mfm §5.1).
#include "optimizers/narrowing/narrowing.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/record/excitation.hpp"
#include "engine/model/law_model.hpp"
#include "models/fixtures.hpp"
#include "models/registry.hpp"
#include "tests/optimizer_test_support.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

/// F = a·x + b·v, except on a dataset named "broken", where every candidate blows up (NaN force), as an ODE
/// model does for every candidate of a hopeless box.
class LinearTestModel final : public Model {
 public:
  [[nodiscard]] std::string_view id() const override { return "test.linear"; }
  [[nodiscard]] std::string_view citation() const override { return "test"; }
  [[nodiscard]] std::string_view law() const override { return "F = a x + b v"; }
  [[nodiscard]] std::span<const ParameterInfo> parameters() const override { return params_; }
  void evaluate_block(const CandidateBatch& batch, int first, int count, const Signals& data, SumSet /*wanted*/,
                      MetricSums* out) const override {
    for (int i = 0; i < count; ++i) {
      MetricSums s;
      const std::vector<double> F = simulate(batch.candidate(first + i), data);
      for (std::size_t k = 0; k < F.size(); ++k) {
        const double e = data.F_N[k] - F[k];
        s.abs_weighted += data.w_trapz_s[k] * std::abs(e);
        s.sq_weighted += data.w_trapz_s[k] * e * e;
        s.abs += std::abs(e);
        s.sq += e * e;
      }
      out[i] = s;
    }
  }
  [[nodiscard]] std::vector<double> simulate(std::span<const double> p, const Signals& data) const override {
    std::vector<double> F(data.size());
    for (std::size_t k = 0; k < F.size(); ++k)
      F[k] = data.name == "broken" ? std::nan("") : p[0] * data.x_m[k] + p[1] * data.v_m_s[k];
    return F;
  }

 private:
  std::vector<ParameterInfo> params_{{"a", "N/m", 0, 10, "N/m"}, {"b", "N*s/m", 0, 10, "N*s/m"}};
};

Signals linear_record(const std::string& name, double a, double b) {
  Dataset d = make_sine({0.01, 1.0, 0, 1.0, 50});
  d.name = name;
  for (std::size_t k = 0; k < d.t_s.size(); ++k) d.F_N.push_back(a * d.x_m[k] + b * d.v_m_s[k]);
  return prepare_signals(d);
}

IdentificationSettings narrowing_settings(int runs) {
  IdentificationSettings s;
  s.runs = runs;
  s.seed = 4;
  s.metric = Metric::nrmse;
  return s;
}

void expect_sane(const Bounds& b) {
  for (int j = 0; j < b.dim(); ++j) {
    EXPECT_TRUE(std::isfinite(b.lower[j]) && std::isfinite(b.upper[j])) << "parameter " << j;
    EXPECT_LE(b.lower[j], b.upper[j]) << "parameter " << j;
  }
}

}  // namespace

// ---- the procedure -----------------------------------------------------------------------------------

TEST(Narrowing, BoundsBecomeMinAndMaxOverTheConditions) {
  const LinearTestModel model;
  const Signals c1 = linear_record("c1", 2, 3), c2 = linear_record("c2", 4, 1), c3 = linear_record("c3", 3, 2);
  const auto r = narrow_bounds(model, {&c1, &c2, &c3}, default_bounds(model), {"ga-lm", 12, 5}, 2, narrowing_settings(2));
  ASSERT_EQ(r.rounds.size(), 2u);
  EXPECT_TRUE(r.completed());
  EXPECT_EQ(r.rounds[0].bounds.lower, default_bounds(model).lower);
  for (const NarrowingRound& round : r.rounds) {
    ASSERT_EQ(round.conditions.size(), 3u);
    for (int j = 0; j < 2; ++j) {
      double lo = INFINITY, hi = -INFINITY;
      for (const auto& c : round.conditions) {
        lo = std::min(lo, c.best_params[j]);
        hi = std::max(hi, c.best_params[j]);
        EXPECT_GE(c.best_params[j], round.bounds.lower[j]);
        EXPECT_LE(c.best_params[j], round.bounds.upper[j]);
      }
      EXPECT_EQ(round.next.lower[j], lo);
      EXPECT_EQ(round.next.upper[j], hi);
    }
  }
  EXPECT_EQ(r.rounds[1].bounds.lower, r.rounds[0].next.lower);
  EXPECT_EQ(r.rounds[1].bounds.upper, r.rounds[0].next.upper);
  EXPECT_EQ(r.final_bounds.lower, r.rounds[1].next.lower);
  // A linear least-squares fit per condition: a ∈ [2, 4], b ∈ [1, 3] exactly (to LM precision).
  EXPECT_NEAR(r.final_bounds.lower[0], 2, 1e-8);
  EXPECT_NEAR(r.final_bounds.upper[0], 4, 1e-8);
  EXPECT_NEAR(r.final_bounds.lower[1], 1, 1e-8);
  EXPECT_NEAR(r.final_bounds.upper[1], 3, 1e-8);
}

TEST(Narrowing, AFailedConditionIsReportedAndLeftOut) {
  const LinearTestModel model;
  const Signals c1 = linear_record("c1", 2, 3), broken = linear_record("broken", 1, 1), c2 = linear_record("c2", 4, 1);
  const auto r = narrow_bounds(model, {&c1, &broken, &c2}, default_bounds(model), {"ga-lm", 12, 5}, 2, narrowing_settings(2));
  ASSERT_EQ(r.rounds.size(), 2u);
  for (const NarrowingRound& round : r.rounds) {
    EXPECT_EQ(round.failed_conditions, 1);
    EXPECT_TRUE(round.conditions[1].failed);
    EXPECT_EQ(round.conditions[1].name, "broken");
    EXPECT_EQ(round.conditions[1].finite_runs, 0);
    EXPECT_EQ(round.conditions[1].best_value, INFINITY);
    EXPECT_TRUE(round.conditions[1].best_params.empty());
    EXPECT_FALSE(round.conditions[0].failed);
    expect_sane(round.next);
  }
  EXPECT_NEAR(r.final_bounds.lower[0], 2, 1e-8);
  EXPECT_NEAR(r.final_bounds.upper[0], 4, 1e-8);
}

TEST(Narrowing, ARoundWhereEveryConditionFailsStopsWithTheBoundsKept) {
  const LinearTestModel model;
  const Signals broken = linear_record("broken", 1, 1);
  const Bounds start = default_bounds(model);
  const auto r = narrow_bounds(model, {&broken, &broken}, start, {"ga", 8, 3}, 4, narrowing_settings(2));
  ASSERT_EQ(r.rounds.size(), 1u);
  EXPECT_FALSE(r.completed());
  EXPECT_EQ(r.stop_reason, "round 1: every condition failed (all runs +inf); bounds kept");
  EXPECT_EQ(r.rounds[0].failed_conditions, 2);
  EXPECT_EQ(r.final_bounds.lower, start.lower);
  EXPECT_EQ(r.final_bounds.upper, start.upper);
}

TEST(Narrowing, PaperStartOfPlusMinus1e8NeitherCrashesNorStalls) {
  // mfm §5.1 starts every Spencer parameter at [−1e8, 1e8]; nearly every candidate there blows up (masked as
  // +inf by the kernels). Whatever the GA finds, the procedure must end, with finite ordered bounds.
  const Model& model = find_model("mrd.spencer");
  const FixtureModel fx = make_fixture_model(find_fixture("mfm.table3"));
  std::vector<Signals> signals;
  for (double I : {0.5, 2.5}) {
    Dataset d = make_sine({0.01, 1.0, 0, 1.0, 100});
    d.operating = {{"I", I}};
    d.F_N = model.simulate(fx.model->base_parameters(fx.coefficients, prepare_signals(d)), prepare_signals(d));
    signals.push_back(prepare_signals(d));
  }
  const auto t0 = std::chrono::steady_clock::now();
  const auto r = narrow_bounds(model, {&signals[0], &signals[1]}, wide_bounds(model), {"ga", 16, 4}, 3, narrowing_settings(1));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 30.0);
  ASSERT_FALSE(r.rounds.empty());
  EXPECT_EQ(r.rounds[0].bounds.lower, std::vector<double>(10, -1e8));
  for (const NarrowingRound& round : r.rounds) {
    expect_sane(round.next);
    for (const auto& c : round.conditions) {
      EXPECT_FALSE(std::isnan(c.best_value));
      EXPECT_EQ(c.failed, !std::isfinite(c.best_value));
      EXPECT_EQ(c.failed, c.best_params.empty());
    }
  }
  expect_sane(r.final_bounds);
  if (!r.completed()) {
    EXPECT_EQ(r.final_bounds.lower, r.rounds.back().bounds.lower);
  }
}

// ---- the mfm pairing: mrd.spencer over currents of the Table 3 laws -------------------------------------

TEST(Narrowing, RecoversSpencerParametersOverThreeCurrents) {
  // Noise-free records at I = 0.5, 1.5, 2.5 A (Amp 0.01 m, 1 Hz, one cycle) from mfm Table 3. Start: a box
  // from a third of the smallest to three times the largest true value of each parameter (n in [0.5, 1.5]).
  // Inner optimizer ga-lm, two rounds.
  const Model& model = find_model("mrd.spencer");
  const FixtureModel fx = make_fixture_model(find_fixture("mfm.table3"));
  std::vector<Signals> signals;
  std::vector<std::vector<double>> truth;
  for (double I : {0.5, 1.5, 2.5}) {
    Dataset d = make_sine({0.01, 1.0, 0, 1.0, 100});
    d.name = fmt::format("I{:g}", I);
    d.operating = {{"I", I}};
    truth.push_back(fx.model->base_parameters(fx.coefficients, prepare_signals(d)));
    d.F_N = model.simulate(truth.back(), prepare_signals(d));
    signals.push_back(prepare_signals(d));
  }
  Bounds start = default_bounds(model);
  for (int j = 0; j < model.dim(); ++j) {
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& t : truth) {
      lo = std::min(lo, t[j]);
      hi = std::max(hi, t[j]);
    }
    start.lower[j] = lo > 0 ? lo / 3 : 3 * lo;
    start.upper[j] = lo > 0 ? 3 * hi : -lo;
  }
  start.lower[9] = 0.5;
  start.upper[9] = 1.5;

  const auto r = narrow_bounds(model, {&signals[0], &signals[1], &signals[2]}, start,
                               {"ga-lm", 30, 20}, 2, narrowing_settings(1));
  ASSERT_TRUE(r.completed());
  const auto index = [&](const char* name) { return model.parameter_index(name); };
  const int alpha = index("alpha"), A = index("A"), beta = index("beta"), gamma = index("gamma"), n = index("n");
  for (std::size_t c = 0; c < 3; ++c) {
    const NarrowingCondition& cond = r.rounds.back().conditions[c];
    const std::vector<double>& p = cond.best_params;
    const std::vector<double>& t = truth[c];
    EXPECT_LT(cond.best_value, 1e-10) << cond.name;
    for (const char* name : {"c0", "c1", "k0", "k1", "x0", "n"})
      EXPECT_NEAR(p[index(name)], t[index(name)], 1e-6 * std::abs(t[index(name)])) << cond.name << " " << name;
    // Bouc–Wen's scaling z → s·z maps (α, A, β, γ) to (α·s, A/s, β·s^(n−1), γ·s^(n−1)) with the same force
    // (Ma et al. 2004): α·A and β·A^(n−1), γ·A^(n−1) are what the data fix, not α and A one by one.
    EXPECT_NEAR(p[alpha] * p[A], t[alpha] * t[A], 1e-5 * t[alpha] * t[A]) << cond.name;
    EXPECT_NEAR(p[beta] * std::pow(p[A], p[n] - 1), t[beta] * std::pow(t[A], t[n] - 1), 1e-5 * t[beta]) << cond.name;
    EXPECT_NEAR(p[gamma] * std::pow(p[A], p[n] - 1), t[gamma] * std::pow(t[A], t[n] - 1), 1e-5 * t[gamma]) << cond.name;
  }
  // The current-dependent damping spans the conditions' values; the constants collapse to a point.
  EXPECT_NEAR(r.final_bounds.lower[index("c0")], truth[0][index("c0")], 1e-6 * truth[0][index("c0")]);
  EXPECT_NEAR(r.final_bounds.upper[index("c0")], truth[2][index("c0")], 1e-6 * truth[2][index("c0")]);
  for (const char* name : {"k1", "x0", "n"})
    EXPECT_LT(r.final_bounds.upper[index(name)] - r.final_bounds.lower[index(name)], 1e-6 * std::abs(truth[0][index(name)]))
        << name;
}

// ---- reproducibility and bad input -------------------------------------------------------------------

TEST(Narrowing, SameBitsWithOneAndTwoThreads) {
  const LinearTestModel model;
  const Signals c1 = linear_record("c1", 2, 3), c2 = linear_record("c2", 4, 1);
  const auto run = [&](int threads, int grain, const char* inner) {
    IdentificationSettings s = narrowing_settings(3);
    s.grain_blocks = grain;
    tbb::task_arena arena(threads);
    NarrowingResult out;
    arena.execute([&] { out = narrow_bounds(model, {&c1, &c2}, default_bounds(model), {inner, 20, 4}, 2, s); });
    return out;
  };
  for (const char* inner : {"ga", "ga-lm"}) {
    SCOPED_TRACE(inner);
    const auto a = run(1, 1, inner), b = run(2, 1, inner), c = run(2, 3, inner);
    for (const auto* other : {&b, &c}) {
      EXPECT_EQ(a.final_bounds.lower, other->final_bounds.lower);
      EXPECT_EQ(a.final_bounds.upper, other->final_bounds.upper);
      for (std::size_t k = 0; k < a.rounds.size(); ++k)
        for (std::size_t i = 0; i < 2; ++i)
          EXPECT_EQ(a.rounds[k].conditions[i].best_params, other->rounds[k].conditions[i].best_params);
    }
  }
  const auto a = run(2, 1, "ga");
  // Each (round, condition) has its own runs: the two conditions' GA searches differ.
  EXPECT_NE(a.rounds[0].conditions[0].best_params, a.rounds[1].conditions[0].best_params);
}

TEST(Narrowing, RejectsBadInput) {
  const LinearTestModel model;
  const Signals c1 = linear_record("c1", 2, 3);
  const Bounds b = default_bounds(model);
  const IdentificationSettings s = narrowing_settings(1);
  EXPECT_EQ(testing::error_of([&] { narrow_bounds(model, {&c1}, b, {"ga", 8, 2}, 0, s); }),
            "narrow: rounds must be at least 1, got 0");
  EXPECT_EQ(testing::error_of([&] { narrow_bounds(model, {}, b, {"ga", 8, 2}, 1, s); }),
            "narrow: give at least one condition (dataset)");
  EXPECT_EQ(testing::error_of([&] { narrow_bounds(model, {&c1, nullptr}, b, {"ga", 8, 2}, 1, s); }),
            "narrow: a condition is missing (null dataset)");
  EXPECT_EQ(testing::error_of([&] { narrow_bounds(model, {&c1}, b, {"ga", 2, 2}, 1, s); }),
            "ga: population must be at least 4, got 2");
  EXPECT_EQ(testing::error_of([&] { narrow_bounds(model, {&c1}, Bounds{{5, 0}, {1, 1}}, {"ga", 8, 2}, 1, s); }),
            "--bounds a: lower bound 5 is greater than upper bound 1");
}

}  // namespace dampbench
