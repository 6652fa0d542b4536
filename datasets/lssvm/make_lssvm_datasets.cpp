// Writes the synthetic LS-SVM set (lssvm paper §4.1 layout: 15 mm, 2 and 4 Hz, 0, 0.4 and 0.8 A, ~1260
// training samples) from a documented parametric truth (datasets/lssvm/README.md):
//
//   mrd.bouc_wen (models/mrd.cpp): ż = −γ|v| sgn(z)|z|^n − β v|z|^n + A v,  F = c0 v + k0 (x − x0) + α z
//   c0(I) = 400 + 800·I N·s/m,  α(I) = 2e4 + 6e4·I N/m,  k0 = 500 N/m,  x0 = 0,  β = γ = 250 /m,  A = 1,  n = 1
//   (z saturates at A/(β + γ) = 2 mm), plus Gaussian force noise of 1 N (keyed stream: seed, file name).
//
// Each condition is simulated from rest (z = 0 at t = 0) for 3 s of x = 15 mm·sin(2πft) at 2 kHz with the
// exact velocity, and written at 250 Hz (every 8th sample) from t = 1 s on, after the start-up transient:
//   train_<f>Hz_<I>A.csv  212 samples, t = 1 … 1.844 s  (210 regressors each with the default lags: 1260)
//   test_<f>Hz_<I>A.csv   250 samples, t = 2 … 2.996 s  (a later, disjoint window; other noise)
// Test records also at 0.2 and 0.6 A (currents not trained on). Columns t[s], x[mm], v[mm/s], F[N]; the current
// and the test condition are in a "# operating:" comment, which the loader reads.
//
// Usage: make_lssvm_datasets OUTPUT_DIR [seed]   (seed 2024 for the committed files)
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "engine/common/random.hpp"
#include "engine/record/signals.hpp"
#include "models/registry.hpp"

namespace {

constexpr double kAmplitude_m = 0.015;
constexpr double kSimRate_Hz = 2000;
constexpr int kDecimation = 8;  // written at 250 Hz
constexpr double kNoise_N = 1.0;

/// Bouc–Wen parameters at current I [A], in the order of mrd.bouc_wen: c0, k0, x0, alpha, beta, gamma, A, n.
std::vector<double> truth(double I) { return {400 + 800 * I, 500, 0, 2e4 + 6e4 * I, 250, 250, 1, 1}; }

std::string label(double v) {
  std::string s = fmt::format("{:g}", v);
  for (char& ch : s)
    if (ch == '.') ch = 'p';
  return s;
}

void write(const std::filesystem::path& dir, const std::string& kind, double f, double I, double t_from_s, int samples,
           std::uint64_t seed) {
  using namespace dampbench;
  const std::string file = fmt::format("{}_{}Hz_{}A.csv", kind, label(f), label(I));
  const double w = 2 * std::numbers::pi * f;
  const int n = static_cast<int>(std::lround(3.0 * kSimRate_Hz)) + 1;
  Dataset d;
  d.name = file;
  for (int k = 0; k < n; ++k) {
    const double t = k / kSimRate_Hz;
    d.t_s.push_back(t);
    d.x_m.push_back(kAmplitude_m * std::sin(w * t));
    d.v_m_s.push_back(kAmplitude_m * w * std::cos(w * t));
    d.a_m_s2.push_back(-kAmplitude_m * w * w * std::sin(w * t));
  }
  const std::vector<double> F = find_model("mrd.bouc_wen").simulate(truth(I), prepare_signals(d));
  RandomStream noise(hash_key({seed, hash_name(file)}));
  std::filesystem::create_directories(dir);
  std::ofstream out(dir / file);
  out << fmt::format("# Synthetic lssvm record: 15 mm, {:g} Hz, {:g} A; truth mrd.bouc_wen with current-dependent c0 and "
                     "alpha, 1 N noise (datasets/lssvm/README.md)\n",
                     f, I);
  out << fmt::format("# operating: I={:g},amp={:g},freq={:g}\n", I, kAmplitude_m, f);
  out << "t[s],x[mm],v[mm/s],F[N]\n";
  const int first = static_cast<int>(std::lround(t_from_s * kSimRate_Hz));
  for (int j = 0; j < samples; ++j) {
    const int k = first + j * kDecimation;
    out << fmt::format("{:.4f},{:.9g},{:.9g},{:.9g}\n", d.t_s[k], 1e3 * d.x_m[k], 1e3 * d.v_m_s[k],
                       F[k] + kNoise_N * noise.normal());
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: make_lssvm_datasets OUTPUT_DIR [seed]\n");
    return 2;
  }
  try {
    const std::filesystem::path dir = argv[1];
    const std::uint64_t seed = argc > 2 ? std::stoull(argv[2]) : 2024;
    for (double f : {2.0, 4.0}) {
      for (double I : {0.0, 0.4, 0.8}) write(dir, "train", f, I, 1.0, 212, seed);
      for (double I : {0.0, 0.2, 0.4, 0.6, 0.8}) write(dir, "test", f, I, 2.0, 250, seed);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_lssvm_datasets: %s\n", e.what());
    return 2;
  }
  return 0;
}
