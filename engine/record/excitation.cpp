#include "engine/record/excitation.hpp"

#include <cmath>
#include <cstddef>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"

namespace dampbench {
namespace {

constexpr double kMinSamplesPerCycle = 8;
constexpr std::size_t kMinSamples = 8;

/// Number of samples: round(cycles * fs / f) + 1 (both ends included).
std::size_t sample_count(const SineSpec& spec) {
  return static_cast<std::size_t>(std::llround(spec.cycles * spec.fs_hz / sine_frequency_hz(spec))) + 1;
}

void require_positive(double value, std::string_view key, std::string_view origin) {
  if (!(value > 0) || !std::isfinite(value))
    throw InputError(fmt::format("{}: {} must be > 0 (got {:g})", origin, key, value));
}

/// Throws InputError, prefixed by `origin`, unless the spec describes a well-sampled sine.
void validate(const SineSpec& spec, std::string_view origin) {
  require_positive(spec.amplitude_m, "amp", origin);
  if (spec.freq_hz != 0 && spec.peak_velocity_m_s != 0)
    throw InputError(fmt::format("{}: give either freq or vpeak, not both", origin));
  if (spec.freq_hz == 0 && spec.peak_velocity_m_s == 0)
    throw InputError(fmt::format("{}: freq or vpeak is required", origin));
  if (spec.freq_hz != 0)
    require_positive(spec.freq_hz, "freq", origin);
  else
    require_positive(spec.peak_velocity_m_s, "vpeak", origin);
  require_positive(spec.cycles, "cycles", origin);
  require_positive(spec.fs_hz, "fs", origin);
  const double freq = sine_frequency_hz(spec);
  if (spec.fs_hz < kMinSamplesPerCycle * freq)
    throw InputError(
        fmt::format("{}: fs = {:g} Hz gives {:g} samples per cycle at {:g} Hz; at least {:g} are "
                    "needed (fs >= {:g} Hz)",
                    origin, spec.fs_hz, spec.fs_hz / freq, freq, kMinSamplesPerCycle, kMinSamplesPerCycle * freq));
  if (const std::size_t samples = sample_count(spec); samples < kMinSamples)
    throw InputError(
        fmt::format("{}: {} samples (cycles * fs / freq + 1); at least {} are needed", origin, samples, kMinSamples));
}

/// The field of `spec` that `key` sets, or nullptr for an unknown key.
double* field(SineSpec& spec, std::string_view key) {
  if (key == "amp") return &spec.amplitude_m;
  if (key == "freq") return &spec.freq_hz;
  if (key == "vpeak") return &spec.peak_velocity_m_s;
  if (key == "cycles") return &spec.cycles;
  if (key == "fs") return &spec.fs_hz;
  return nullptr;
}

}  // namespace

SineSpec parse_sine_option(std::string_view text) {
  SineSpec spec;
  bool has_amp = false;
  bool has_fs = false;
  for (const auto& [key, value] : parse_key_values(text, "--sine")) {
    double* target = field(spec, key);
    if (target == nullptr)
      throw InputError(fmt::format("--sine: unknown key '{}' (expected amp, freq or vpeak, cycles, fs)", key));
    *target = parse_number(value, fmt::format("--sine {}", key));
    has_amp = has_amp || key == "amp";
    has_fs = has_fs || key == "fs";
  }
  if (!has_amp) throw InputError("--sine: amp is required (displacement amplitude in m)");
  if (!has_fs) throw InputError("--sine: fs is required (sampling rate in Hz)");
  validate(spec, "--sine");
  return spec;
}

double sine_frequency_hz(const SineSpec& spec) {
  if (spec.freq_hz != 0) return spec.freq_hz;
  return spec.peak_velocity_m_s / (2 * std::numbers::pi * spec.amplitude_m);
}

Dataset make_sine(const SineSpec& spec) {
  validate(spec, "sine excitation");
  const double freq = sine_frequency_hz(spec);
  const double omega = 2 * std::numbers::pi * freq;
  const double amp = spec.amplitude_m;
  const std::size_t n = sample_count(spec);
  Dataset data;
  data.name = "sine";
  data.source =
      fmt::format("sine amp={:g} m, freq={:g} Hz, cycles={:g}, fs={:g} Hz", amp, freq, spec.cycles, spec.fs_hz);
  data.t_s.resize(n);
  data.x_m.resize(n);
  data.v_m_s.resize(n);
  data.a_m_s2.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / spec.fs_hz;
    const double phase = omega * t;
    data.t_s[k] = t;
    data.x_m[k] = amp * std::sin(phase);
    data.v_m_s[k] = amp * omega * std::cos(phase);
    data.a_m_s2[k] = -amp * omega * omega * std::sin(phase);
  }
  data.operating["amp"] = amp;
  data.operating["freq"] = freq;
  data.operating_source["amp"] = data.operating_source["freq"] = "sine excitation";
  return data;
}

}  // namespace dampbench
