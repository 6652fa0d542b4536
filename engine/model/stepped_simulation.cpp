#include "engine/model/stepped_simulation.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench {

std::vector<double> simulate_stepped(const Model& model, std::span<const double> params, const Signals& data,
                                     int substeps) {
  if (substeps < 1) throw InputError(fmt::format("--fixed-step: expected a whole number of sub-steps >= 1, got {}", substeps));
  auto stepper = model.stepper();
  if (!stepper)
    throw InputError(fmt::format("{} cannot be stepped sample by sample (fixed-step simulation, export, structures)",
                                 model.id()));
  const std::size_t n = data.size();
  // Variables with a column (Dataset::operating_signals) change sample by sample: the value at sample k holds
  // over the interval that starts there (a controller's zero-order hold), and the force at sample 0 takes the
  // first value.
  std::map<std::string, double> variables = data.law_variables;
  for (const auto& [name, column] : data.operating_signals)
    if (column.size() != n)
      throw InputError(fmt::format("record '{}': column {} has {} samples, the record {}", data.name, name, column.size(), n));
  const auto hold = [&](std::size_t k) {
    bool changed = k == 0;
    for (const auto& [name, column] : data.operating_signals) {
      auto& value = variables[name];
      changed = changed || value != column[k];
      value = column[k];
    }
    if (changed) stepper->set_parameters(params, variables);
  };
  hold(0);
  stepper->reset();
  std::vector<double> force(n, std::numeric_limits<double>::quiet_NaN());
  if (n == 0) return force;
  const auto a = [&](std::size_t k) { return k < data.a_m_s2.size() ? data.a_m_s2[k] : 0.0; };
  force[0] = stepper->force(data.x_m[0], data.v_m_s[0], a(0));
  for (std::size_t k = 1; k < n; ++k) {
    hold(k - 1);
    stepper->advance(data.x_m[k - 1], data.v_m_s[k - 1], data.x_m[k], data.v_m_s[k], data.t_s[k] - data.t_s[k - 1],
                     substeps);
    const double f = stepper->force(data.x_m[k], data.v_m_s[k], a(k));
    if (!std::isfinite(f)) break;  // the rest stays NaN: a blown-up state does not come back
    force[k] = f;
  }
  return force;
}

}  // namespace dampbench
