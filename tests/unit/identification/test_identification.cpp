// Lockstep repeated runs (engine/identification/identification.cpp): reproducibility for any thread count and batch
// split, and the bookkeeping of each run.
#include "engine/identification/identification.hpp"

#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include "engine/common/error.hpp"
#include "models/registry.hpp"
#include "optimizers/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

struct Problem {
  const Model& model = find_model("fvd.gv_linear_elastic");
  Signals data;
  Problem() {
    Dataset d = testing::two_sine_record(600);
    d.F_N = model.simulate(std::vector<double>{300, 9e5, 0.4, 5e6}, prepare_signals(d));
    // A structural error the model cannot follow, so runs end in different places.
    for (std::size_t k = 0; k < d.F_N.size(); ++k) d.F_N[k] += 2e4 * std::tanh(d.v_m_s[k] / 0.01);
    data = prepare_signals(d);
  }
  Identification run(std::uint64_t seed, int threads, int grain, int runs = 6,
                     Precision search = Precision::float64) const {
    IdentificationSettings s;
    s.runs = runs;
    s.seed = seed;
    s.search_precision = search;
    s.task_key = task_key(model.id(), "two_sine", "pso");
    s.grain_blocks = grain;
    tbb::task_arena arena(threads);
    Identification out;
    arena.execute([&] { out = identify(model, data, default_bounds(model), make_optimizer_factory({"pso", 30, 25}), s); });
    return out;
  }
};

void expect_identical(const Identification& a, const Identification& b) {
  ASSERT_EQ(a.runs.size(), b.runs.size());
  for (std::size_t r = 0; r < a.runs.size(); ++r) {
    EXPECT_EQ(a.runs[r].best_params, b.runs[r].best_params) << "run " << r;
    EXPECT_EQ(a.runs[r].best_value, b.runs[r].best_value);
    EXPECT_EQ(a.runs[r].trace, b.runs[r].trace);
    for (int m = 0; m < kMetricCount; ++m) EXPECT_EQ(a.runs[r].best_metrics[m], b.runs[r].best_metrics[m]);
  }
}

}  // namespace

TEST(Identification, SameSeedSameBitsWithOneAndTwoThreads) {
  const Problem p;
  expect_identical(p.run(3, 1, 1), p.run(3, 2, 1));
}

TEST(Identification, BatchSplitDoesNotChangeResults) {
  const Problem p;
  expect_identical(p.run(3, 2, 1), p.run(3, 2, 4));
}

// --precision mixed: the search runs float32 lanes, with the same bits for any thread count and batch split; what
// a run reports at its best is the float64 evaluation, not the search's float value.
TEST(Identification, MixedPrecisionSearchIsReproducibleAndReportsFloat64Values) {
  const Problem p;
  const Identification mixed = p.run(3, 1, 1, 6, Precision::float32);
  expect_identical(mixed, p.run(3, 2, 4, 6, Precision::float32));
  const BatchEvaluator float64(p.model, p.data);
  bool some_trace_differs = false;
  for (const RunResult& r : mixed.runs) {
    CandidateBatch best(p.model.dim(), 1);
    best.set_candidate(0, r.best_params);
    std::vector<double> value(1);
    float64.evaluate(best, Metric::of_abs, value);
    EXPECT_EQ(r.best_value, value[0]);
    some_trace_differs |= r.trace.back() != r.best_value;  // the search's own value is a float32 lane's
  }
  EXPECT_TRUE(some_trace_differs) << "the search did not run float32 lanes";
}

TEST(Identification, RunsDoNotDependOnHowManyRunsShareTheBatch) {
  const Problem p;
  const auto six = p.run(3, 2, 1, 6), two = p.run(3, 2, 1, 2);
  for (int r = 0; r < 2; ++r) EXPECT_EQ(six.runs[r].best_params, two.runs[r].best_params);
}

TEST(Identification, DifferentSeedsGiveDifferentRuns) {
  const Problem p;
  EXPECT_NE(p.run(3, 2, 1).runs[0].best_params, p.run(4, 2, 1).runs[0].best_params);
}

TEST(Identification, RunBookkeeping) {
  const Problem p;
  const auto id = p.run(3, 2, 1);
  for (const auto& r : id.runs) {
    EXPECT_EQ(r.evaluations, 30 * 25);
    ASSERT_EQ(r.trace.size(), 25u);
    for (std::size_t i = 1; i < r.trace.size(); ++i) EXPECT_LE(r.trace[i], r.trace[i - 1]);
    EXPECT_EQ(r.trace.back(), r.best_value);  // re-evaluated best equals what the optimizer saw
    EXPECT_EQ(r.best_metrics[0], r.best_value);
    EXPECT_GE(r.wall_time_s, 0.0);
  }
  EXPECT_DOUBLE_EQ(id.candidate_samples, 6.0 * 30 * 25 * 600);
  for (const auto& r : id.runs) EXPECT_GE(r.best_value, id.runs[id.best_run()].best_value);
}

TEST(Identification, RejectsBadSettings) {
  const Problem p;
  IdentificationSettings s;
  s.runs = 0;
  EXPECT_THROW(identify(p.model, p.data, default_bounds(p.model), make_optimizer_factory({}), s), InputError);
  Bounds inverted = default_bounds(p.model);
  std::swap(inverted.lower[1], inverted.upper[1]);
  s.runs = 1;
  EXPECT_EQ(testing::error_of([&] { identify(p.model, p.data, inverted, make_optimizer_factory({}), s); }),
            "--bounds C: lower bound 1e+07 is greater than upper bound 0");
}

}  // namespace dampbench
