#include "engine/record/signals.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/vector_math.hpp"

namespace dampbench {

namespace {

/// The per-sample invariants of the power laws and the stroke's statistics (rig records only).
void prepare_displacement_input(Signals& s) {
  const std::size_t n = s.x_m.size();
  s.sgn_x.resize(n);
  s.sgn_v.resize(n);
  s.log_abs_x.resize(n);
  s.log_abs_v.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    s.sgn_x[k] = sign(s.x_m[k]);
    s.sgn_v[k] = sign(s.v_m_s[k]);
    s.log_abs_x[k] = log_abs_clamped(s.x_m[k]);
    s.log_abs_v[k] = log_abs_clamped(s.v_m_s[k]);
  }
  if (n == 0) return;
  const auto [lo, hi] = std::minmax_element(s.x_m.begin(), s.x_m.end());
  s.displacement_ptp = *hi - *lo;
  for (double v : s.v_m_s) s.velocity_max_abs = std::max(s.velocity_max_abs, std::fabs(v));
  s.excitation_freq_hz = s.displacement_ptp > 0 ? s.velocity_max_abs / (std::numbers::pi * s.displacement_ptp) : 0.0;
}

/// Operating variables plus amp, freq, vamp and w estimated from the stroke when the record does not state them.
void prepare_law_variables(Signals& s) {
  s.law_variables = s.operating;
  for (const auto& [name, value] : s.operating) {
    const auto source = s.operating_source.find(name);
    s.law_variable_source[name] = source != s.operating_source.end() ? source->second : "dataset";
  }
  if (s.is_system()) return;  // a force-driven record has no stroke to estimate them from
  if (s.law_variables.try_emplace("amp", 0.5 * s.displacement_ptp).second)
    s.law_variable_source["amp"] = "record estimate (half peak-to-peak)";
  if (s.law_variables.try_emplace("freq", s.excitation_freq_hz).second)
    s.law_variable_source["freq"] = "record estimate (fdsp eq. 15)";
  s.law_variables["vamp"] = 2 * std::numbers::pi * s.law_variables.at("amp") * s.law_variables.at("freq");
  s.law_variable_source["vamp"] = "2π·amp·freq";
  s.law_variables["w"] = s.excitation_freq_hz;
  s.law_variable_source["w"] = "record estimate (fdsp eq. 15)";
}

void prepare_measured_statistics(Signals& s) {
  const std::vector<double>& measured = s.measured();
  if (measured.empty()) return;
  const auto n = static_cast<double>(measured.size());
  double mean = 0;
  for (double f : measured) mean += f;
  mean /= n;
  double var = 0;
  for (double f : measured) {
    var += (f - mean) * (f - mean);
    s.measured_max_abs = std::max(s.measured_max_abs, std::fabs(f));
    s.measured_sum_sq += f * f;
  }
  s.measured_std = std::sqrt(var / n);
}

}  // namespace

bool same_operating_value(double a, double b) {
  return a == b || std::fabs(a - b) <= 1e-9 * std::max(std::fabs(a), std::fabs(b));
}

void check_uniform_sampling(const Dataset& data) {
  const std::size_t n = data.size();
  if (n < 2) return;
  const double step = (data.t_s.back() - data.t_s.front()) / static_cast<double>(n - 1);
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const double expected = data.t_s.front() + static_cast<double>(k) * step;
    if (std::fabs(data.t_s[k] - expected) > kUniformSamplingTolerance * step)
      throw InputError(fmt::format("record '{}': sample {} is at {:.9g} s, {:.3g} steps from the uniform grid of {:g} s "
                                   "from {:g} s; a system record needs a constant sampling rate",
                                   data.name, k, data.t_s[k], (data.t_s[k] - expected) / step, step, data.t_s.front()));
  }
}

Signals prepare_signals(const Dataset& data) {
  Signals s;
  static_cast<Dataset&>(s) = data;
  const std::size_t n = s.t_s.size();
  s.w_trapz_s.assign(n, 0.0);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double half_dt = 0.5 * (s.t_s[k + 1] - s.t_s[k]);
    s.w_trapz_s[k] += half_dt;
    s.w_trapz_s[k + 1] += half_dt;
  }
  s.duration_s = n > 1 ? s.t_s.back() - s.t_s.front() : 0.0;
  prepare_displacement_input(s);
  prepare_law_variables(s);
  prepare_measured_statistics(s);
  return s;
}

}  // namespace dampbench
