// How BatchEvaluator cuts a sorted batch into lane blocks (engine/evaluation/lane_blocks.hpp): known answers
// worked out by hand from the rule "a block of up to kLanes candidates takes its dearest lane's cost, a wider
// one wide_time times that; least total time".
#include "engine/evaluation/lane_blocks.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "engine/model/batch.hpp"

namespace dampbench {
namespace {

std::vector<std::pair<int, int>> cut(const std::vector<double>& costs, int max_lanes, double wide_time) {
  std::vector<std::pair<int, int>> out;
  for (const LaneBlock& b : cut_lane_blocks(costs, max_lanes, wide_time)) out.emplace_back(b.first, b.count);
  return out;
}

using Blocks = std::vector<std::pair<int, int>>;

}  // namespace

static_assert(kLanes == 16 && kWideLanes == 32, "the known answers below are worked out for 16 and 32 lanes");

TEST(LaneBlocks, EqualCostsGoIntoWideBlocksWhereTheyAreFaster) {
  // 64 alike: two wide blocks take 2 × 1.67 = 3.34, four narrow ones 4.
  EXPECT_EQ(cut(std::vector<double>(64, 1.0), kWideLanes, 1.67), (Blocks{{0, 32}, {32, 32}}));
  // Where a wide block takes twice a narrow one it never pays.
  EXPECT_EQ(cut(std::vector<double>(64, 1.0), kWideLanes, 2.0), (Blocks{{0, 16}, {16, 16}, {32, 16}, {48, 16}}));
  // A model without wide blocks.
  EXPECT_EQ(cut(std::vector<double>(40, 1.0), kLanes, 1.67), (Blocks{{0, 8}, {8, 16}, {24, 16}}));
  // 50 alike: 18 + 32 in two wide blocks (3.34) beat 2 + 16 + 32 (1 + 1 + 1.67 = 3.67) and four narrow (4).
  EXPECT_EQ(cut(std::vector<double>(50, 1.0), kWideLanes, 1.67), (Blocks{{0, 18}, {18, 32}}));
  // 16 or fewer: one narrow block.
  EXPECT_EQ(cut(std::vector<double>(7, 3.0), kWideLanes, 1.67), (Blocks{{0, 7}}));
  EXPECT_TRUE(cut({}, kWideLanes, 1.67).empty());
}

TEST(LaneBlocks, ACostlyLaneDoesNotMakeCheapOnesWait) {
  std::vector<double> costs(32, 1.0);
  for (int i = 16; i < 32; ++i) costs[i] = 100.0;
  // Two narrow blocks: 1 + 100; one wide block: 1.67 × 100.
  EXPECT_EQ(cut(costs, kWideLanes, 1.67), (Blocks{{0, 16}, {16, 16}}));
  // Costs close to each other: 10 + 11 = 21 narrow, 1.67 × 11 = 18.37 wide.
  for (int i = 0; i < 32; ++i) costs[i] = i < 16 ? 10.0 : 11.0;
  EXPECT_EQ(cut(costs, kWideLanes, 1.67), (Blocks{{0, 32}}));
  // 16 cheap, 32 dear: a narrow block of the cheap and a wide one of the dear (1 + 1.67 × 9 = 16.03) beat a wide
  // block over cheap and dear plus a narrow one (1.67 × 9 + 9 = 24.03) and three narrow ones (1 + 9 + 9 = 19).
  costs.assign(48, 9.0);
  for (int i = 0; i < 16; ++i) costs[i] = 1.0;
  EXPECT_EQ(cut(costs, kWideLanes, 1.67), (Blocks{{0, 16}, {16, 32}}));
}

}  // namespace dampbench
