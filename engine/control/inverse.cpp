#include "engine/control/inverse.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/model/law_model.hpp"

namespace dampbench::control {

void check_commanded_variable(const Model& model, const std::string& variable, const std::string& command) {
  const auto* laws = dynamic_cast<const LawModel*>(&model);
  const auto names = laws ? laws->law_variables() : std::vector<std::string>{};
  if (std::find(names.begin(), names.end(), variable) == names.end())
    throw InputError(fmt::format("{}: model {} has no law in {}, so no command in {} changes its force (fit it with "
                                 "laws in {}, e.g. --laws \"c0=poly({},1)\")",
                                 command, model.id(), variable, variable, variable, variable));
}

namespace {

void check(const Model& model, const Signals& data, const InverseSettings& s) {
  if (!(s.low < s.high) || !std::isfinite(s.low) || !std::isfinite(s.high))
    throw InputError(fmt::format("--range: expected {}=LOW:HIGH with LOW < HIGH, got {}:{}", s.variable, s.low, s.high));
  if (s.substeps < 1) throw InputError(fmt::format("--substeps: expected a whole number >= 1, got {}", s.substeps));
  check_commanded_variable(model, s.variable, "inverse");
  if (!data.has_force())
    throw InputError(fmt::format("inverse: record '{}' has no force column: it must hold the desired force F", data.name));
  for (std::size_t k = 0; k < data.size(); ++k)
    if (!std::isfinite(data.F_N[k]))
      throw InputError(fmt::format("inverse: record '{}': sample {} (t = {} s): the desired force is not a finite number",
                                   data.name, k, data.t_s[k]));
}

}  // namespace

InverseResult inverse_command(const Model& model, std::span<const double> params, const Signals& data,
                              const InverseSettings& s) {
  check(model, data, s);
  auto stepper = model.stepper();
  if (!stepper) throw InputError(fmt::format("inverse: {} cannot be stepped sample by sample", model.id()));
  const std::size_t n = data.size();
  std::map<std::string, double> variables = data.law_variables;
  const auto a = [&](std::size_t k) { return k < data.a_m_s2.size() ? data.a_m_s2[k] : 0.0; };
  InverseResult r;
  r.command.assign(n, s.low);
  r.force_N.assign(n, std::nan(""));
  r.reachable.assign(n, false);
  if (n == 0) return r;
  const auto command_at = [&](double c) {
    variables[s.variable] = c;
    stepper->set_parameters(params, variables);
  };
  command_at(s.low);
  stepper->reset();
  r.force_N[0] = stepper->force(data.x_m[0], data.v_m_s[0], a(0));
  double sum_err = 0, sum_desired = 0;
  std::size_t reached = 0;
  for (std::size_t k = 1; k < n; ++k) {
    const std::vector<double> saved = stepper->states();
    const double desired = data.F_N[k], dt = data.t_s[k] - data.t_s[k - 1];
    const auto force_with = [&](double c) {  // the force at sample k with command c over the interval
      command_at(c);
      if (k == 1) stepper->reset();  // at rest with the first command: a driver lag starts at u(0) = c(0)
      else stepper->set_states(saved);
      stepper->advance(data.x_m[k - 1], data.v_m_s[k - 1], data.x_m[k], data.v_m_s[k], dt, s.substeps);
      return stepper->force(data.x_m[k], data.v_m_s[k], a(k));
    };
    double c = s.low;
    if (s.law == InverseLaw::on_off) {
      const double last = r.force_N[k - 1];
      c = desired * last > 0 && std::fabs(desired) > std::fabs(last) ? s.high : s.low;
    } else {
      double lo = s.low, hi = s.high;
      double f_lo = force_with(lo) - desired, f_hi = force_with(hi) - desired;
      if (f_lo * f_hi <= 0) {  // bracketed: bisection to the command's rounding (60 halvings of the range)
        r.reachable[k] = true;
        for (int i = 0; i < 60 && hi - lo > 1e-12 * (s.high - s.low); ++i) {
          const double mid = 0.5 * (lo + hi), f_mid = force_with(mid) - desired;
          if (f_mid == 0) lo = hi = mid;
          else if ((f_mid < 0) == (f_lo < 0)) lo = mid, f_lo = f_mid;
          else hi = mid, f_hi = f_mid;
        }
        c = std::fabs(f_lo) <= std::fabs(f_hi) ? lo : hi;
      } else {
        c = std::fabs(f_lo) <= std::fabs(f_hi) ? s.low : s.high;
      }
    }
    if (k == 1) {  // the force at rest under the first command
      command_at(c);
      stepper->reset();
      r.force_N[0] = stepper->force(data.x_m[0], data.v_m_s[0], a(0));
    }
    r.force_N[k] = force_with(c);  // the states carried forward with the command chosen
    r.command[k - 1] = c;
    if (r.reachable[k]) {
      ++reached;
      sum_err += (r.force_N[k] - desired) * (r.force_N[k] - desired);
      sum_desired += desired * desired;
    }
  }
  r.command[n - 1] = n > 1 ? r.command[n - 2] : s.low;  // no interval after the last sample: the command holds
  const auto share = [&](auto pred) {
    return static_cast<double>(std::count_if(r.command.begin(), r.command.end(), pred)) / static_cast<double>(n);
  };
  r.share_at_low = share([&](double c) { return c == s.low; });
  r.share_at_high = share([&](double c) { return c == s.high; });
  r.share_reachable = n > 1 ? static_cast<double>(reached) / static_cast<double>(n - 1) : 0.0;
  r.tracking_error = sum_desired > 0 ? std::sqrt(sum_err / sum_desired) : 0.0;
  return r;
}

}  // namespace dampbench::control
