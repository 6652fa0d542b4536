#pragma once
// The work a force does along a record's displacement, ∫F dx: over whole cycles of a closed loop it is the loop's
// area, the energy the damper dissipates (fvd paper, the text under Figs. 3-4). A force that is a function of x
// alone (an elastic spring, linear or quadratic) does no work over a closed loop, so the number depends on the
// dissipative part of the force only.
#include <algorithm>
#include <cstddef>
#include <span>

namespace dampbench {

/// ∫F dx by the trapezoid rule, Σ ½(F_k + F_{k+1})(x_{k+1} − x_k) [N·m = J], over the samples both spans hold.
inline double loop_work_j(std::span<const double> force_n, std::span<const double> x_m) {
  const std::size_t n = std::min(force_n.size(), x_m.size());
  double work = 0;
  for (std::size_t k = 0; k + 1 < n; ++k) work += 0.5 * (force_n[k] + force_n[k + 1]) * (x_m[k + 1] - x_m[k]);
  return work;
}

}  // namespace dampbench
