#include "engine/evaluation/batch_evaluator.hpp"

#include <algorithm>
#include <cassert>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

namespace dampbench {

BatchEvaluator::BatchEvaluator(const Model& model, const Signals& data, int grain_blocks)
    : BatchEvaluator(model, std::vector<const Signals*>{&data}, grain_blocks) {}

BatchEvaluator::BatchEvaluator(const Model& model, std::vector<const Signals*> datasets, int grain_blocks)
    : model_(model), datasets_(std::move(datasets)), grain_blocks_(std::max(1, grain_blocks)) {
  assert(!datasets_.empty());
}

double BatchEvaluator::samples() const {
  double n = 0;
  for (const Signals* d : datasets_) n += static_cast<double>(d->size());
  return n;
}

std::vector<MetricSums> BatchEvaluator::sums(const CandidateBatch& batch) const {
  assert(batch.dim() == model_.dim());
  const int count = batch.count();
  const int blocks = (count + kLanes - 1) / kLanes;
  const int tasks = blocks * static_cast<int>(datasets_.size());
  std::vector<MetricSums> out(datasets_.size() * static_cast<std::size_t>(count));
  tbb::parallel_for(
      tbb::blocked_range<int>(0, tasks, grain_blocks_),
      [&](const tbb::blocked_range<int>& range) {
        for (int task = range.begin(); task < range.end(); ++task) {
          const int d = task / blocks, first = (task % blocks) * kLanes;
          model_.evaluate_block(batch, first, std::min(kLanes, count - first), *datasets_[d],
                                out.data() + static_cast<std::size_t>(d) * count + first);
        }
      },
      tbb::simple_partitioner());
  return out;
}

void BatchEvaluator::evaluate(const CandidateBatch& batch, Metric metric, std::span<double> out) const {
  const auto s = sums(batch);
  const int count = batch.count();
  const double D = static_cast<double>(datasets_.size());
  for (int i = 0; i < count; ++i) {
    double total = 0;
    for (std::size_t d = 0; d < datasets_.size(); ++d) total += finish_metric(metric, s[d * count + i], *datasets_[d]);
    out[i] = total / D;
  }
}

void BatchEvaluator::evaluate_all(const CandidateBatch& batch, std::span<MetricRow> out) const {
  const auto s = sums(batch);
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
