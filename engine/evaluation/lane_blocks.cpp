#include "engine/evaluation/lane_blocks.hpp"

#include <algorithm>

#include "engine/kernels/isa.hpp"
#include "engine/model/batch.hpp"

namespace dampbench {
namespace {
constexpr std::array<int, 3> kWidths{kLanes, kWideLanes, kWidestLanes};  // the float64 widths, those of BlockTimes
}  // namespace

std::vector<LaneBlock> cut_lane_blocks(std::span<const double> costs, int max_lanes, const BlockTimes& times) {
  std::vector<BlockShape> shapes;
  for (std::size_t w = 0; w < kWidths.size() && kWidths[w] <= max_lanes; ++w) shapes.push_back({kWidths[w], times[w]});
  return cut_lane_blocks(costs, shapes);
}

std::vector<BlockShape> float32_block_shapes(int max_lanes, const BlockTimes& times) {
  // One vector instead of two at avx512 (two instead of four at avx2): less independent work per stage, so
  // more than half the time of the next width (docs/performance.md, "Mixed precision").
  constexpr double kNarrowest = 0.6;
  std::vector<BlockShape> shapes{{kLanes, kNarrowest * times[0]}};
  for (std::size_t w = 0; w < kWidths.size() && kFloat32LaneScale * kWidths[w] <= max_lanes; ++w)
    shapes.push_back({kFloat32LaneScale * kWidths[w], times[w]});
  return shapes;
}

std::vector<LaneBlock> cut_lane_blocks(std::span<const double> costs, std::span<const BlockShape> shapes) {
  const int n = static_cast<int>(costs.size());
  // time[i]: least time of candidates [0, i); start[i]: where the last block of that cut starts. time only
  // grows with i, so a block of a given width ending at i best starts as far left as the width allows, and a
  // width pays only for a block the next narrower one cannot hold.
  std::vector<double> time(static_cast<std::size_t>(n) + 1, 0.0);
  std::vector<int> start(static_cast<std::size_t>(n) + 1, 0);
  for (int i = 1; i <= n; ++i) {
    const double dearest = costs[static_cast<std::size_t>(i) - 1];
    for (std::size_t w = 0; w < shapes.size(); ++w) {
      const int from = std::max(0, i - shapes[w].lanes);
      if (w > 0 && i - from <= shapes[w - 1].lanes) break;
      const double t = time[static_cast<std::size_t>(from)] + shapes[w].time * dearest;
      if (w == 0 || t < time[static_cast<std::size_t>(i)]) {
        time[static_cast<std::size_t>(i)] = t;
        start[static_cast<std::size_t>(i)] = from;
      }
    }
  }
  std::vector<LaneBlock> blocks;
  for (int end = n; end > 0; end = start[static_cast<std::size_t>(end)])
    blocks.push_back({start[static_cast<std::size_t>(end)], end - start[static_cast<std::size_t>(end)]});
  std::ranges::reverse(blocks);
  return blocks;
}

BlockTimes block_times() {
  // A block's time relative to a 16-lane block's, from the 1-thread `bench` rates of Bouc–Wen and Spencer (a
  // batch of equal-cost lanes) with all blocks of one width (docs/performance.md, "Measurements behind code
  // choices"). Wider blocks gain most at avx512 and a little at avx2, where a block of 32 is taken halfway
  // between 16 and 64. At sse2 wider blocks are not used: a block of twice the lanes is taken to take twice the
  // time, so the cut never prefers them.
  constexpr BlockTimes kAvx512{1.0, 1.67, 3.05}, kAvx2{1.0, 1.8, 3.6}, kNoGain{1.0, 2.0, 4.0};
  switch (active_isa()) {
    case Isa::avx512: return kAvx512;
    case Isa::avx2: return kAvx2;
    case Isa::native:
#if defined(__AVX512F__)
      return kAvx512;
#elif defined(__AVX2__)
      return kAvx2;
#else
      return kNoGain;
#endif
    default: return kNoGain;
  }
}

}  // namespace dampbench
