// crfd test grids (docs/models.md (crfd)): 7 motor angles × 6 MTS amplitudes × 5 frequencies, 10 cycles each, as
// MTS records (actuator displacement and force) that `--transform slider-crank` turns into angle and torque, with
// 1 % noise on the torque. The torque is turned into the actuator force by the rig's statics,
// F_e = T·sin γ/(L_AB·sin(θ + γ)) (inverse of SliderCrank::torque). Two truths on the same conditions and file
// names (datasets/README.md):
//   crfd          the GV–NEM (eq. 3.6) with parameters interpolated between the paper's Table 2 (1 Hz–1 mm) and
//                 Table 3 (3 Hz–3 mm) at the same angle: p = (1 − s)·Table2 + s·Table3 with
//                 s = clamp(((A − 1 mm)/2 mm + (f − 1 Hz)/2 Hz)/2, 0, 1): the form of the modified GV–NEM that
//                 Table 8 compares, so a comparison on it is a recovery check;
//   crfd-neutral  a rotary orifice damper none of the compared models is (datasets/synthetic/neutral_truths.hpp).
#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include <fmt/format.h>

#include "datasets/synthetic/neutral_truths.hpp"
#include "datasets/synthetic/synthetic.hpp"
#include "engine/record/differentiate.hpp"
#include "engine/record/record_transforms.hpp"
#include "models/registry.hpp"

