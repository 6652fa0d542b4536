#include "engine/export/fixed_step_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/model/law_model.hpp"
#include "engine/model/stepped_simulation.hpp"
#include "engine/record/signals.hpp"

namespace dampbench::exporting {
namespace {

constexpr double kSamplesPerPeriod = 20;      // the coarsest sampling checked: a motion needs its shape
constexpr int kFineFactor = 16;               // the reference run's sub-steps, times the export's
constexpr double kShrink = 0.8;               // from one dt tried to the next
constexpr int kTries = 60;                    // 0.8^60 ≈ 1.5e-6 of the first dt
constexpr std::size_t kMaxSamples = 20000;    // a tiny dt checks the first samples, where |v| peaks

/// x = (S/2)·sin(ωt) with (S/2)·ω the peak velocity: it starts at its peak |v|, where stiffness peaks. Two periods,
/// or kMaxSamples at a tiny dt.
Signals sinusoid(const CheckedMotion& m, const std::map<std::string, double>& variables, double dt_s) {
  const double amplitude = 0.5 * m.stroke_m, omega = m.velocity_max_abs_m_s / amplitude;
  const double period = 2 * std::numbers::pi / omega;
  const auto n = static_cast<std::size_t>(std::min(static_cast<double>(kMaxSamples), std::ceil(2 * period / dt_s) + 1));
  Dataset d;
  d.name = "fixed-step check";
  d.operating = variables;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * dt_s;
    d.t_s.push_back(t);
    d.x_m.push_back(amplitude * std::sin(omega * t));
    d.v_m_s.push_back(amplitude * omega * std::cos(omega * t));
    d.a_m_s2.push_back(-amplitude * omega * omega * std::sin(omega * t));
  }
  return prepare_signals(d);
}

bool finite(const std::vector<double>& force) {
  return std::all_of(force.begin(), force.end(), [](double f) { return std::isfinite(f); });
}

/// Finite and within kFixedStepTolerance of kFineFactor times the sub-steps (the finer run only when the coarse
/// one is finite: a failing try costs one run).
bool passes(const Model& model, std::span<const double> params, int substeps, const Signals& s) {
  const std::vector<double> coarse = simulate_stepped(model, params, s, substeps);
  if (!finite(coarse)) return false;
  const std::vector<double> fine = simulate_stepped(model, params, s, substeps * kFineFactor);
  double diff = 0, norm = 0;
  for (std::size_t k = 0; k < coarse.size(); ++k) {
    diff += (coarse[k] - fine[k]) * (coarse[k] - fine[k]);
    norm += fine[k] * fine[k];
  }
  return finite(fine) && diff <= kFixedStepTolerance * kFixedStepTolerance * norm;
}

/// The model's stiffness estimate at `variables` on the motion.
double stiffness_at(ModelStepper& stepper, std::span<const double> params, const CheckedMotion& m,
                    const std::map<std::string, double>& variables) {
  stepper.set_parameters(params, variables);
  stepper.reset();
  return stepper.stiffness(m.velocity_max_abs_m_s, m.stroke_m);
}

/// x rounded down to 3 significant digits, so that the printed step is never above the one checked.
double down_to_3_digits(double x) {
  const double unit = std::pow(10.0, std::floor(std::log10(x)) - 2);
  return std::floor(x / unit) * unit;
}

}  // namespace

bool steps_states(const Model& model) {
  const auto* law = dynamic_cast<const LawModel*>(&model);
  return model.has_internal_states() || (law && !law->lags().empty());
}

