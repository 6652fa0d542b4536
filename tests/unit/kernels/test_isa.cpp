// Vector levels (engine/kernels/isa.hpp): names, refusal of a level this CPU lacks, the same bits within a
// level for any thread count and batch split, simulate and evaluate seeing the same kernel, and how far the
// levels differ from each other (printed per model; docs/performance.md "Vector levels" quotes it).
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "engine/common/error.hpp"
#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/evaluation/bench_workload.hpp"
#include "engine/kernels/isa.hpp"
#include "models/registry.hpp"

namespace dampbench {
namespace {

/// Restores the level a test started with.
struct KeepIsa {
  Isa saved = active_isa();
  ~KeepIsa() { select_isa(saved); }
};

std::vector<double> metrics(const Model& model, const Signals& data, const CandidateBatch& batch, int grain, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  const BatchEvaluator evaluator(model, {&data}, grain);
  std::vector<double> out(static_cast<std::size_t>(batch.count()));
  evaluator.evaluate(batch, Metric::nrmse, out);
  return out;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

}  // namespace

TEST(Isa, NamesRoundTripAndUnknownNamesAreRefused) {
  for (Isa i : {Isa::sse2, Isa::avx2, Isa::avx512, Isa::native, Isa::generic}) EXPECT_EQ(parse_isa(isa_name(i)), i);
  EXPECT_FALSE(parse_isa("avx1024"));
  KeepIsa keep;
  try {
    select_isa("avx1024", "--isa");
    FAIL() << "an unknown level was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--isa: expected one of"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("got 'avx1024'"), std::string::npos) << e.what();
  }
  EXPECT_EQ(active_isa(), keep.saved);
}

TEST(Isa, ALevelTheCpuLacksIsRefused) {
  KeepIsa keep;
  const auto& have = supported_isas();
  ASSERT_FALSE(have.empty());
  EXPECT_EQ(best_isa(), have.back());
  EXPECT_EQ(active_isa(), best_isa()) << "kernels must start at the CPU's best level";
  for (Isa i : {Isa::sse2, Isa::avx2, Isa::avx512, Isa::native, Isa::generic}) {
    if (std::find(have.begin(), have.end(), i) != have.end()) {
      select_isa(i);
      EXPECT_EQ(active_isa(), i);
    } else {
      EXPECT_THROW(select_isa(i), InputError) << isa_name(i);
    }
  }
  std::printf("vector levels: %s\n", isa_summary().c_str());
}

TEST(Isa, EveryLevelGivesTheSameBitsForAnyThreadCountAndBatchSplit) {
  KeepIsa keep;
  for (const char* id : {"fvd.gv_linear_elastic", "mrd.magic_formula", "mrd.bouc_wen", "mrd.spencer", "mrd.spencer_voltage"}) {
    const Model& model = find_model(id);
    const Signals data = bench_record(model, 513, 1.0, 256.0);
    const CandidateBatch batch = bench_candidates(model, 100, 7);  // 100: a partial last lane block
    for (Isa level : supported_isas()) {
      select_isa(level);
      const auto reference = metrics(model, data, batch, 1, 1);
      EXPECT_TRUE(same_bits(reference, metrics(model, data, batch, 1, 2))) << id << " " << isa_name(level);
      EXPECT_TRUE(same_bits(reference, metrics(model, data, batch, 3, 2))) << id << " " << isa_name(level);
      // Each candidate alone in a block gives the bits it gets among 99 others (the ODE lanes choose per lane
      // between a series and the exact power of the state, and run the exact one for the whole block when any
      // lane needs it: a lane's choice must not depend on its neighbours).
      for (int i = 0; i < batch.count(); ++i) {
        CandidateBatch one(model.dim(), 1);
        one.set_candidate(0, batch.candidate(i));
        EXPECT_EQ(metrics(model, data, one, 1, 1)[0], reference[static_cast<std::size_t>(i)])
            << id << " " << isa_name(level) << " candidate " << i;
      }
    }
  }
}

// simulate (one candidate broadcast to a lane block) and evaluate_block (candidates side by side) run the same kernel:
// a lane's force has the same bits in both, at every level, wherever the lane sits in its block.
TEST(Isa, SimulateAndEvaluateRunTheSameKernelAtEveryLevel) {
  KeepIsa keep;
  for (const char* id : {"fvd.gv_linear_elastic", "mrd.spencer", "mrd.bouc_wen", "mrd.spencer_voltage",
                         "mrd.spencer_freq", "crfd.maxwell"}) {
    const Model& model = find_model(id);
    const Signals data = bench_record(model, 257, 1.0, 128.0);
    const int count = kLanes + 7;  // a full block and a partial one
    const CandidateBatch batch = bench_candidates(model, count, 11);
    for (Isa level : supported_isas()) {
      select_isa(level);
      std::vector<MetricSums> sums(static_cast<std::size_t>(count));
      for (int first = 0; first < count; first += kLanes)
        model.evaluate_block(batch, first, std::min(kLanes, count - first), data, SumSet::every, sums.data() + first);
      for (int i = 0; i < count; ++i) {
        const auto force = model.simulate(batch.candidate(i), data);
        double abs_e = 0;  // the kernel's own accumulation order: sample by sample
        for (std::size_t k = 0; k < data.size(); ++k) abs_e += std::fabs(data.F_N[k] - force[k]);
        EXPECT_EQ(abs_e, sums[static_cast<std::size_t>(i)].abs) << id << " " << isa_name(level) << " candidate " << i;
      }
    }
  }
}

// Models with internal states also run wider blocks (kWideLanes and kWidestLanes lanes; BatchEvaluator chooses the
// widths by the lanes' costs, engine/evaluation/lane_blocks.hpp): a lane must get the same bits in a wider block as
// in a kLanes block, at every level, full or partial, wherever it sits.
TEST(Isa, WideBlocksGiveEachLaneTheBitsOfANarrowBlockAtEveryLevel) {
  KeepIsa keep;
  int wide_models = 0;
  for (const Model* model : all_models()) {
    if (model->max_block_lanes() == kLanes) continue;
    ASSERT_EQ(model->max_block_lanes(), kWidestLanes) << model->id();
    ++wide_models;
    const Signals data = bench_record(*model, 257, 1.0, 128.0);
    const int count = kWidestLanes + kLanes + 3;  // a full block of kWidestLanes, then 19 in one of kWideLanes
    const CandidateBatch batch = bench_candidates(*model, count, 13);
    for (Isa level : supported_isas()) {
      select_isa(level);
      std::vector<MetricSums> wide(static_cast<std::size_t>(count)), narrow(wide.size());
      for (int first = 0; first < count; first += kWidestLanes)
        model->evaluate_block(batch, first, std::min(kWidestLanes, count - first), data, SumSet::every, wide.data() + first);
      for (int first = 0; first < count; first += kLanes)
        model->evaluate_block(batch, first, std::min(kLanes, count - first), data, SumSet::every, narrow.data() + first);
      for (int i = 0; i < count; ++i)
        EXPECT_TRUE(std::memcmp(&wide[static_cast<std::size_t>(i)], &narrow[static_cast<std::size_t>(i)], sizeof(MetricSums)) == 0)
            << model->id() << " " << isa_name(level) << " candidate " << i << ": |e| sum "
            << wide[static_cast<std::size_t>(i)].abs << " wide, " << narrow[static_cast<std::size_t>(i)].abs << " narrow";
    }
  }
  EXPECT_EQ(wide_models, 5) << "Bouc-Wen, Spencer, spencer_voltage, spencer_freq and crfd.maxwell run wider blocks";
}

TEST(Isa, LevelsAgreeToRoundingOnEveryModel) {
  // The levels run the same arithmetic (-ffp-contract=off: no fused multiply-add is introduced) except the
  // vector math functions, whose libmvec variants differ by a few ulp. Every model's bench metrics at every
  // level must agree with the lowest level to 1e-11 relative: about a thousand times the largest difference
  // measured (1.7e-14, mrd.bouc_wen over 2 049 samples, AMD EPYC 2026-11-23; most algebraic models are
  // identical), far below any difference a fit could resolve.
  KeepIsa keep;
  const auto& levels = supported_isas();
  if (levels.size() < 2) GTEST_SKIP() << "one vector level on this machine and build (" << isa_summary() << ")";
  for (const Model* model : all_models()) {
    const Signals data = bench_record(*model, 2049, 1.0, 1024.0);
    const CandidateBatch batch = bench_candidates(*model, 64, 3);
    select_isa(levels.front());
    const auto low = metrics(*model, data, batch, 1, 2);
    for (std::size_t li = 1; li < levels.size(); ++li) {
      select_isa(levels[li]);
      const auto high = metrics(*model, data, batch, 1, 2);
      double worst = 0;
      int identical = 0;
      for (std::size_t i = 0; i < low.size(); ++i) {
        if (!std::isfinite(low[i]) || !std::isfinite(high[i])) {
          EXPECT_EQ(std::isfinite(low[i]), std::isfinite(high[i])) << model->id() << " candidate " << i;
          continue;
        }
        identical += low[i] == high[i];
        worst = std::max(worst, std::fabs(high[i] - low[i]) / std::max(std::fabs(low[i]), 1e-300));
      }
      std::printf("%-28s %s vs %s: worst relative metric difference %.2g, %d of %zu identical\n",
                  std::string(model->id()).c_str(), std::string(isa_name(levels[li])).c_str(),
                  std::string(isa_name(levels.front())).c_str(), worst, identical, low.size());
      EXPECT_LT(worst, 1e-11) << model->id() << " " << isa_name(levels[li]);
    }
  }
}

}  // namespace dampbench
