#include "engine/signals.hpp"

#include <algorithm>
#include <cmath>

namespace dampbench {

Signals prepare_signals(const Dataset& data) {
  Signals s;
  s.name = data.name;
  s.t_s = data.t_s;
  s.x_m = data.x_m;
  s.v_m_s = data.v_m_s;
  s.a_m_s2 = data.a_m_s2;
  s.F_N = data.F_N;
  s.operating = data.operating;
  const std::size_t n = s.t_s.size();
  s.w_trapz_s.assign(n, 0.0);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double half_dt = 0.5 * (s.t_s[k + 1] - s.t_s[k]);
    s.w_trapz_s[k] += half_dt;
    s.w_trapz_s[k + 1] += half_dt;
  }
  s.duration_s = n > 1 ? s.t_s.back() - s.t_s.front() : 0.0;
  if (!s.F_N.empty()) {
    double mean = 0;
    for (double f : s.F_N) mean += f;
    mean /= static_cast<double>(n);
    double var = 0;
    for (double f : s.F_N) {
      var += (f - mean) * (f - mean);
      s.force_max_abs_N = std::max(s.force_max_abs_N, std::fabs(f));
    }
    s.force_std_N = std::sqrt(var / static_cast<double>(n));
  }
  return s;
}

}  // namespace dampbench
