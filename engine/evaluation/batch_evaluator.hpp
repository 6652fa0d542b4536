#pragma once
// Evaluates a whole batch of candidates of one model on one or more datasets: oneTBB splits the work
// into (lane block, dataset) tasks across cores. Every block is computed the same way wherever it runs,
// results land in per-candidate slots and datasets are combined in a fixed order, so the output is
// bit-identical for any thread count and any grain size.
//
// Several datasets (conditions) are fitted at once by averaging the metric over them: each dataset's
// metric is normalized by its own force statistics, so the mean weighs every condition alike.
#include <array>
#include <span>
#include <vector>

#include "engine/model/batch.hpp"
#include "engine/model/metrics.hpp"
#include "engine/model/model.hpp"
#include "engine/record/signals.hpp"

namespace dampbench {

using MetricRow = std::array<double, kMetricCount>;  ///< every metric, in the order of kAllMetrics

/// The real type of the model's lanes in an evaluation: float64, or float32 (single-precision lanes, twice the
/// lanes per vector) for a model that has them (Model::has_float32_lanes; the others run float64). The metric
/// sums are added in double either way. float32 serves the global search of `--precision mixed`; what is
/// reported is evaluated in float64 (engine/identification/identification.hpp).
enum class Precision { float64, float32 };

class BatchEvaluator {
 public:
  /// `grain_blocks`: lane blocks handed to a task at once (tbb::simple_partitioner); any value gives the
  /// same results, it only changes how the batch is split across threads.
  BatchEvaluator(const Model& model, const Signals& data, int grain_blocks = 1,
                 Precision precision = Precision::float64);
  /// Several datasets; the metric of a candidate is the mean of its metric on each dataset.
  BatchEvaluator(const Model& model, std::vector<const Signals*> datasets, int grain_blocks = 1,
                 Precision precision = Precision::float64);

  /// One metric per candidate (mean over the datasets); +inf for candidates whose force is NaN or Inf.
  void evaluate(const CandidateBatch& batch, Metric metric, std::span<double> out) const;

  /// Every metric per candidate (each the mean over the datasets).
  void evaluate_all(const CandidateBatch& batch, std::span<MetricRow> out) const;

  [[nodiscard]] const Model& model() const { return model_; }
  [[nodiscard]] const std::vector<const Signals*>& datasets() const { return datasets_; }
  /// Samples per candidate evaluation (summed over the datasets).
  [[nodiscard]] double samples() const;

 private:
  /// Metric sums of every candidate on every dataset (those of `wanted`, the others NaN): sums[d * count + i].
  std::vector<MetricSums> sums(const CandidateBatch& batch, SumSet wanted) const;

  const Model& model_;
  std::vector<const Signals*> datasets_;
  int grain_blocks_;
  Precision precision_;
};

}  // namespace dampbench
