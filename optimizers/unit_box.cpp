#include "optimizers/unit_box.hpp"

#include <algorithm>

namespace dampbench {

UnitBox::UnitBox(const Bounds& bounds) : lower_(bounds.lower), upper_(bounds.upper) {
  for (int j = 0; j < bounds.dim(); ++j)
    if (lower_[j] < upper_[j]) free_.push_back(j);
}

std::vector<double> UnitBox::to_unit(std::span<const double> x) const {
  std::vector<double> y(free_.size());
  for (std::size_t i = 0; i < free_.size(); ++i) {
    const int j = free_[i];
    y[i] = std::clamp((x[j] - lower_[j]) / (upper_[j] - lower_[j]), 0.0, 1.0);
  }
  return y;
}

void UnitBox::to_params(std::span<const double> y, std::span<double> x) const {
  for (int j = 0; j < dim(); ++j) x[j] = lower_[j];
  for (std::size_t i = 0; i < free_.size(); ++i) {
    const int j = free_[i];
    x[j] = std::clamp(lower_[j] + y[i] * (upper_[j] - lower_[j]), lower_[j], upper_[j]);
  }
}

std::vector<double> UnitBox::to_params(std::span<const double> y) const {
  std::vector<double> x(lower_.size());
  to_params(y, x);
  return x;
}

}  // namespace dampbench