namespace dampbench::synthetic {
namespace {

// crfd Tables 2 and 3: J, c_r, α, k_r, β, T_f, η, μ, ξ at 0°, 30°, …, 180°.
constexpr double kTable2[7][9] = {{0.011, 1.784, 0.824, 2.719, 0.929, 0.012, 0.129, 4.963, 49.192},
                                  {0.012, 4.185, 0.886, 3.048, 0.827, 0.028, 0.202, 6.566, 48.944},
                                  {0.011, 6.522, 0.858, 5.498, 0.866, 0.038, 0.228, 7.239, 49.352},
                                  {0.011, 7.321, 0.925, 8.360, 0.87, 0.047, 0.592, 7.678, 46.105},
                                  {0.012, 7.417, 0.817, 10.536, 0.854, 0.041, 0.557, 8.189, 45.436},
                                  {0.010, 9.459, 0.867, 12.634, 0.914, 0.017, 0.692, 8.883, 47.964},
                                  {0.012, 11.398, 0.89, 15.484, 0.891, 0.016, 0.792, 10.140, 49.363}};
constexpr double kTable3[7][9] = {{0.011, 0.277, 0.852, 12.268, 0.907, 0.015, 0.419, 6.865, 48.551},
                                  {0.012, 3.136, 0.857, 16.041, 0.902, 0.016, 0.496, 7.913, 50.475},
                                  {0.011, 4.668, 0.863, 23.772, 0.901, 0.018, 0.494, 7.278, 50.243},
                                  {0.011, 5.632, 0.852, 23.222, 0.849, 0.016, 0.927, 8.586, 46.504},
                                  {0.012, 7.045, 0.868, 28.176, 0.89, 0.025, 0.843, 8.764, 46.724},
                                  {0.011, 8.066, 0.885, 35.740, 0.868, 0.028, 0.908, 8.628, 51.203},
                                  {0.012, 9.991, 0.892, 42.049, 0.865, 0.019, 1.173, 11.012, 52.941}};
constexpr double kAmplitudesMm[] = {0.8, 1, 1.5, 2, 2.5, 3};
constexpr double kFrequenciesHz[] = {1, 2, 3, 4, 5};
constexpr int kCrfdCycles = 10, kCrfdSamplesPerCycle = 100;

std::string mm_label(double v) {
  std::string s = fmt::format("{:g}", v);
  std::replace(s.begin(), s.end(), '.', 'p');
  return s;
}

/// The torque of a grid's truth at angle index `a` (φ = 30°·a) on the rotation `rot` (θ, θ̇, θ̈ at the record's times)
/// made by the MTS motion x_e = A·sin(2πft); `words` receives what the truth is, for the record's header.
using RotaryTruth = std::function<std::vector<double>(int a, double amp_mm, double freq_hz, const Dataset& rot,
                                                      std::string& words)>;

void write_crfd_grid(const std::filesystem::path& dir, std::uint64_t seed, const RotaryTruth& torque) {
  const SliderCrank rig;
  for (int a = 0; a < 7; ++a)
    for (double amp_mm : kAmplitudesMm)
      for (double f : kFrequenciesHz) {
        Record r;
        r.file = fmt::format("phi{:03d}_A{}mm_f{}Hz.csv", 30 * a, mm_label(amp_mm), mm_label(f));
        r.operating = {{"phi", 30.0 * a}, {"amp", amp_mm * 1e-3}, {"freq", f}};
        Dataset rot;
        rot.name = r.file;
        std::vector<SliderCrank::Pose> poses;
        for (int k = 0; k <= kCrfdCycles * kCrfdSamplesPerCycle; ++k) {
          const double t = k / (f * kCrfdSamplesPerCycle), x_e = amp_mm * 1e-3 * std::sin(2 * std::numbers::pi * f * t);
          r.t_s.push_back(t);
          r.x.push_back(x_e * 1e3);
          poses.push_back(rig.solve(x_e));
          rot.t_s.push_back(t);
          rot.x_m.push_back(poses.back().theta_rad);
        }
        rot.v_m_s = differentiate_3rd_order(rot.t_s, rot.x_m);
        rot.a_m_s2 = differentiate_3rd_order(rot.t_s, rot.v_m_s);
        std::string words;
        std::vector<double> T = torque(a, amp_mm, f, rot, words);
        r.description = fmt::format("Synthetic crfd MTS record: phi = {} deg, +-{:g} mm, {:g} Hz, {} cycles; {}, 1 % "
                                    "torque noise (datasets/README.md)",
                                    30 * a, amp_mm, f, kCrfdCycles, words);
        add_noise(T, 0.01, seed, r.file);
        for (std::size_t k = 0; k < T.size(); ++k) {
          const auto& q = poses[k];
          r.F.push_back(T[k] * std::sin(q.gamma_rad) / (rig.L_AB_m * std::sin(q.theta_rad + q.gamma_rad)));
        }
        write_record(dir, r);
      }
}

/// The rig's rotation under x_e = A·sin(2πft) in closed form: θ from the slider-crank, θ̇ and θ̈ by central
/// differences of it (steps of 1e-5 and 1e-4 periods: errors near 1e-10 and 1e-8 relative, far below the noise).
Motion rig_rotation(double amp_mm, double f) {
  const SliderCrank rig;
  auto theta = [=](double t) { return rig.solve(amp_mm * 1e-3 * std::sin(2 * std::numbers::pi * f * t)).theta_rad; };
  const double h1 = 1e-5 / f, h2 = 1e-4 / f;
  return {theta, [=](double t) { return (theta(t + h1) - theta(t - h1)) / (2 * h1); },
          [=](double t) { return (theta(t + h2) - 2 * theta(t) + theta(t - h2)) / (h2 * h2); }};
}

}  // namespace

void write_crfd(const std::filesystem::path& dir, std::uint64_t seed) {
  const Model& gvnem = find_model("crfd.gvnem");
  write_crfd_grid(dir, seed, [&](int a, double amp_mm, double f, const Dataset& rot, std::string& words) {
    const double s = std::clamp(((amp_mm - 1) / 2 + (f - 1) / 2) / 2, 0.0, 1.0);
    std::vector<double> p(9);
    for (int j = 0; j < 9; ++j) p[j] = (1 - s) * kTable2[a][j] + s * kTable3[a][j];
    words = fmt::format("truth GV-NEM interpolated between Tables 2 and 3 (s = {:.3f})", s);
    return gvnem.simulate(p, prepare_signals(rot));
  });
}

void write_crfd_neutral(const std::filesystem::path& dir, std::uint64_t seed) {
  write_crfd_grid(dir, seed, [](int a, double amp_mm, double f, const Dataset& rot, std::string& words) {
    words = "neutral truth: rotary orifice damper (laminar-turbulent orifice behind the oil column, Dahl friction)";
    return rotary_orifice_torque(crfd_orifice_damper(30.0 * a), rig_rotation(amp_mm, f), rot.t_s);
  });
}

}  // namespace dampbench::synthetic
