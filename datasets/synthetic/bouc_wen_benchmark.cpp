#include "datasets/synthetic/bouc_wen_benchmark.hpp"

#include <cmath>
#include <complex>
#include <fstream>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>
#include <unsupported/Eigen/FFT>

#include "engine/common/error.hpp"
#include "engine/common/random.hpp"
#include "engine/record/decimate.hpp"

namespace dampbench::synthetic {
namespace {

using B = BoucWenBenchmark;
constexpr std::size_t kFineSamples = static_cast<std::size_t>(B::kPeriodSamples) * B::kUpsampling;
constexpr double kFineStep_s = 1.0 / (B::kSampleRate_Hz * B::kUpsampling);
constexpr int kDecimationSteps[] = {2, 2, 5};  // MATLAB's factor(20), in that order

std::uint64_t stream_key(std::uint64_t seed, std::string_view what) {
  return hash_key({seed, hash_name("bouc-wen-benchmark"), hash_name(what)});
}

/// Every 20th sample from the first: the 750 Hz samples of a 15 kHz signal.
std::vector<double> every_upsampled(std::span<const double> fine, std::size_t count) {
  std::vector<double> out(count);
  for (std::size_t k = 0; k < count; ++k) out[k] = fine[k * B::kUpsampling];
  return out;
}

/// A t, y, u record at 750 Hz from a 15 kHz input and output; y is decimated, u sampled.
Dataset system_record(std::string name, std::string source, std::span<const double> u_fine,
                      std::span<const double> y_fine, std::size_t samples) {
  Dataset d;
  d.name = std::move(name);
  d.source = std::move(source);
  const std::vector<double> y = decimate_fir_cascade(y_fine, kDecimationSteps);
  d.y_m.assign(y.begin(), y.begin() + static_cast<std::ptrdiff_t>(samples));
  d.u_N = every_upsampled(u_fine, samples);
  d.t_s.resize(samples);
  for (std::size_t k = 0; k < samples; ++k) d.t_s[k] = static_cast<double>(k) / B::kSampleRate_Hz;
  return d;
}

void write_system_csv(const std::filesystem::path& path, const Dataset& d, const std::string& description) {
  std::ofstream out(path);
  if (!out) throw InputError(fmt::format("cannot write '{}'", path.string()));
  out << "# " << description << "\n";
  out << "t[s],y[m],u[N]\n";
  for (std::size_t k = 0; k < d.size(); ++k) out << fmt::format("{:.17g},{:.17g},{:.17g}\n", d.t_s[k], d.y_m[k], d.u_N[k]);
  if (!out) throw InputError(fmt::format("cannot write '{}'", path.string()));
}

}  // namespace

std::vector<double> benchmark_multisine(std::uint64_t seed) {
  RandomStream phases(stream_key(seed, "phases"));
  std::vector<std::complex<double>> spectrum(kFineSamples);
  for (int line = B::kFirstLine; line <= B::kLastLine; ++line)
    spectrum[static_cast<std::size_t>(line)] = std::polar(1.0, 2 * std::numbers::pi * phases.uniform());
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> signal;
  fft.inv(signal, spectrum);
  std::vector<double> u(kFineSamples);
  double mean = 0;
  for (std::size_t n = 0; n < u.size(); ++n) {
    u[n] = 2 * signal[n].real();
    mean += u[n];
  }
  mean /= static_cast<double>(u.size());
  double sum_sq = 0;
  for (double value : u) sum_sq += (value - mean) * (value - mean);
  const double scale = B::kInputRms_N / std::sqrt(sum_sq / static_cast<double>(u.size() - 1));
  for (double& value : u) value *= scale;
  return u;
}

std::vector<double> newmark_response(const HystereticStructure& structure, double h_s, std::span<const double> u_N) {
  std::vector<double> y(u_N.size());
  StructureState state = structure_at_rest(structure, u_N[0]);
  for (std::size_t n = 1; n < u_N.size(); ++n) {
    if (!newmark_step(structure, h_s, u_N[n], state))
      throw std::runtime_error(fmt::format("Newmark: Newton missed its tolerance at step {}", n));
    y[n] = state.y_m;
  }
  return y;
}

std::vector<double> benchmark_output_noise(std::uint64_t seed, std::size_t samples) {
  RandomStream stream(stream_key(seed, "noise"));
  std::vector<std::complex<double>> white(samples);
  for (auto& value : white) value = stream.normal();
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> spectrum;
  fft.fwd(spectrum, white);
  const double fine_rate = B::kSampleRate_Hz * B::kUpsampling;
  for (std::size_t k = 0; k < samples; ++k) {
    const double frequency_Hz = static_cast<double>(std::min(k, samples - k)) * fine_rate / static_cast<double>(samples);
    if (frequency_Hz > B::kNoiseBand_Hz) spectrum[k] = 0;
  }
  std::vector<std::complex<double>> band;
  fft.inv(band, spectrum);
  std::vector<double> noise(samples);
  double sum_sq = 0;
  for (std::size_t n = 0; n < samples; ++n) {
    noise[n] = band[n].real();
    sum_sq += noise[n] * noise[n];
  }
  const double scale = B::kNoiseRms_m / std::sqrt(sum_sq / static_cast<double>(samples));
  for (double& value : noise) value *= scale;
  return noise;
}

Dataset bouc_wen_training_record(std::uint64_t seed) {
  const std::vector<double> period = benchmark_multisine(seed);
  std::vector<double> u;  // the kept periods and one more, whose samples absorb the decimation filter's end
  for (int p = 0; p <= B::kPeriods; ++p) u.insert(u.end(), period.begin(), period.end());
  std::vector<double> y = newmark_response(B::kTruth, kFineStep_s, u);
  const std::vector<double> noise = benchmark_output_noise(seed, y.size());
  for (std::size_t n = 0; n < y.size(); ++n) y[n] += noise[n];
  return system_record(fmt::format("training_seed{}", seed), "dampbench datasets bouc-wen-benchmark", u, y,
                       static_cast<std::size_t>(B::kPeriods) * B::kPeriodSamples);
}

Dataset bouc_wen_sweep_record() {
  constexpr double kAmplitude_N = 40, kStart_Hz = 20, kRate_Hz_s = 10.0 / 60, kDuration_s = 180;
  const auto fine = static_cast<std::size_t>(kDuration_s / kFineStep_s + 0.5) + 1;
  std::vector<double> u(fine);
  for (std::size_t n = 0; n < fine; ++n) {
    const double t = static_cast<double>(n) * kFineStep_s;
    u[n] = kAmplitude_N * std::sin(2 * std::numbers::pi * (kStart_Hz * t + 0.5 * kRate_Hz_s * t * t));
  }
  const std::vector<double> y = newmark_response(B::kTruth, kFineStep_s, u);
  return system_record("sweep_40N_20-50Hz", "dampbench datasets bouc-wen-benchmark", u, y,
                       (fine - 1) / B::kUpsampling + 1);
}

void write_bouc_wen_benchmark(const std::filesystem::path& dir, std::uint64_t seed) {
  std::filesystem::create_directories(dir);
  write_system_csv(dir / fmt::format("training_seed{}.csv", seed), bouc_wen_training_record(seed),
                   fmt::format("hysteretic benchmark training data (Noel & Schoukens 2016), made by dampbench: seed {}, "
                               "multisine lines {}-{} of 8192 at 750 Hz, RMS 50 N, 5 periods from rest; Newmark at "
                               "15 kHz; output noise RMS 8e-6 m band-limited to 375 Hz; FIR decimation 2*2*5",
                               seed, B::kFirstLine, B::kLastLine));
  write_system_csv(dir / "sweep_40N_20-50Hz.csv", bouc_wen_sweep_record(),
                   "sine sweep 40 N, 20 -> 50 Hz at 10 Hz/min, from rest, through the benchmark's true structure "
                   "(Newmark at 15 kHz, FIR decimation 2*2*5), no noise; made by dampbench");
}

}  // namespace dampbench::synthetic
