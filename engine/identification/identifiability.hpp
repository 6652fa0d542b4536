#pragma once
// Identifiability evidence at a best fit (docs/design.md, "Evidence with every result"): standard errors and
// correlations of the parameters from the residual Jacobian, the classical nonlinear least-squares
// covariance (Bates & Watts 1988, §2.3): cov = s²·(JᵀJ)⁻¹, s² = ‖r‖²/(N − p), with J = ∂r/∂p by central
// differences at the best parameters and r the scaled residuals of identification.hpp (the scaling cancels).
// (JᵀJ)⁻¹ is the SVD pseudo-inverse; a direction the data cannot see (singular value ≤ 1e-10 of the
// largest) gives its parameters an infinite standard error and ±1 correlations.
//
// A parameter is flagged
//   "not identifiable"  its relative standard error se/|p| exceeds 1 (100 %), or is infinite;
//   "correlated"        |correlation| > 0.99 with another parameter (they trade off: the fit fixes a
//                        combination, not each one);
//   "at bound"          within 1e-6 of the box width from a bound (the optimum may lie outside the box).
#include <span>
#include <string>
#include <vector>

#include "engine/model/bounds.hpp"
#include "engine/model/model.hpp"

namespace dampbench {

struct Identifiability {
  std::vector<double> std_error;                 ///< SI, +inf when not determined by the data
  std::vector<double> relative_error;            ///< se/|p| (+inf for p = 0 with se > 0)
  std::vector<std::vector<double>> correlation;  ///< p × p
  std::vector<std::vector<std::string>> flags;   ///< per parameter: "not identifiable", "correlated with X", "at bound"
  int samples = 0;                               ///< N, residuals summed over the datasets
  [[nodiscard]] bool all_identifiable() const;
  /// Parameter j is determined by the data: neither "not identifiable" nor "correlated" (a bound may hold it).
  [[nodiscard]] bool determined(int j) const;
  /// Parameter j ended within the bound tolerance of its box.
  [[nodiscard]] bool at_bound(int j) const;
  /// "ok", or the flags of every flagged parameter: "m: correlated with K1; K1: correlated with m".
  [[nodiscard]] std::string summary(const Model& model) const;
};

Identifiability assess_identifiability(const Model& model, std::span<const Signals* const> data, const Bounds& bounds,
                                       std::span<const double> best_params);

}  // namespace dampbench
