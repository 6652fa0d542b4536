// How BatchEvaluator cuts a sorted batch into lane blocks (engine/evaluation/lane_blocks.hpp): known answers
// worked out by hand from the rule "a block takes its dearest lane's cost times the relative time of the narrowest
// width that holds it; least total time".
#include "engine/evaluation/lane_blocks.hpp"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "engine/model/batch.hpp"

namespace dampbench {
namespace {

using Blocks = std::vector<std::pair<int, int>>;

Blocks cut(const std::vector<double>& costs, int max_lanes, const BlockTimes& times) {
  Blocks out;
  for (const LaneBlock& b : cut_lane_blocks(costs, max_lanes, times)) out.emplace_back(b.first, b.count);
  return out;
}

constexpr BlockTimes kFaster{1.0, 1.67, 3.05}, kNoGain{1.0, 2.0, 4.0};

}  // namespace

static_assert(kLanes == 16 && kWideLanes == 32 && kWidestLanes == 64,
              "the known answers below are worked out for blocks of 16, 32 and 64 lanes");

TEST(LaneBlocks, EqualCostsGoIntoWiderBlocksWhereTheyAreFaster) {
  // 64 alike: one block of 64 takes 3.05, two of 32 3.34, four of 16 4.
  EXPECT_EQ(cut(std::vector<double>(64, 1.0), kWidestLanes, kFaster), (Blocks{{0, 64}}));
  // 128 alike: two of 64 (6.1) beat four of 32 (6.68).
  EXPECT_EQ(cut(std::vector<double>(128, 1.0), kWidestLanes, kFaster), (Blocks{{0, 64}, {64, 64}}));
  // Where a wider block takes as long as narrow ones it never pays (ties go to the narrower).
  EXPECT_EQ(cut(std::vector<double>(64, 1.0), kWidestLanes, kNoGain), (Blocks{{0, 16}, {16, 16}, {32, 16}, {48, 16}}));
  // A model without wider blocks.
  EXPECT_EQ(cut(std::vector<double>(40, 1.0), kLanes, kFaster), (Blocks{{0, 8}, {8, 16}, {24, 16}}));
  // 50 alike: 50 in a block of 64 (3.05) beat 18 + 32 in two of 32 (3.34); without the widest, those two beat
  // 2 + 16 + 32 (1 + 1 + 1.67 = 3.67) and four of 16 (4).
  EXPECT_EQ(cut(std::vector<double>(50, 1.0), kWidestLanes, kFaster), (Blocks{{0, 50}}));
  EXPECT_EQ(cut(std::vector<double>(50, 1.0), kWideLanes, kFaster), (Blocks{{0, 18}, {18, 32}}));
  // 16 or fewer: one narrow block.
  EXPECT_EQ(cut(std::vector<double>(7, 3.0), kWidestLanes, kFaster), (Blocks{{0, 7}}));
  EXPECT_TRUE(cut({}, kWidestLanes, kFaster).empty());
}

TEST(LaneBlocks, ACostlyLaneDoesNotMakeCheapOnesWait) {
  std::vector<double> costs(32, 1.0);
  for (int i = 16; i < 32; ++i) costs[i] = 100.0;
  // Two narrow blocks: 1 + 100; one of 32: 1.67 × 100.
  EXPECT_EQ(cut(costs, kWidestLanes, kFaster), (Blocks{{0, 16}, {16, 16}}));
  // Costs close to each other: 10 + 11 = 21 narrow, 1.67 × 11 = 18.37 in one block.
  for (int i = 0; i < 32; ++i) costs[i] = i < 16 ? 10.0 : 11.0;
  EXPECT_EQ(cut(costs, kWidestLanes, kFaster), (Blocks{{0, 32}}));
  // 16 cheap, 32 dear: a narrow block of the cheap and a block of 32 of the dear (1 + 1.67 × 9 = 16.03) beat one of
  // 48 in 64 lanes (3.05 × 9 = 27.45), one of 32 over cheap and dear plus a narrow one (1.67 × 9 + 9 = 24.03) and
  // three narrow ones (1 + 9 + 9 = 19).
  costs.assign(48, 9.0);
  for (int i = 0; i < 16; ++i) costs[i] = 1.0;
  EXPECT_EQ(cut(costs, kWidestLanes, kFaster), (Blocks{{0, 16}, {16, 32}}));
}

}  // namespace dampbench
