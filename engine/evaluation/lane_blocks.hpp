#pragma once
// How BatchEvaluator cuts a batch into lane blocks. A block runs its dearest lane's sub-steps on every lane
// (engine/kernels/ode_kernel.hpp), so candidates sorted by cost (Model::lane_costs) go into blocks in that
// order, and the block widths are chosen to minimize the batch's time: a wide block (kWideLanes, for models
// that run them) takes `wide_time` times a kLanes block's time at the same cost per lane, so it pays where its
// lanes cost alike and not where a costly lane would make many cheap ones wait. Widths change the time only:
// a lane gets the same bits in a block of either width.
#include <span>
#include <vector>

namespace dampbench {

struct LaneBlock {
  int first = 0;  ///< first candidate (in sorted order)
  int count = 0;  ///< candidates in the block (≤ the block's lanes)
};

/// Blocks of up to `max_lanes` candidates (kLanes or kWideLanes) over candidates [0, costs.size()), whose costs
/// are in ascending order, with the least total time: a block of up to kLanes candidates takes the cost of its
/// last (dearest) one, a block of more takes `wide_time` times that (dynamic programming over the ends of the
/// blocks; the leftmost cut wins ties, so equal costs give the same blocks on every machine).
std::vector<LaneBlock> cut_lane_blocks(std::span<const double> costs, int max_lanes, double wide_time);

/// Time of a kWideLanes block relative to a kLanes block at the same cost per lane, for the vector level the
/// kernels run with (engine/kernels/isa.hpp), measured on `dampbench bench`'s ODE models.
double wide_block_time();

}  // namespace dampbench
