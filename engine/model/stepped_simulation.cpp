#include "engine/model/stepped_simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench {
namespace {

std::unique_ptr<ModelStepper> stepper_of(const Model& model) {
  auto stepper = model.stepper();
  if (!stepper)
    throw InputError(fmt::format("{} cannot be stepped sample by sample (fixed-step simulation, export, structures)",
                                 model.id()));
  return stepper;
}

/// The record's variables with each column's value at sample k (zero-order hold over the interval from k).
class HeldVariables {
 public:
  explicit HeldVariables(const Signals& data) : data_(data), values_(data.law_variables) {
    for (const auto& [name, column] : data.operating_signals)
      if (column.size() != data.size())
        throw InputError(fmt::format("record '{}': column {} has {} samples, the record {}", data.name, name,
                                     column.size(), data.size()));
  }
  /// The variables at sample k; `changed` tells whether a column's value differs from the last call's.
  const std::map<std::string, double>& at(std::size_t k, bool& changed) {
    changed = first_;
    first_ = false;
    for (const auto& [name, column] : data_.operating_signals) {
      auto& value = values_[name];
      changed = changed || value != column[k];
      value = column[k];
    }
    return values_;
  }

 private:
  const Signals& data_;
  std::map<std::string, double> values_;
  bool first_ = true;
};

constexpr std::size_t kStiffnessProbes = 64;

/// The samples whose variables kernel_substeps probes: 64 spread evenly, and each column's smallest and largest.
std::set<std::size_t> probe_samples(const Signals& data) {
  std::set<std::size_t> samples;
  const std::size_t n = data.size();
  for (std::size_t i = 0; i < kStiffnessProbes && n > 0; ++i) samples.insert(i * (n - 1) / (kStiffnessProbes - 1));
  for (const auto& [name, column] : data.operating_signals) {
    if (column.size() != n || n == 0) continue;  // HeldVariables refuses it
    const auto [lo, hi] = std::minmax_element(column.begin(), column.end());
    samples.insert(static_cast<std::size_t>(lo - column.begin()));
    samples.insert(static_cast<std::size_t>(hi - column.begin()));
  }
  return samples;
}

}  // namespace

std::vector<int> kernel_substeps(const Model& model, std::span<const double> params, const Signals& data) {
  auto stepper = stepper_of(model);
  double lambda = 0;
  for (const std::size_t k : probe_samples(data)) {
    std::map<std::string, double> variables = data.law_variables;
    for (const auto& [name, column] : data.operating_signals)
      if (k < column.size()) variables[name] = column[k];
    stepper->set_parameters(params, variables);
    stepper->reset();  // a driver lag's u at the probe's command
    lambda = std::max(lambda, stepper->stiffness(data.velocity_max_abs, data.displacement_ptp));
  }
  std::vector<int> counts;
  for (std::size_t k = 1; k < data.size(); ++k) {
    const int n = stepper->kernel_substeps(data, k, lambda);
    if (n < 1) return {};
    counts.push_back(n);
  }
  return counts;
}

std::vector<double> simulate_stepped(const Model& model, std::span<const double> params, const Signals& data,
                                     int substeps) {
  if (substeps < 1 && substeps != kKernelSubsteps)
    throw InputError(fmt::format("--fixed-step: expected a whole number of sub-steps >= 1, got {}", substeps));
  auto stepper = stepper_of(model);
  const std::size_t n = data.size();
  HeldVariables variables(data);
  const auto hold = [&](std::size_t k) {
    bool changed = false;
    const auto& values = variables.at(k, changed);
    if (changed) stepper->set_parameters(params, values);
  };
  std::vector<double> force(n, std::numeric_limits<double>::quiet_NaN());
  std::vector<int> counts;
  if (substeps == kKernelSubsteps) {
    counts = kernel_substeps(model, params, data);
    if (counts.empty() && n > 1) return force;  // masked as too stiff
  }
  if (n == 0) return force;
  hold(0);
  stepper->reset();
  const auto a = [&](std::size_t k) { return k < data.a_m_s2.size() ? data.a_m_s2[k] : 0.0; };
  force[0] = stepper->force(data.x_m[0], data.v_m_s[0], a(0));
  for (std::size_t k = 1; k < n; ++k) {
    hold(k - 1);
    stepper->advance(data.x_m[k - 1], data.v_m_s[k - 1], data.x_m[k], data.v_m_s[k], data.t_s[k] - data.t_s[k - 1],
                     counts.empty() ? substeps : counts[k - 1]);
    const double f = stepper->force(data.x_m[k], data.v_m_s[k], a(k));
    if (!std::isfinite(f)) break;  // the rest stays NaN: a blown-up state does not come back
    force[k] = f;
  }
  return force;
}

}  // namespace dampbench
