#include "engine/evaluation/batch_evaluator.hpp"

#include <algorithm>
#include <cassert>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "engine/evaluation/lane_blocks.hpp"

namespace dampbench {

BatchEvaluator::BatchEvaluator(const Model& model, const Signals& data, int grain_blocks, Precision precision)
    : BatchEvaluator(model, std::vector<const Signals*>{&data}, grain_blocks, precision) {}

BatchEvaluator::BatchEvaluator(const Model& model, std::vector<const Signals*> datasets, int grain_blocks,
                               Precision precision)
    : model_(model), datasets_(std::move(datasets)), grain_blocks_(std::max(1, grain_blocks)), precision_(precision) {
  assert(!datasets_.empty());
}

double BatchEvaluator::samples() const {
  double n = 0;
  for (const Signals* d : datasets_) n += static_cast<double>(d->size());
  return n;
}

std::vector<MetricSums> BatchEvaluator::sums(const CandidateBatch& batch, SumSet wanted) const {
  assert(batch.dim() == model_.dim());
  const int count = batch.count();
  // Candidates of similar cost side by side (Model::lane_costs, on the first dataset), in blocks whose widths
  // suit their costs (engine/evaluation/lane_blocks.hpp). A lane's bits do not depend on its block-mates.
  // The threads take the costliest blocks first (longest processing time first): a block of stiff candidates can
  // outlast all the others together, and taken last it leaves the other thread idle (docs/performance.md has
  // the gain; the results are the same).
  const bool float32 = precision_ == Precision::float32 && model_.has_float32_lanes();
  std::vector<double> cost(static_cast<std::size_t>(count), 1.0);
  std::vector<int> order;
  CandidateBatch sorted;
  if (count > kLanes && model_.lane_costs(batch, *datasets_.front(), cost)) {
    order.resize(static_cast<std::size_t>(count));
    std::iota(order.begin(), order.end(), 0);
    std::ranges::stable_sort(order, [&](int a, int b) { return cost[a] < cost[b]; });  // costs are never NaN
    sorted.resize(batch.dim(), count);
    for (int i = 0; i < count; ++i)
      for (int j = 0; j < batch.dim(); ++j) sorted.at(i, j) = batch.at(order[i], j);
    std::ranges::sort(cost);
  }
  const CandidateBatch& run = order.empty() ? batch : sorted;
  const std::vector<LaneBlock> blocks =
      float32 ? cut_lane_blocks(cost, float32_block_shapes(kFloat32LaneScale * model_.max_block_lanes(), block_times()))
              : cut_lane_blocks(cost, model_.max_block_lanes(), block_times());
  const int B = static_cast<int>(blocks.size());
  const int tasks = B * static_cast<int>(datasets_.size());
  std::vector<MetricSums> out(datasets_.size() * static_cast<std::size_t>(count));
  tbb::parallel_for(
      tbb::blocked_range<int>(0, tasks, grain_blocks_),
      [&](const tbb::blocked_range<int>& range) {
        for (int task = range.begin(); task < range.end(); ++task) {
          const int d = task / B;
          const int block = order.empty() ? task % B : B - 1 - task % B;  // costliest first
          const LaneBlock& b = blocks[static_cast<std::size_t>(block)];
          MetricSums* block_out = out.data() + static_cast<std::size_t>(d) * count + b.first;
          if (float32)
            model_.evaluate_block_float32(run, b.first, b.count, *datasets_[d], wanted, block_out);
          else
            model_.evaluate_block(run, b.first, b.count, *datasets_[d], wanted, block_out);
        }
      },
      tbb::simple_partitioner());
  if (order.empty()) return out;
  std::vector<MetricSums> unsorted(out.size());
  for (std::size_t d = 0; d < datasets_.size(); ++d)
    for (std::size_t i = 0; i < order.size(); ++i) unsorted[d * order.size() + static_cast<std::size_t>(order[i])] = out[d * order.size() + i];
  return unsorted;
}

void BatchEvaluator::evaluate(const CandidateBatch& batch, Metric metric, std::span<double> out) const {
  const auto s = sums(batch, sum_set_of(metric));
  const int count = batch.count();
  const double D = static_cast<double>(datasets_.size());
  for (int i = 0; i < count; ++i) {
    double total = 0;
    for (std::size_t d = 0; d < datasets_.size(); ++d) total += finish_metric(metric, s[d * count + i], *datasets_[d]);
    out[i] = total / D;
  }
}

void BatchEvaluator::evaluate_all(const CandidateBatch& batch, std::span<MetricRow> out) const {
  const auto s = sums(batch, SumSet::every);
  const int count = batch.count();
  const double D = static_cast<double>(datasets_.size());
  for (int i = 0; i < count; ++i) {
    out[i].fill(0.0);
    for (std::size_t d = 0; d < datasets_.size(); ++d) {
      const MetricRow m = finish_all_metrics(s[d * count + i], *datasets_[d]);
      for (int j = 0; j < kMetricCount; ++j) out[i][j] += m[j];
    }
    for (double& v : out[i]) v /= D;
  }
}

}  // namespace dampbench
