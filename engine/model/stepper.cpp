#include "engine/model/stepper.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/model/model.hpp"

namespace dampbench {

std::vector<double> simulate_stepped(const Model& model, std::span<const double> params, const Signals& data,
                                     int substeps) {
  if (substeps < 1) throw InputError(fmt::format("--fixed-step: expected a whole number of sub-steps >= 1, got {}", substeps));
  auto stepper = model.stepper();
  if (!stepper)
    throw InputError(fmt::format("{} cannot be stepped sample by sample (fixed-step simulation, export, structures)",
                                 model.id()));
  stepper->set_parameters(params, data.law_variables);
  stepper->reset();
  const std::size_t n = data.size();
  std::vector<double> force(n, std::numeric_limits<double>::quiet_NaN());
  if (n == 0) return force;
  const auto a = [&](std::size_t k) { return k < data.a_m_s2.size() ? data.a_m_s2[k] : 0.0; };
  force[0] = stepper->force(data.x_m[0], data.v_m_s[0], a(0));
  for (std::size_t k = 1; k < n; ++k) {
    stepper->advance(data.x_m[k - 1], data.v_m_s[k - 1], data.x_m[k], data.v_m_s[k], data.t_s[k] - data.t_s[k - 1],
                     substeps);
    const double f = stepper->force(data.x_m[k], data.v_m_s[k], a(k));
    if (!std::isfinite(f)) break;  // the rest stays NaN: a blown-up state does not come back
    force[k] = f;
  }
  return force;
}

}  // namespace dampbench
