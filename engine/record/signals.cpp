#include "engine/record/signals.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/common/vector_math.hpp"

namespace dampbench {

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
  s.duration_s = n > 1 ? s.t_s.back() - s.t_s.front() : 0.0;
  if (n > 0) {
    const auto [lo, hi] = std::minmax_element(s.x_m.begin(), s.x_m.end());
    s.displacement_ptp = *hi - *lo;
    for (double v : s.v_m_s) s.velocity_max_abs = std::max(s.velocity_max_abs, std::fabs(v));
    s.excitation_freq_hz = s.displacement_ptp > 0 ? s.velocity_max_abs / (std::numbers::pi * s.displacement_ptp) : 0.0;
  }
  s.law_variables = s.operating;
  for (const auto& [name, value] : s.operating) {
    const auto source = s.operating_source.find(name);
    s.law_variable_source[name] = source != s.operating_source.end() ? source->second : "dataset";
  }
  if (s.law_variables.try_emplace("amp", 0.5 * s.displacement_ptp).second)
    s.law_variable_source["amp"] = "record estimate (half peak-to-peak)";
  if (s.law_variables.try_emplace("freq", s.excitation_freq_hz).second)
    s.law_variable_source["freq"] = "record estimate (fdsp eq. 15)";
  s.law_variables["vamp"] = 2 * std::numbers::pi * s.law_variables.at("amp") * s.law_variables.at("freq");
  s.law_variable_source["vamp"] = "2π·amp·freq";
  s.law_variables["w"] = s.excitation_freq_hz;
  s.law_variable_source["w"] = "record estimate (fdsp eq. 15)";
  if (!s.F_N.empty()) {
    double mean = 0;
    for (double f : s.F_N) mean += f;
    mean /= static_cast<double>(n);
    double var = 0;
    for (double f : s.F_N) {
      var += (f - mean) * (f - mean);
      s.force_max_abs_N = std::max(s.force_max_abs_N, std::fabs(f));
      s.force_sum_sq += f * f;
    }
    s.force_std_N = std::sqrt(var / static_cast<double>(n));
  }
  return s;
}

}  // namespace dampbench
