#include "engine/fit/model_file_of_fit.hpp"

#include <algorithm>

#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/kernels/isa.hpp"

namespace dampbench {

ModelFile model_file_of_fit(const FitSpec& spec, const PreparedFit& prepared, const FitOutcome& fit,
                            const std::string& dampbench_version) {
  const Model& model = *prepared.model.model;
  const RunResult& best = fit.best();
  const auto metric_at = static_cast<std::size_t>(
      std::find(kAllMetrics.begin(), kAllMetrics.end(), prepared.metric) - kAllMetrics.begin());
  ModelFile f;
  f.dampbench_version = dampbench_version;
  f.vector_level = std::string(isa_name(active_isa()));
  f.choice = spec.model;
  f.choice.bounds.clear();  // the box searched is not part of the model
  f.model_id = std::string(model.id());
  for (int i = 0; i < model.dim(); ++i) f.coefficients.emplace_back(model.parameters()[i].name, best.best_params[i]);
  f.metric = std::string(metric_name(prepared.metric));
  f.fitted_value = best.best_metrics[metric_at];
  CandidateBatch batch(model.dim(), 1);
  batch.set_candidate(0, best.best_params);
  for (std::size_t r = 0; r < prepared.records.signals.size(); ++r) {
    const Signals& s = prepared.records.signals[r];
    std::vector<MetricRow> row(1);
    BatchEvaluator(model, s).evaluate_all(batch, row);  // as `evaluate` does, so that it reproduces these bits
    // A record loaded beforehand (the Python module's) names its file, or "arrays", as its source.
    const std::string& path = spec.paths.empty() ? spec.records.at(r).source : spec.paths.at(r);
    f.records.push_back({s.name, path, row[0][metric_at], operating_json(s), s.displacement_ptp, s.velocity_max_abs});
  }
  return f;
}

}  // namespace dampbench
