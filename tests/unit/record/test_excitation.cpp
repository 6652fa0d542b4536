// Tests for engine/excitation: --sine parsing and validation, and the sampled sine with analytic v and a.
#include "engine/record/excitation.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "engine/common/error.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

using testing::error_of;

std::string sine_error(const char* text) {
  return error_of([&] { parse_sine_option(text); });
}

using testing::HasText;

TEST(SineOption, ParsesAllKeys) {
  const SineSpec spec = parse_sine_option("amp=0.02,freq=1,cycles=3,fs=500");
  EXPECT_DOUBLE_EQ(spec.amplitude_m, 0.02);
  EXPECT_DOUBLE_EQ(spec.freq_hz, 1.0);
  EXPECT_DOUBLE_EQ(spec.peak_velocity_m_s, 0.0);
  EXPECT_DOUBLE_EQ(spec.cycles, 3.0);
  EXPECT_DOUBLE_EQ(spec.fs_hz, 500.0);
}

TEST(SineOption, CyclesDefaultToOne) { EXPECT_DOUBLE_EQ(parse_sine_option("amp=0.01,freq=2,fs=100").cycles, 1.0); }

TEST(SineOption, FrequencyFromPeakVelocity) {
  const SineSpec spec = parse_sine_option("amp=0.02,vpeak=0.46,cycles=2,fs=200");
  EXPECT_DOUBLE_EQ(spec.freq_hz, 0.0);
  // f = v / (2π X) = 0.46 / (2π · 0.02) = 3.6606 Hz
  EXPECT_NEAR(sine_frequency_hz(spec), 3.6606, 1e-4);
  const Dataset data = make_sine(spec);
  EXPECT_NEAR(data.operating.at("freq"), 3.66, 0.005);
  EXPECT_NEAR(data.v_m_s.front(), 0.46, 1e-12);  // v(0) = X ω = the peak velocity
}

TEST(SineOption, RejectsUnknownKey) {
  EXPECT_EQ(sine_error("ampl=0.02,freq=1,fs=500"),
            "--sine: unknown key 'ampl' (expected amp, freq or vpeak, cycles, fs)");
}

TEST(SineOption, RejectsNonNumbers) {
  EXPECT_EQ(sine_error("amp=1.2x,freq=1,fs=500"), "--sine amp: expected a number, got '1.2x'");
  EXPECT_TRUE(HasText(sine_error("amp=0.02,freq=inf,fs=500"), "--sine freq: expected a finite number"));
  EXPECT_TRUE(HasText(sine_error("amp=0.02,freq"), "--sine: expected name=value, got 'freq'"));
}

TEST(SineOption, RejectsMissingOrNonPositiveValues) {
  EXPECT_EQ(sine_error("freq=1,fs=500"), "--sine: amp is required (displacement amplitude in m)");
  EXPECT_EQ(sine_error("amp=0.02,freq=1"), "--sine: fs is required (sampling rate in Hz)");
  EXPECT_EQ(sine_error("amp=0,freq=1,fs=500"), "--sine: amp must be > 0 (got 0)");
  EXPECT_EQ(sine_error("amp=-0.01,freq=1,fs=500"), "--sine: amp must be > 0 (got -0.01)");
  EXPECT_EQ(sine_error("amp=0.02,freq=-1,fs=500"), "--sine: freq must be > 0 (got -1)");
  EXPECT_EQ(sine_error("amp=0.02,vpeak=-0.1,fs=500"), "--sine: vpeak must be > 0 (got -0.1)");
  EXPECT_EQ(sine_error("amp=0.02,freq=1,cycles=0,fs=500"), "--sine: cycles must be > 0 (got 0)");
  EXPECT_EQ(sine_error("amp=0.02,freq=1,fs=-5"), "--sine: fs must be > 0 (got -5)");
}

