// The benchmark workload (engine/evaluation/bench_workload.hpp): its candidates stay inside every model's default
// bounds, and none of them blows up, so `dampbench bench` and bench/bench_models time the models' real work
// rather than the masking of failed lanes (in the central half of the default boxes every mrd.spencer
// candidate and half of the mrd.bouc_wen candidates blow up).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/evaluation/bench_workload.hpp"
#include "models/registry.hpp"

namespace dampbench {
namespace {

constexpr int kCandidates = 64;

TEST(BenchWorkload, CandidatesLieInsideTheDefaultBounds) {
  for (const Model* m : all_models()) {
    const Bounds b = default_bounds(*m);
    const CandidateBatch batch = bench_candidates(*m, kCandidates, 7);
    for (int i = 0; i < kCandidates; ++i)
      for (int j = 0; j < m->dim(); ++j) {
        EXPECT_GE(batch.at(i, j), b.lower[j]) << m->id() << " " << m->parameters()[j].name;
        EXPECT_LE(batch.at(i, j), b.upper[j]) << m->id() << " " << m->parameters()[j].name;
      }
  }
}

TEST(BenchWorkload, ReferenceBoxesSpanTwentyPercentAroundThePoint) {
  const Model& spencer = find_model("mrd.spencer");
  const Bounds box = bench_box(spencer);
  const int beta = spencer.parameter_index("beta"), x0 = spencer.parameter_index("x0");
  EXPECT_DOUBLE_EQ(box.lower[beta], 0.8 * 6079);
  EXPECT_DOUBLE_EQ(box.upper[beta], 1.2 * 6079);
  EXPECT_DOUBLE_EQ(box.lower[x0], 1.2 * -0.06678);  // a negative value: the bounds stay ordered
  EXPECT_DOUBLE_EQ(box.upper[x0], 0.8 * -0.06678);
  EXPECT_FALSE(bench_reference_point(find_model("fvd.gv_linear_elastic")).has_value());
}

TEST(BenchWorkload, NoBenchCandidateIsMaskedOnTheBenchRecord) {
  for (const Model* m : all_models()) {
    const Signals data = bench_record(*m, 2049, 1.0, 1024.0);  // the `dampbench bench` record
    const CandidateBatch batch = bench_candidates(*m, kCandidates, 2024);
    std::vector<double> metric(kCandidates);
    BatchEvaluator(*m, data).evaluate(batch, Metric::of_abs, metric);
    int masked = 0;
    for (double v : metric) masked += !std::isfinite(v);
    EXPECT_EQ(masked, 0) << m->id() << ": " << masked << " of " << kCandidates << " bench candidates blow up";
  }
}

}  // namespace
}  // namespace dampbench
