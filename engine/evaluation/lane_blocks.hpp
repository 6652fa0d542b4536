#pragma once
// How BatchEvaluator cuts a batch into lane blocks. A block runs its dearest lane's sub-steps on every lane
// (engine/kernels/ode_kernel.hpp), so candidates sorted by cost (Model::lane_costs) go into blocks in that
// order, and the block widths are chosen to minimize the batch's time: a wider block (kWideLanes or
// kWidestLanes, for models that run them) takes less time per lane than a kLanes block at the same cost per
// lane, so it pays where its lanes cost alike and not where a costly lane would make many cheap ones wait.
// Widths change the time only: a lane gets the same bits in a block of any width.
#include <array>
#include <span>
#include <vector>

namespace dampbench {

struct LaneBlock {
  int first = 0;  ///< first candidate (in sorted order)
  int count = 0;  ///< candidates in the block (≤ the block's lanes)
};

/// Time of a block of kLanes, kWideLanes and kWidestLanes lanes at the same cost per lane, relative to the first.
using BlockTimes = std::array<double, 3>;

/// A block width a batch may be cut into, and the time of such a block at a given cost per lane.
struct BlockShape {
  int lanes = 0;
  double time = 1;
};

/// Blocks over candidates [0, costs.size()), whose costs are in ascending order, with the least total time: a
/// block takes the cost of its last (dearest) candidate times the time of the narrowest shape that holds it
/// (dynamic programming over the ends of the blocks; the narrower block wins ties). `shapes` ascend in lanes.
std::vector<LaneBlock> cut_lane_blocks(std::span<const double> costs, std::span<const BlockShape> shapes);
/// The float64 shapes: kLanes, kWideLanes and kWidestLanes lanes (those up to `max_lanes`) with `times`.
std::vector<LaneBlock> cut_lane_blocks(std::span<const double> costs, int max_lanes, const BlockTimes& times);

/// The shapes of Model::evaluate_block_float32's blocks up to `max_lanes` (kFloat32LaneScale × the model's
/// max_block_lanes): kLanes float lanes, then kFloat32LaneScale × each float64 width, which holds as many vectors
/// as that float64 block and takes its time (`times`). The narrowest, one vector at avx512, holds the stiffest
/// candidates: a block runs its dearest lane's sub-steps, and one stiff lane can outlast the rest of a batch.
std::vector<BlockShape> float32_block_shapes(int max_lanes, const BlockTimes& times);

/// BlockTimes for the vector level the kernels run with (engine/kernels/isa.hpp), measured on `dampbench
/// bench`'s ODE models.
BlockTimes block_times();

}  // namespace dampbench