FixedStepCheck check_fixed_step(const Model& model, std::span<const double> params, int substeps,
                                const CheckedMotion& motion) {
  if (substeps < 1 || substeps > kMaxExportSubsteps)
    throw InputError(fmt::format("--substeps: expected a whole number from 1 to {}, got {}", kMaxExportSubsteps, substeps));
  if (!(motion.stroke_m > 0) || !(motion.velocity_max_abs_m_s > 0) || !std::isfinite(motion.stroke_m) ||
      !std::isfinite(motion.velocity_max_abs_m_s))
    throw InputError(fmt::format("fixed-step check: expected a finite stroke and peak velocity above 0, got {} m and {} m/s",
                                 motion.stroke_m, motion.velocity_max_abs_m_s));
  FixedStepCheck check{.motion = motion, .has_states = steps_states(model)};
  auto stepper = model.stepper();
  if (!stepper) throw InputError(fmt::format("{} cannot be stepped sample by sample", model.id()));
  for (const auto& variables : motion.variables)
    check.stiffness_per_s = std::max(check.stiffness_per_s, stiffness_at(*stepper, params, motion, variables));
  double stiffest_probe = 0;
  const std::map<std::string, double>* probe = nullptr;
  for (const auto& variables : motion.probes)
    if (const double l = stiffness_at(*stepper, params, motion, variables); l > stiffest_probe) stiffest_probe = l, probe = &variables;
  if (probe && stiffest_probe > check.stiffness_per_s) {
    check.motion.variables.push_back(*probe);
    check.stiffness_per_s = stiffest_probe;
  }
  if (!check.has_states || !std::isfinite(check.stiffness_per_s)) return check;
  const double period_s = std::numbers::pi * motion.stroke_m / motion.velocity_max_abs_m_s;
  const double rk4_s = check.stiffness_per_s > 0 ? substeps * kRk4StabilityBound / check.stiffness_per_s
                                                 : std::numeric_limits<double>::infinity();
  double dt = std::min(period_s / kSamplesPerPeriod, rk4_s);
  check.period_bound = dt < rk4_s;
  for (int i = 0; i < kTries; ++i, dt *= kShrink) {
    check.dt_tried_last_s = dt;
    const bool ok = std::all_of(check.motion.variables.begin(), check.motion.variables.end(), [&](const auto& variables) {
      return passes(model, params, substeps, sinusoid(check.motion, variables, dt));
    });
    if (ok) {
      check.dt_max_s = dt;
      check.checked_duration_s = std::min(2 * period_s, static_cast<double>(kMaxSamples - 1) * dt);
      check.period_bound = check.period_bound && i == 0;
      return check;
    }
  }
  check.period_bound = false;
  return check;
}

std::string printed_step(const FixedStepCheck& check) { return fmt::format("{:.3g}", down_to_3_digits(check.dt_max_s)); }

std::string fixed_step_statement(const FixedStepCheck& c, int substeps) {
  if (!c.has_states) return " * Step size: the model has no states, so dbm_step holds at any dt.\n";
  if (!std::isfinite(c.stiffness_per_s))
    return " * Step size: NOT checked: the model's stiffness estimate is not finite at these coefficients.\n";
  std::string at;
  for (const auto& variables : c.motion.variables) {
    std::string corner;
    for (const auto& [name, value] : variables) corner += fmt::format("{}{} = {:.6g}", corner.empty() ? "" : ", ", name, value);
    if (!corner.empty()) at += (at.empty() ? " at " : " and at ") + corner;
  }
  const double period_s = std::numbers::pi * c.motion.stroke_m / c.motion.velocity_max_abs_m_s;
  const std::string span = c.dt_max_s > 0 && c.checked_duration_s < 1.99 * period_s
                               ? fmt::format(" (its first {:.3g} s)", c.checked_duration_s)
                               : "";
  const std::string motion = fmt::format(" * on a sinusoid of {:.6g} m stroke and {:.6g} m/s peak velocity{}{}.\n",
                                         c.motion.stroke_m, c.motion.velocity_max_abs_m_s, span, at);
  const std::string stiffness =
      c.stiffness_per_s > 0
          ? fmt::format(" * Stiffness estimate {:.6g} 1/s (RK4 bound: sub-steps * 2.78 / stiffness).", c.stiffness_per_s)
          : std::string(" * No stiffness estimate: the check starts at 1/20 of the motion's period.");
  if (c.dt_max_s <= 0)
    return fmt::format(" * Step size: NOT stable with {} sub-steps down to dt = {:.3g} s\n{}{} Raise --substeps.\n",
                       substeps, c.dt_tried_last_s, motion, stiffness);
  return fmt::format(" * Step size: checked stable for dt <= {} s{}: finite and within 1 % (relative L2) of {} sub-steps\n"
                     "{}{} The largest dt tried from that\n"
                     " * bound down by factors of 0.8; a larger stroke or velocity stiffens the model: check dt on the\n"
                     " * motions the controller will see (simulate --fixed-step).\n",
                     printed_step(c), c.period_bound ? " (the check's coarsest sampling, 1/20 of the period)" : "",
                     substeps * kFineFactor, motion, stiffness);
}

}  // namespace dampbench::exporting
