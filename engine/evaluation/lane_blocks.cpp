#include "engine/evaluation/lane_blocks.hpp"

#include <algorithm>

#include "engine/kernels/isa.hpp"
#include "engine/model/batch.hpp"

namespace dampbench {

std::vector<LaneBlock> cut_lane_blocks(std::span<const double> costs, int max_lanes, double wide_time) {
  const int n = static_cast<int>(costs.size());
  // time[i]: least time of candidates [0, i); start[i]: where the last block of that cut starts. time only
  // grows with i, so a block ending at i best starts as far left as its width allows.
  std::vector<double> time(static_cast<std::size_t>(n) + 1, 0.0);
  std::vector<int> start(static_cast<std::size_t>(n) + 1, 0);
  for (int i = 1; i <= n; ++i) {
    const double dearest = costs[static_cast<std::size_t>(i) - 1];
    const int narrow = std::max(0, i - kLanes), wide = std::max(0, i - max_lanes);
    time[i] = time[narrow] + dearest;
    start[i] = narrow;
    if (i - wide > kLanes && time[wide] + wide_time * dearest < time[i]) {
      time[i] = time[wide] + wide_time * dearest;
      start[i] = wide;
    }
  }
  std::vector<LaneBlock> blocks;
  for (int end = n; end > 0; end = start[end]) blocks.push_back({start[end], end - start[end]});
  std::ranges::reverse(blocks);
  return blocks;
}

double wide_block_time() {
  // Measured with kLanes = 16 and kWideLanes = 32 on the Bouc–Wen and Spencer `bench` workload, one thread (a
  // block of equal lanes): Zen 5 at avx512 1.67 (both models). At a level where wide blocks gain nothing, 2
  // keeps every block at kLanes (a wide block is never strictly cheaper than two narrow ones).
  switch (active_isa()) {
    case Isa::avx512: return 1.67;
    case Isa::native:
#if defined(__AVX512F__)
      return 1.67;
#else
      return 2.0;
#endif
    default: return 2.0;
  }
}

}  // namespace dampbench
