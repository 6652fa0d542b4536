#include "engine/evaluation/sensitivity.hpp"

#include <cmath>

#include <fmt/format.h>

#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/common/error.hpp"

namespace dampbench {
namespace {

/// f(z) of every candidate of a batch: the chosen metric, or the RMS of the model force.
std::vector<double> objective(const Model& model, const CandidateBatch& batch, const Signals& data,
                              const SensitivitySettings& s) {
  std::vector<double> f(batch.count());
  if (s.metric) {
    BatchEvaluator(model, data).evaluate(batch, *s.metric, f);
    return f;
  }
  for (int i = 0; i < batch.count(); ++i) {
    double sum_sq = 0;
    for (double F : model.simulate(batch.candidate(i), data)) sum_sq += F * F;
    f[i] = std::sqrt(sum_sq / static_cast<double>(data.size()));
  }
  return f;
}

}  // namespace

Sensitivity differential_sensitivity(const Model& model, std::span<const double> params, const Signals& data,
                                     const SensitivitySettings& s) {
  if (s.points < 3) throw InputError(fmt::format("sensitivity: --points must be at least 3, got {}", s.points));
  if (!(s.range > 0 && s.range < 1)) throw InputError(fmt::format("sensitivity: --range must be in (0, 1), got {}", s.range));
  if (s.metric && !data.has_force())
    throw InputError("sensitivity: a metric objective needs a record with measured force F");
  const int D = model.dim(), N = s.points;
  // One batch: every parameter's grid, the others held at their values.
  CandidateBatch batch(D, D * N);
  for (int j = 0; j < D; ++j)
    for (int i = 0; i < N; ++i) {
      batch.set_candidate(j * N + i, params);
      batch.at(j * N + i, j) = params[j] * (1 - s.range + 2 * s.range * i / (N - 1));
    }
  const std::vector<double> f = objective(model, batch, data, s);

  Sensitivity out;
  double total = 0;
  for (int j = 0; j < D; ++j) {
    const double dz = 2 * s.range * params[j] / (N - 1);  // signed grid step
    double sum_sq = 0;
    for (int i = 0; i < N; ++i) {
      const double* fj = f.data() + j * N;
      double Si = 0;
      if (dz != 0) {
        if (i == 0) Si = (fj[1] - fj[0]) / dz;
        else if (i == N - 1) Si = (fj[N - 1] - fj[N - 2]) / dz;
        else Si = (fj[i + 1] - fj[i - 1]) / (2 * dz);
      }
      sum_sq += Si * Si;
    }
    double S = std::sqrt(sum_sq / N);
    if (s.normalized) S *= std::fabs(params[j]);
    out.S.push_back(S);
    total += S;
  }
  for (double S : out.S) out.SP.push_back(total > 0 ? 100 * S / total : 0.0);
  return out;
}

}  // namespace dampbench
