#pragma once
// Evaluates a whole batch of candidates of one model on one dataset: oneTBB splits the batch into lane
// blocks across cores. Every block is computed the same way wherever it runs, and results land in
// per-candidate slots, so the output is bit-identical for any thread count and any grain size.
#include <span>

#include "engine/batch.hpp"
#include "engine/metrics.hpp"
#include "engine/model.hpp"
#include "engine/signals.hpp"

namespace dampbench {

class BatchEvaluator {
 public:
  /// `grain_blocks`: lane blocks handed to a task at once (tbb::simple_partitioner); any value gives the
  /// same results, it only changes how the batch is split across threads.
  BatchEvaluator(const Model& model, const Signals& data, int grain_blocks = 1);

  /// Metric sums of every candidate of the batch (out.size() == batch.count()).
  void evaluate_sums(const CandidateBatch& batch, std::span<MetricSums> out) const;

  /// One metric per candidate; +inf for candidates whose force is NaN or Inf.
  void evaluate(const CandidateBatch& batch, Metric metric, std::span<double> out) const;

  [[nodiscard]] const Model& model() const { return model_; }
  [[nodiscard]] const Signals& data() const { return data_; }

 private:
  const Model& model_;
  const Signals& data_;
  int grain_blocks_;
};

}  // namespace dampbench
