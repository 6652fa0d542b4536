#include "engine/record/record_transforms.hpp"

#include <algorithm>
#include <cmath>
#include <regex>

#include <fmt/format.h>

#include "engine/record/differentiate.hpp"
#include "engine/common/error.hpp"

namespace dampbench {

SliderCrank::Pose SliderCrank::solve(double x_e) const {
  // f(θ) = L_AB sin θ + L_BC sin γ(θ) − H − x_e with cos γ = (L_AB/L_BC) cos θ, γ in (0, π/2).
  double theta = 0.0;
  for (int it = 0; it < 50; ++it) {
    const double c = L_AB_m * std::cos(theta) / L_BC_m;
    if (!(std::fabs(c) < 1)) break;
    const double sin_g = std::sqrt(1 - c * c);
    const double f = L_AB_m * std::sin(theta) + L_BC_m * sin_g - H_m - x_e;
    // d(L_BC sin γ)/dθ = L_BC · (c/sin γ) · (L_AB sin θ / L_BC)
    const double df = L_AB_m * std::cos(theta) + c * L_AB_m * std::sin(theta) / sin_g;
    const double step = f / df;
    theta -= step;
    if (std::fabs(step) < 1e-15) break;
  }
  const double c = L_AB_m * std::cos(theta) / L_BC_m;
  const double residual = L_AB_m * std::sin(theta) + L_BC_m * std::sqrt(std::max(0.0, 1 - c * c)) - H_m - x_e;
  if (!(std::fabs(c) < 1) || !(std::fabs(residual) < 1e-12))
    throw InputError(fmt::format("slider-crank: actuator displacement {:g} mm is outside the rig's reach", x_e * 1e3));
  return {theta, std::acos(c)};
}

double SliderCrank::torque(double F_e, const Pose& p) const {
  const double s = std::sin(p.theta_rad + p.gamma_rad);
  return printed_torque ? F_e * std::sin(p.gamma_rad) * L_AB_m * s : F_e * L_AB_m * s / std::sin(p.gamma_rad);
}

Dataset to_rotary(const Dataset& mts, const SliderCrank& rig) {
  Dataset out = mts;
  for (std::size_t k = 0; k < mts.size(); ++k) {
    const auto pose = rig.solve(mts.x_m[k]);
    out.x_m[k] = pose.theta_rad;
    if (mts.has_force()) out.F_N[k] = rig.torque(mts.F_N[k], pose);
  }
  out.v_m_s = differentiate_3rd_order(out.t_s, out.x_m);
  out.a_m_s2 = differentiate_3rd_order(out.t_s, out.v_m_s);
  return out;
}

namespace {

/// Linear interpolation of y(t) at time q (t increasing, q within [t.front(), t.back()]).
double interpolate(const std::vector<double>& t, const std::vector<double>& y, double q) {
  const auto it = std::upper_bound(t.begin(), t.end(), q);
  if (it == t.begin()) return y.front();
  if (it == t.end()) return y.back();
  const std::size_t i = static_cast<std::size_t>(it - t.begin());
  const double th = (q - t[i - 1]) / (t[i] - t[i - 1]);
  return y[i - 1] + th * (y[i] - y[i - 1]);
}

}  // namespace

Dataset average_cycles(const Dataset& r, int cycles, int drop) {
  if (cycles < 1 || drop < 0 || cycles - 2 * drop < 1)
    throw InputError(fmt::format("{}: cycle averaging needs cycles >= 1 and at least one kept cycle (cycles {}, drop {})",
                                 r.source, cycles, drop));
  const double t0 = r.t_s.front(), period = (r.t_s.back() - t0) / cycles;
  const double start = t0 + drop * period;
  std::vector<double> grid;  // the first kept cycle's own sample times, relative to its start
  for (double t : r.t_s)
    if (t >= start && t < start + period) grid.push_back(t - start);
  if (grid.size() < 4)
    throw InputError(fmt::format("{}: a cycle has {} samples; cycle averaging needs at least 4", r.source, grid.size()));
  const int kept = cycles - 2 * drop;
  Dataset out;
  out.name = r.name;
  out.source = r.source + fmt::format(" (cycles {}-{} of {} averaged)", drop + 1, cycles - drop, cycles);
  out.operating = r.operating;
  out.operating_source = r.operating_source;
  out.operating_refused = r.operating_refused;
  auto average = [&](const std::vector<double>& y, std::vector<double>& dest) {
    if (y.empty()) return;
    for (double g : grid) {
      double sum = 0;
      for (int c = 0; c < kept; ++c) sum += interpolate(r.t_s, y, start + c * period + g);
      dest.push_back(sum / kept);
    }
  };
  out.t_s = grid;
  average(r.x_m, out.x_m);
  average(r.v_m_s, out.v_m_s);
  average(r.a_m_s2, out.a_m_s2);
  average(r.F_N, out.F_N);
  for (const auto& [name, column] : r.operating_signals) average(column, out.operating_signals[name]);
  return out;
}

std::map<std::string, double> utfsm_conditions(std::string_view stem) {
  static const std::regex pattern(R"(^([0-9]+(?:x[0-9]+)?)mm([0-9]+(?:x[0-9]+)?)Hz([0-9]+(?:x[0-9]+)?)A$)");
  std::cmatch m;
  const std::string name(stem);
  if (!std::regex_match(name.c_str(), m, pattern))
    throw InputError(fmt::format("'{}': expected a UTFSM file name like 25mm0x25Hz0x75A (amplitude mm, frequency Hz, "
                                 "current A, 'x' as decimal point)",
                                 stem));
  auto number = [](std::string s) {
    std::replace(s.begin(), s.end(), 'x', '.');
    return std::stod(s);
  };
  return {{"amp", number(m[1]) * 1e-3}, {"freq", number(m[2])}, {"I", number(m[3])}};
}

}  // namespace dampbench
