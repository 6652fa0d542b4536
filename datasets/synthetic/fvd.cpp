// fvd paper Table 2 tests from a truth that is none of the four candidate models (datasets/fvd/README.md):
//
//   F = m·a + C·sgn(v)|v|^α + K1·x + K2·x² + z,   ż = A·v − β|v|·z − γ·v|z|   (Bouc–Wen, n = 1)
//
// plus Gaussian noise of 0.5 % × RMS(F). z is integrated with SUNDIALS CVODE (rtol 1e-10) under the exact
// sinusoidal velocity. Files carry t[s], x[mm], F[kN] only, like a rig record: the loader recomputes v and
// a by 3rd-order differentiation, as in the paper.
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "datasets/synthetic/synthetic.hpp"
#include "engine/kernels/cvode_integrator.hpp"

namespace dampbench::synthetic {
namespace {

struct Truth {
  double m_kg = 300.0;
  double C = 8.204e5;      // N/(m/s)^α: 650 kN of viscous force at 0.46 m/s
  double alpha = 0.3;
  double K1_N_m = 4.0e6;   // 4 kN/mm
  double K2_N_m2 = 3.0e7;  // 0.03 kN/mm²
  double A_N_m = 2.0e7;    // Bouc–Wen: initial stiffness of z, 20 kN/mm
  double beta_1_m = 300.0; // z saturates at A/(β+γ) = 40 kN
  double gamma_1_m = 200.0;
  double noise_rel = 0.005;
};

struct Test {
  const char* file;
  double amplitude_m, peak_velocity_m_s, cycles;
};

constexpr int kSamplesPerCycle = 200;

Record fvd_test(const Truth& truth, const Test& test, std::uint64_t seed) {
  const double X = test.amplitude_m;
  const double w = test.peak_velocity_m_s / X;  // ω = v/X, f = v/(2πX)
  const double f = w / (2 * std::numbers::pi);
  const int n = static_cast<int>(std::lround(test.cycles * kSamplesPerCycle)) + 1;
  Record r;
  r.file = test.file;
  r.description = fmt::format(
      "Synthetic fvd test (fvd paper Table 2): +-{:g} mm, {:g} mm/s peak, {:g} cycles, f = {:.6g} Hz; truth: GV + "
      "quadratic elastic + Bouc-Wen (datasets/fvd/README.md)",
      X * 1e3, test.peak_velocity_m_s * 1e3, test.cycles, f);
  r.operating = {{"amp", X}, {"freq", f}};
  r.F_unit = "kN";
  for (int k = 0; k < n; ++k) r.t_s.push_back(k / (f * kSamplesPerCycle));

  auto velocity = [&](double time) { return X * w * std::cos(w * time); };
  const auto z = integrate_cvode(
      [&](double time, std::span<const double> y, std::span<double> dy) {
        const double v = velocity(time);
        dy[0] = truth.A_N_m * v - truth.beta_1_m * std::fabs(v) * y[0] - truth.gamma_1_m * v * std::fabs(y[0]);
      },
      {0.0}, r.t_s, {1e-10, 1e-6, 100000, /*stop_at_each_time=*/false});

  std::vector<double> F(n);
  for (int k = 0; k < n; ++k) {
    const double x = X * std::sin(w * r.t_s[k]);
    const double v = velocity(r.t_s[k]), a = -w * w * x;
    const double sgn = (v > 0) - (v < 0);
    F[k] = truth.m_kg * a + truth.C * sgn * std::pow(std::fabs(v), truth.alpha) + truth.K1_N_m * x +
           truth.K2_N_m2 * x * x + z[k][0];
    r.x.push_back(x * 1e3);
  }
  add_noise(F, truth.noise_rel, seed, test.file);
  for (double& v : F) v *= 1e-3;  // kN
  r.F = std::move(F);
  return r;
}

}  // namespace

void write_fvd(const std::filesystem::path& dir, std::uint64_t seed) {
  const Truth truth;
  const Test tests[] = {{"test1_20mm_92mms.csv", 0.020, 0.092, 3},
                        {"test2_20mm_230mms.csv", 0.020, 0.230, 3},
                        {"test3_20mm_460mms.csv", 0.020, 0.460, 3},
                        {"test4_17mm_460mms.csv", 0.017, 0.460, 10}};
  for (const auto& test : tests) write_record(dir, fvd_test(truth, test, seed));
}

}  // namespace dampbench::synthetic
