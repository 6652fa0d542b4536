#include "datasets/synthetic/neutral_truths.hpp"

#include <cmath>
#include <numbers>

#include "engine/common/vector_math.hpp"
#include "engine/kernels/cvode_integrator.hpp"

namespace dampbench::synthetic {
namespace {

// The motions are smooth in time, so CVODE steps across the sample times freely (as the fvd generator does).
const CvodeSettings kTruthSettings{1e-10, 1e-9, 200000, /*stop_at_each_time=*/false};

}  // namespace

Motion sine_motion(double amp, double freq) {
  const double w = 2 * std::numbers::pi * freq;
  return {[=](double t) { return amp * std::sin(w * t); }, [=](double t) { return amp * w * std::cos(w * t); },
          [=](double t) { return -amp * w * w * std::sin(w * t); }};
}

MrValveDamper mfm_valve_damper(double current_A) {
  const double saturation = std::tanh(current_A / 1.2);
  MrValveDamper d;
  d.yield_N = 60 + 900 * saturation;
  d.viscous_N = 1500 + 700 * saturation;
  d.flow_exponent = 0.7;
  d.leak_N_s_m = 8e4;
  d.column_N_m = 2e6;
  d.seal_friction_N = 25;
  d.gas_N = 150;
  return d;
}

MrValveDamper fdsp_valve_damper() {
  return {.yield_N = 40, .viscous_N = 900, .flow_exponent = 0.6, .leak_N_s_m = 2e4, .column_N_m = 2e5,
          .seal_friction_N = 15, .gas_N = 200};
}

std::vector<double> mr_valve_force(const MrValveDamper& d, const Motion& motion, std::span<const double> t_s) {
  const double inverse_exponent = 1 / d.flow_exponent;
  auto flow_velocity = [&](double f) {
    const double excess = std::fabs(f) - d.yield_N;
    const double through_valve = excess > 0 ? sign(f) * std::pow(excess / d.viscous_N, inverse_exponent) : 0.0;
    return through_valve + f / d.leak_N_s_m;
  };
  const auto valve = integrate_cvode(
      [&](double t, std::span<const double> y, std::span<double> dy) {
        dy[0] = d.column_N_m * (motion.v(t) - flow_velocity(y[0]));
      },
      {0.0}, t_s, kTruthSettings);
  std::vector<double> F(t_s.size());
  for (std::size_t k = 0; k < t_s.size(); ++k) {
    const double x = motion.x(t_s[k]), v = motion.v(t_s[k]);
    F[k] = valve[k][0] + d.seal_friction_N * std::tanh(v / d.seal_velocity_m_s) +
           d.gas_N * (std::pow(1 - x / d.gas_length_m, -1.4) - 1);
  }
  return F;
}

RotaryOrificeDamper crfd_orifice_damper(double phi_deg) {
  const double half = 0.5 * phi_deg * std::numbers::pi / 180;
  const double opening = 0.2 + 0.8 * std::cos(half) * std::cos(half);
  RotaryOrificeDamper d;
  d.inertia_kg_m2 = 0.008;
  d.laminar_N_m_s = 2 / opening;
  d.turbulent_N_m_s2 = 0.1 / (opening * opening);
  d.column_N_m_rad = 1500;
  d.friction_N_m = 0.12;
  d.friction_1_rad = 150;
  d.spring_N_m_rad = 8;
  d.spring3_N_m_rad3 = 3000;
  return d;
}

std::vector<double> rotary_orifice_torque(const RotaryOrificeDamper& d, const Motion& motion,
                                          std::span<const double> t_s) {
  // ω(T) inverts T = c_l·ω + c_t·ω|ω| (the root of the quadratic that has ω's sign, written without cancellation).
  auto flow_rate = [&](double T) {
    return 2 * T / (d.laminar_N_m_s + std::sqrt(d.laminar_N_m_s * d.laminar_N_m_s + 4 * d.turbulent_N_m_s2 * std::fabs(T)));
  };
  const auto states = integrate_cvode(
      [&](double t, std::span<const double> y, std::span<double> dy) {
        const double w = motion.v(t);
        dy[0] = d.column_N_m_rad * (w - flow_rate(y[0]));
        dy[1] = d.friction_1_rad * w * (1 - y[1] * sign(w));
      },
      {0.0, 0.0}, t_s, kTruthSettings);
  std::vector<double> T(t_s.size());
  for (std::size_t k = 0; k < t_s.size(); ++k) {
    const double th = motion.x(t_s[k]);
    T[k] = d.inertia_kg_m2 * motion.a(t_s[k]) + states[k][0] + d.friction_N_m * states[k][1] +
           d.spring_N_m_rad * th + d.spring3_N_m_rad3 * th * th * th;
  }
  return T;
}

}  // namespace dampbench::synthetic
