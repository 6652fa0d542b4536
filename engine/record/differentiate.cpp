#include "engine/record/differentiate.hpp"

#include <cstddef>
#include <stdexcept>

namespace dampbench {
namespace {

constexpr std::size_t kStencil = 4;

/// Derivative, at node `k` of the 4 points starting at `first`, of the cubic through those points:
/// sum_j y_j L_j'(t_k), with L_k'(t_k) = sum_{m≠k} 1/(t_k - t_m) and, for j ≠ k,
/// L_j'(t_k) = prod_{l≠j,k} (t_k - t_l) / prod_{l≠j} (t_j - t_l).
double stencil_derivative(const std::vector<double>& t, const std::vector<double>& y, std::size_t first,
                          std::size_t k) {
  const double* ts = t.data() + first;
  const double* ys = y.data() + first;
  double derivative = 0;
  for (std::size_t j = 0; j < kStencil; ++j) {
    double weight = 0;
    if (j == k) {
      for (std::size_t m = 0; m < kStencil; ++m)
        if (m != k) weight += 1.0 / (ts[k] - ts[m]);
    } else {
      double numerator = 1;
      double denominator = 1;
      for (std::size_t l = 0; l < kStencil; ++l) {
        if (l != j) denominator *= ts[j] - ts[l];
        if (l != j && l != k) numerator *= ts[k] - ts[l];
      }
      weight = numerator / denominator;
    }
    derivative += weight * ys[j];
  }
  return derivative;
}

}  // namespace

std::vector<double> differentiate_3rd_order(const std::vector<double>& t, const std::vector<double>& y) {
  if (t.size() != y.size()) throw std::invalid_argument("differentiate_3rd_order: t and y differ in size");
  if (t.size() < kStencil) throw std::invalid_argument("differentiate_3rd_order: needs at least 4 samples");
  const std::size_t n = t.size();
  std::vector<double> dy(n);
  for (std::size_t i = 0; i < 2; ++i) {
    dy[i] = stencil_derivative(t, y, 0, i);                         // forward stencil {0..3}
    dy[n - 1 - i] = stencil_derivative(t, y, n - kStencil, 3 - i);  // backward stencil {n-4..n-1}
  }
  for (std::size_t i = 2; i + 2 < n; ++i)
    dy[i] = 0.5 * (stencil_derivative(t, y, i - 2, 2) + stencil_derivative(t, y, i - 1, 1));
  return dy;
}

}  // namespace dampbench
