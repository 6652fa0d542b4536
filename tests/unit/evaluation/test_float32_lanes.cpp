// Single-precision lanes (engine/kernels/lane_kernel.hpp, Float32; `--precision mixed`): every model that has them
// computes forces within float rounding of its float64 lanes and never equal to them bit for bit (they are float
// lanes); a batch gives the same bits for any thread count, batch split or block width; models without them
// run float64; the stiffest candidates get the narrowest block. The CVODE bound in float32 lanes is checked in
// tests/unit/kernels/test_ode_stiff_lanes.cpp.
#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <algorithm>
#include <string>
#include <vector>

#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/evaluation/bench_workload.hpp"
#include "engine/evaluation/lane_blocks.hpp"
#include "models/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

std::vector<double> candidate(const CandidateBatch& batch, int i) {
  std::vector<double> p(batch.dim());
  for (int j = 0; j < batch.dim(); ++j) p[j] = batch.at(i, j);
  return p;
}

std::vector<double> evaluate(const Model& model, const Signals& data, const CandidateBatch& batch, int threads,
                             int grain, Precision precision) {
  std::vector<double> out(batch.count());
  tbb::task_arena arena(threads);
  arena.execute([&] { BatchEvaluator(model, data, grain, precision).evaluate(batch, Metric::of_abs, out); });
  return out;
}

}  // namespace

TEST(Float32Lanes, TheModelsThatHaveThemAreFloatWithinFloatRoundingOfFloat64) {
  int with = 0;
  for (const Model* model : all_models()) {
    if (!model->has_float32_lanes()) continue;
    ++with;
    const Signals data = bench_record(*model, 1025, 1.0, 512);
    const CandidateBatch batch = bench_candidates(*model, 3, 5);
    for (int i = 0; i < batch.count(); ++i) {
      const auto p = candidate(batch, i);
      const double d = testing::relative_l2(model->simulate_float32(p, data), model->simulate(p, data));
      EXPECT_GT(d, 1e-10) << model->id() << ": the float32 lanes gave the float64 forces";
      EXPECT_LT(d, 1e-5) << model->id() << " candidate " << i;
    }
  }
  // fvd's four laws (algebraic, one exp) and the MR Bouc–Wen and Spencer (ODE, chained powers)
  EXPECT_GE(with, 6);
}

TEST(Float32Lanes, SameBitsForAnyThreadCountBatchSplitAndBlockWidth) {
  for (const char* id : {"fvd.gv_linear_elastic", "mrd.spencer"}) {
    const Model& model = find_model(id);
    const Signals data = bench_record(model, 1025, 1.0, 512);
    const CandidateBatch batch = bench_candidates(model, 150, 9);  // blocks of 16, 32, 64 and 128 lanes
    const auto one = evaluate(model, data, batch, 1, 1, Precision::float32);
    EXPECT_EQ(one, evaluate(model, data, batch, 2, 3, Precision::float32)) << id;
    // each candidate alone: a block of one candidate, the narrowest width
    for (int i = 0; i < batch.count(); i += 37) {
      CandidateBatch alone(model.dim(), 1);
      alone.set_candidate(0, candidate(batch, i));
      EXPECT_EQ(evaluate(model, data, alone, 1, 1, Precision::float32)[0], one[static_cast<std::size_t>(i)]) << id;
    }
    EXPECT_NE(one, evaluate(model, data, batch, 1, 1, Precision::float64)) << id << ": float32 lanes not used";
  }
}

TEST(Float32Lanes, ModelsWithoutThemRunFloat64) {
  const Model& model = find_model("mrd.magic_formula");
  ASSERT_FALSE(model.has_float32_lanes());
  const Signals data = bench_record(model, 1025, 1.0, 512);
  const CandidateBatch batch = bench_candidates(model, 40, 9);
  EXPECT_EQ(evaluate(model, data, batch, 2, 1, Precision::float32), evaluate(model, data, batch, 2, 1, Precision::float64));
}

// A block runs its dearest lane's sub-steps: one stiff candidate among many mild ones gets a block of the narrowest
// float32 width (one vector at avx512), and the mild ones blocks wider than any float64 block.
TEST(Float32Lanes, TheStiffestCandidateGetsTheNarrowestBlock) {
  constexpr BlockTimes kTimes{1.0, 1.67, 3.05};
  const auto shapes = float32_block_shapes(kFloat32LaneScale * kWidestLanes, kTimes);
  ASSERT_EQ(shapes.size(), 4u);
  EXPECT_EQ(shapes.front().lanes, kLanes);
  EXPECT_EQ(shapes.back().lanes, kFloat32LaneScale * kWidestLanes);
  std::vector<double> costs(255, 1.0);
  costs.push_back(100.0);
  const auto blocks = cut_lane_blocks(costs, shapes);
  EXPECT_LE(blocks.back().count, kLanes);
  EXPECT_EQ(blocks.back().first + blocks.back().count, 256);
  int widest = 0;
  for (const LaneBlock& b : blocks) widest = std::max(widest, b.count);
  EXPECT_GT(widest, kWidestLanes);
  // algebraic models (blocks of kLanes in float64): float32 blocks of kLanes and 2 kLanes
  EXPECT_EQ(float32_block_shapes(kFloat32LaneScale * kLanes, kTimes).size(), 2u);
}

}  // namespace dampbench
