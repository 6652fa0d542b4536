#pragma once
// The training data of the hysteretic benchmark (Noël & Schoukens 2016; datasets/README.md), made as the benchmark
// prescribes: a random-phase multisine force of 5–150 Hz and RMS 50 N, 8192 samples per period at 750 Hz, the true
// structure stepped by Newmark at 15 kHz, band-limited output noise of RMS 8e−3 mm, MATLAB-style FIR decimation in
// steps 2·2·5. The true parameters (the benchmark's Table 1) appear here and nowhere in the identification path.
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "engine/kernels/newmark.hpp"
#include "engine/record/dataset.hpp"

namespace dampbench::synthetic {

/// The benchmark's constants (its section 2 and Table 1).
struct BoucWenBenchmark {
  static constexpr double kSampleRate_Hz = 750;
  static constexpr int kUpsampling = 20;  ///< integration at 15 kHz
  static constexpr int kPeriodSamples = 8192;
  static constexpr int kFirstLine = 55, kLastLine = 1639;  ///< excited lines: 5.035–150.055 Hz
  static constexpr int kPeriods = 5;                       ///< kept periods (one more is simulated and dropped)
  static constexpr double kInputRms_N = 50;
  static constexpr double kNoiseRms_m = 8e-6;
  static constexpr double kNoiseBand_Hz = 375;
  /// m, c, k, α, βγ = 10³·0.8, βδ = 10³·(−1.1), ν.
  static constexpr HystereticStructure kTruth{2, 10, 5e4, 5e4, 800, -1100, 1};
};

/// One period of the multisine at 15 kHz (163 840 samples): lines kFirstLine…kLastLine of unit amplitude and phases
/// uniform on [0, 2π) from the stream (seed, "bouc-wen-benchmark", "phases"), scaled to 50 N by the sample standard
/// deviation (divisor n − 1, as MATLAB's std).
std::vector<double> benchmark_multisine(std::uint64_t seed);

/// The structure stepped from rest through a 15 kHz input: y at every input sample. Throws std::runtime_error when a
/// Newton iteration misses its tolerance (the truth never should).
std::vector<double> newmark_response(const HystereticStructure& structure, double h_s, std::span<const double> u_N);

/// White Gaussian noise at 15 kHz from the stream (seed, "bouc-wen-benchmark", "noise"), band-limited to 0–375 Hz
/// (FFT bins above zeroed) and scaled to an RMS of exactly kNoiseRms_m.
std::vector<double> benchmark_output_noise(std::uint64_t seed, std::size_t samples);

/// The training record: 5 periods (40 960 samples, t = k/750 s) of u and the noisy, decimated y, as columns t, y, u.
Dataset bouc_wen_training_record(std::uint64_t seed);

/// A sine sweep u = 40·sin(2π(20·t + t²/12)) N (20 → 50 Hz at 10 Hz/min, 180 s) applied from rest to the true
/// structure, without noise, decimated like the training data: the non-periodic check of an identified model.
Dataset bouc_wen_sweep_record();

/// Writes training_seed<S>.csv and sweep_40N_20-50Hz.csv (t[s],y[m],u[N], %.17g) into `dir`.
void write_bouc_wen_benchmark(const std::filesystem::path& dir, std::uint64_t seed);

}  // namespace dampbench::synthetic