TEST(SineOption, RequiresExactlyOneOfFreqAndVpeak) {
  EXPECT_EQ(sine_error("amp=0.02,fs=500"), "--sine: freq or vpeak is required");
  EXPECT_EQ(sine_error("amp=0.02,freq=1,vpeak=0.1,fs=500"), "--sine: give either freq or vpeak, not both");
}

TEST(SineOption, RequiresEightSamplesPerCycle) {
  EXPECT_EQ(sine_error("amp=0.01,freq=10,fs=50"),
            "--sine: fs = 50 Hz gives 5 samples per cycle at 10 Hz; at least 8 are needed (fs >= 80 Hz)");
  EXPECT_NO_THROW(parse_sine_option("amp=0.01,freq=10,fs=80"));
}

TEST(SineOption, RequiresEightSamples) {
  // 0.5 cycles at 8 samples per cycle: round(0.5 · 8 / 1) + 1 = 5 samples
  EXPECT_EQ(sine_error("amp=0.01,freq=1,cycles=0.5,fs=8"),
            "--sine: 5 samples (cycles * fs / freq + 1); at least 8 are needed");
}

TEST(MakeSine, SampleCountAndEndpoints) {
  const Dataset data = make_sine(parse_sine_option("amp=0.02,freq=1,cycles=3,fs=500"));
  ASSERT_EQ(data.size(), 1501u);  // 3 s at 500 Hz, both ends included
  ASSERT_EQ(data.x_m.size(), 1501u);
  ASSERT_EQ(data.v_m_s.size(), 1501u);
  ASSERT_EQ(data.a_m_s2.size(), 1501u);
  EXPECT_DOUBLE_EQ(data.t_s.front(), 0.0);
  EXPECT_DOUBLE_EQ(data.t_s.back(), 3.0);
  EXPECT_DOUBLE_EQ(data.t_s[1], 0.002);
  EXPECT_NEAR(data.x_m.front(), 0.0, 1e-15);
  EXPECT_NEAR(data.x_m.back(), 0.0, 1e-15);
  EXPECT_FALSE(data.has_force());
  EXPECT_EQ(data.name, "sine");
  EXPECT_DOUBLE_EQ(data.operating.at("amp"), 0.02);
  EXPECT_DOUBLE_EQ(data.operating.at("freq"), 1.0);
}

TEST(MakeSine, AnalyticVelocityAndAcceleration) {
  const Dataset data = make_sine(parse_sine_option("amp=0.02,freq=1,cycles=3,fs=500"));
  const double omega = 2 * std::numbers::pi;
  // t = 0: x = 0, v = X ω = 0.12566..., a = 0
  EXPECT_NEAR(data.v_m_s[0], 0.12566370614359174, 1e-14);
  EXPECT_NEAR(data.a_m_s2[0], 0.0, 1e-14);
  // t = 0.25 s (k = 125): x = X, v = 0, a = -X ω² = -0.78956835...
  EXPECT_NEAR(data.x_m[125], 0.02, 1e-15);
  EXPECT_NEAR(data.v_m_s[125], 0.0, 1e-14);
  EXPECT_NEAR(data.a_m_s2[125], -0.7895683520871486, 1e-13);
  // t = 0.5 s (k = 250): v = -X ω
  EXPECT_NEAR(data.v_m_s[250], -0.12566370614359174, 1e-14);
  // everywhere: a = -ω² x
  for (std::size_t k = 0; k < data.size(); ++k) EXPECT_NEAR(data.a_m_s2[k], -omega * omega * data.x_m[k], 1e-13);
}

TEST(MakeSine, RejectsInvalidSpec) {
  SineSpec spec;
  spec.freq_hz = 1;
  spec.fs_hz = 100;
  EXPECT_EQ(error_of([&] { make_sine(spec); }), "sine excitation: amp must be > 0 (got 0)");
  spec.amplitude_m = 0.01;
  spec.fs_hz = 4;
  EXPECT_TRUE(HasText(error_of([&] { make_sine(spec); }), "sine excitation: fs = 4 Hz gives 4 samples per cycle"));
}

}  // namespace
}  // namespace dampbench
