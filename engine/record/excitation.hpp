#pragma once
// Synthetic sinusoidal displacement inputs (for simulate and for synthetic reference datasets).
#include <string_view>

#include "engine/record/dataset.hpp"

namespace dampbench {

/// A sinusoidal displacement x = X sin(2π f t), given by amplitude and frequency or peak velocity.
struct SineSpec {
  double amplitude_m = 0;        ///< displacement amplitude [m]
  double freq_hz = 0;            ///< frequency [Hz]; or 0 when peak_velocity_m_s is given (f = v/(2πX))
  double peak_velocity_m_s = 0;  ///< peak velocity X·2πf [m/s]; 0 when freq_hz is given
  double cycles = 1;             ///< number of periods (need not be whole)
  double fs_hz = 0;              ///< sampling rate [Hz]
};

/// Parses "amp=0.02,freq=1,cycles=3,fs=500" (or vpeak=0.46 instead of freq; SI units). Validates: amp>0,
/// exactly one of freq/vpeak >0, cycles>0, fs>0, fs >= 8*freq (at least 8 samples per cycle), and at least 8 samples;
/// unknown keys rejected ("--sine: unknown key 'ampl' (expected amp, freq or vpeak, cycles, fs)"). cycles defaults to
/// 1; the others are required. Messages start with "--sine: ".
SineSpec parse_sine_option(std::string_view text);

/// The frequency of `spec`: freq_hz, or peak_velocity_m_s / (2π amplitude_m) when freq_hz is 0.
double sine_frequency_hz(const SineSpec& spec);

/// x = X sin(2π f t), t = k/fs for k = 0 .. round(cycles*fs/f) inclusive; v and a analytic (exact). F empty.
/// operating["amp"] = X, operating["freq"] = f. name "sine". Throws InputError ("sine excitation: ...") for a
/// spec that parse_sine_option would reject.
Dataset make_sine(const SineSpec& spec);

}  // namespace dampbench
