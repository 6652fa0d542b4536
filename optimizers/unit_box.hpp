#pragma once
// The free parameters of a box (lower < upper) mapped to the unit cube, x_j = lower_j + y_j·(upper_j − lower_j),
// so that parameters of very different magnitudes (fdsp: β ≈ 3e5, Z0 ≈ 0.01) have comparable steps; parameters
// with lower == upper stay at their bound. The local phases of the hybrids (optimizers/hybrid) and CMA-ES
// (optimizers/cmaes) work in these coordinates.
#include <span>
#include <vector>

#include "engine/model/bounds.hpp"

namespace dampbench {

/// The free parameters of a box mapped to [0, 1]^m.
class UnitBox {
 public:
  explicit UnitBox(const Bounds& bounds);
  /// Number of free parameters (lower < upper).
  [[nodiscard]] int free_dim() const { return static_cast<int>(free_.size()); }
  [[nodiscard]] int dim() const { return static_cast<int>(lower_.size()); }
  /// Free coordinates of x in the unit cube, clamped to [0, 1].
  [[nodiscard]] std::vector<double> to_unit(std::span<const double> x) const;
  /// Every parameter from unit coordinates (fixed ones at their bound); clamped to [lower, upper], so
  /// rounding never leaves the box.
  void to_params(std::span<const double> y, std::span<double> x) const;
  [[nodiscard]] std::vector<double> to_params(std::span<const double> y) const;

 private:
  std::vector<double> lower_, upper_;
  std::vector<int> free_;  ///< indices of the free parameters
};

}  // namespace dampbench
