#include "engine/batch_evaluator.hpp"

#include <algorithm>
#include <cassert>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

namespace dampbench {

BatchEvaluator::BatchEvaluator(const Model& model, const Signals& data, int grain_blocks)
    : model_(model), data_(data), grain_blocks_(std::max(1, grain_blocks)) {}

void BatchEvaluator::evaluate_sums(const CandidateBatch& batch, std::span<MetricSums> out) const {
  assert(static_cast<int>(out.size()) == batch.count() && batch.dim() == model_.dim());
  const int blocks = (batch.count() + kLanes - 1) / kLanes;
  tbb::parallel_for(
      tbb::blocked_range<int>(0, blocks, grain_blocks_),
      [&](const tbb::blocked_range<int>& range) {
        for (int b = range.begin(); b < range.end(); ++b) {
          const int first = b * kLanes;
          const int count = std::min(kLanes, batch.count() - first);
          model_.evaluate_block(batch, first, count, data_, out.data() + first);
        }
      },
      tbb::simple_partitioner());
}

void BatchEvaluator::evaluate(const CandidateBatch& batch, Metric metric, std::span<double> out) const {
  std::vector<MetricSums> sums(batch.count());
  evaluate_sums(batch, sums);
  for (int i = 0; i < batch.count(); ++i) out[i] = finish_metric(metric, sums[i], data_);
}

}  // namespace dampbench
