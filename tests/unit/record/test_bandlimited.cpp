// Tests for engine/record/bandlimited: FFT interpolation reproduces trigonometric polynomials below Nyquist (odd and
// even N, the benchmark's multisine shape) and treats the Nyquist bin as interpft does; the not-a-knot spline is
// exact on cubics, passes through the samples and converges as h⁴; both match MATLAB-equivalent references.
#include "engine/record/bandlimited.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "tests/test_support.hpp"

#include "engine/common/error.hpp"

namespace dampbench {
namespace {

// Made by tests/unit/record/signal_chain_reference.py: MATLAB's interpft transcribed in numpy, interpft(lehmer(10,
// 4242), 30) and interpft(lehmer(9, 4243), 18), and scipy's not-a-knot CubicSpline through lehmer(8, 99) at thirds.
const std::vector<double> kInterpftEven = {
    -0.40464859548956156, -0.42819828639686242, -0.16736676053271277,
    0.20764926634728914, 0.48717114591409949, 0.55796767458664132,
    0.43775175604969263, 0.21181633080991696, -0.044258540425825513,
    -0.28496264666318893, -0.46591975407255964, -0.52796742146621389,
    -0.4319122452288866, -0.21096089696101217, 0.026175922551106224,
    0.16401208657771343, 0.16528672744483597, 0.09020319154827805,
    0.02744611818343401, 0.003720775497821105, -0.035186846243850212,
    -0.14841731172055006, -0.3057449104163153, -0.37999104971164016,
    -0.25204615993425256, 0.060590427553730251, 0.37835952900121128,
    0.47981938673183322, 0.27693009547986858, -0.10324404445347177,
};
const std::vector<double> kInterpftOdd = {
    -0.40462611755356193, 0.044680212189659868, 0.29268171545118093,
    0.20173003657287736, 0.039104361552745139, -0.11544177323734016,
    -0.39335136953741312, -0.64022933103932467, -0.46395654324442137,
    0.079571565308260331, 0.35370185831561679, 0.0014318414765075694,
    -0.45757805742323399, -0.32383248692201583, 0.24959107628092159,
    0.45853856212337679, 0.010860005393624306, -0.48002169723654275,
};
const std::vector<double> kSpline = {
    -0.49777468433603644, -0.36680130352582413, -0.21992797132296393,
    -0.081787534989416599, 0.022987158212857392, 0.069763261021897588,
    0.033907926175743341, -0.087534226652639074, -0.21080871005057628,
    -0.23048356967046857, -0.080341467572668371, 0.14897646855066035,
    0.32761449459940195, 0.36343522718223231, 0.31517472574299732,
    0.27928741043433547, 0.32527206471645137, 0.41480492527981588,
    0.48260659212246537, 0.46339766524243703, 0.29189874463776749,
    -0.097169569693505764,
};

/// A real trigonometric polynomial Σ a_k cos(2πkt + φ_k) over lines [first, last], t in periods.
struct TrigPolynomial {
  std::vector<int> lines;
  std::vector<double> amplitudes, phases;
  TrigPolynomial(int first, int last, std::uint64_t seed) {
    std::mt19937_64 engine(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int k = first; k <= last; ++k) {
      lines.push_back(k);
      amplitudes.push_back(k == 0 ? unit(engine) : 0.5 + unit(engine));
      phases.push_back(k == 0 ? 0.0 : 2 * std::numbers::pi * unit(engine));
    }
  }
  /// The value at t = i/m periods; k·i is reduced modulo m in integers, so that the cosines' arguments stay below
  /// 2π + φ and the reference is accurate to rounding rather than to k·t's.
  double operator()(std::size_t i, std::size_t m) const {
    double sum = 0;
    for (std::size_t l = 0; l < lines.size(); ++l) {
      const auto cycles = static_cast<double>(static_cast<std::size_t>(lines[l]) * i % m) / static_cast<double>(m);
      sum += amplitudes[l] * std::cos(2 * std::numbers::pi * cycles + phases[l]);
    }
    return sum;
  }
};

/// Largest |upsample_periodic − p| over every `stride`-th fine point of one period sampled at n points.
double periodic_error(const TrigPolynomial& p, std::size_t n, int factor, std::size_t stride) {
  std::vector<double> x(n);
  for (std::size_t k = 0; k < n; ++k) x[k] = p(k, n);
  const std::vector<double> fine = upsample_periodic(x, factor);
  EXPECT_EQ(fine.size(), n * factor);
  double worst = 0;
  for (std::size_t i = 0; i < fine.size(); i += stride)
    worst = std::max(worst, std::abs(fine[i] - p(i, fine.size())));
  return worst;
}

void expect_near_all(const std::vector<double>& got, const std::vector<double>& want, double tol) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], want[i], tol) << "index " << i;
}

TEST(UpsamplePeriodic, ReproducesTrigPolynomialsBelowNyquist) {
  // Every line up to just below N/2, the constant included, for odd and even N and several factors.
  for (std::size_t n : {37U, 40U, 64U, 81U}) {
    const TrigPolynomial p(0, static_cast<int>((n - 1) / 2), 1000 + n);
    for (int factor : {2, 3, 5, 20})
      EXPECT_LT(periodic_error(p, n, factor, 1), 1e-12) << "n " << n << " factor " << factor;
  }
}

// The benchmark's shape: 8192 points per period, lines 55…1639, to 15 kHz (factor 20, 163 840 = 2¹⁵·5 points).
TEST(UpsamplePeriodic, ReproducesBenchmarkMultisine) {
  const TrigPolynomial p(55, 1639, 7);
  EXPECT_LT(periodic_error(p, 8192, 20, 97), 1e-12);  // the signal's RMS is 29
}

// The Nyquist line cos(πk) of an even N comes back as the cosine cos(2π·(N/2)·t), as interpft's split makes it.
TEST(UpsamplePeriodic, KeepsNyquistLineAsCosine) {
  const std::size_t n = 12;
  std::vector<double> x(n);
  for (std::size_t k = 0; k < n; ++k) x[k] = k % 2 == 0 ? 1.0 : -1.0;
  const std::vector<double> fine = upsample_periodic(x, 4);
  for (std::size_t i = 0; i < fine.size(); ++i)
    EXPECT_NEAR(fine[i], std::cos(std::numbers::pi * static_cast<double>(i) / 4), 1e-14) << "i " << i;
}

TEST(UpsamplePeriodic, FactorOneIsIdentityAndBadInputRefused) {
  const std::vector<double> x = testing::lehmer(11, 3);
  EXPECT_EQ(upsample_periodic(x, 1), x);
  EXPECT_THROW(upsample_periodic(x, 0), InputError);
  EXPECT_THROW(upsample_periodic(std::vector<double>{}, 2), InputError);
}

TEST(UpsamplePeriodic, MatchesInterpftTranscription) {
  expect_near_all(upsample_periodic(testing::lehmer(10, 4242), 3), kInterpftEven, 1e-15);
  expect_near_all(upsample_periodic(testing::lehmer(9, 4243), 2), kInterpftOdd, 1e-15);
}

// Not-a-knot makes a cubic through the samples the spline itself, from 4 samples (one cubic) up.
TEST(UpsampleSpline, ReproducesCubicsExactly) {
  const auto cubic = [](double t) { return 1.5 - 2.0 * t + 0.75 * t * t - 0.125 * t * t * t; };
  for (std::size_t n : {4U, 5U, 6U, 7U, 30U}) {
    std::vector<double> x(n);
    for (std::size_t k = 0; k < n; ++k) x[k] = cubic(static_cast<double>(k));
    const double scale = std::max(std::abs(x.front()), std::abs(x.back()));
    for (int factor : {1, 3, 7}) {
      const std::vector<double> fine = upsample_spline(x, factor);
      ASSERT_EQ(fine.size(), (n - 1) * factor + 1);
      for (std::size_t i = 0; i < fine.size(); ++i)
        EXPECT_NEAR(fine[i], cubic(static_cast<double>(i) / factor), 1e-12 * scale) << "n " << n << " i " << i;
    }
  }
}

TEST(UpsampleSpline, LineAndParabolaFromTwoAndThreeSamples) {
  expect_near_all(upsample_spline(std::vector<double>{1.0, 3.0}, 4), {1.0, 1.5, 2.0, 2.5, 3.0}, 1e-15);
  // 1, 2, 5 are t² + 1 at t = 0, 1, 2.
  expect_near_all(upsample_spline(std::vector<double>{1.0, 2.0, 5.0}, 2), {1.0, 1.25, 2.0, 3.25, 5.0}, 1e-15);
  EXPECT_THROW(upsample_spline(std::vector<double>{1.0}, 2), InputError);
  EXPECT_THROW(upsample_spline(std::vector<double>{1.0, 2.0}, 0), InputError);
}

TEST(UpsampleSpline, PassesThroughSamples) {
  const std::vector<double> x = testing::lehmer(500, 17);
  const std::vector<double> fine = upsample_spline(x, 20);
  for (std::size_t k = 0; k < x.size(); ++k) EXPECT_EQ(fine[k * 20], x[k]) << "k " << k;
}

/// Largest spline error for sin(t + 0.3) sampled with step h over [0, 2], evaluated at tenths of a step.
double spline_sine_error(int intervals) {
  const double h = 2.0 / intervals;
  std::vector<double> x(intervals + 1);
  for (int k = 0; k <= intervals; ++k) x[k] = std::sin(k * h + 0.3);
  const std::vector<double> fine = upsample_spline(x, 10);
  double worst = 0;
  for (std::size_t i = 0; i < fine.size(); ++i)
    worst = std::max(worst, std::abs(fine[i] - std::sin(static_cast<double>(i) * h / 10 + 0.3)));
  return worst;
}

TEST(UpsampleSpline, ConvergesAsFourthPowerOfStep) {
  double previous = spline_sine_error(10);
  for (int intervals : {20, 40, 80}) {
    const double error = spline_sine_error(intervals);
    EXPECT_GT(previous / error, 14.0) << intervals << " intervals";
    EXPECT_LT(previous / error, 18.0) << intervals << " intervals";
    previous = error;
  }
}

TEST(UpsampleSpline, MatchesScipyNotAKnot) {
  expect_near_all(upsample_spline(testing::lehmer(8, 99), 3), kSpline, 1e-15);
}

// 150 000 samples (the benchmark's longest non-periodic record) go through the O(N) solve; a line stays a line.
TEST(UpsampleSpline, LongRecordKeepsLine) {
  std::vector<double> x(150000);
  for (std::size_t k = 0; k < x.size(); ++k) x[k] = 0.5 - 1e-3 * static_cast<double>(k);
  const std::vector<double> fine = upsample_spline(x, 20);
  ASSERT_EQ(fine.size(), (x.size() - 1) * 20 + 1);
  double worst = 0;
  for (std::size_t i = 0; i < fine.size(); ++i)
    worst = std::max(worst, std::abs(fine[i] - (0.5 - 1e-3 * static_cast<double>(i) / 20)));
  EXPECT_LT(worst, 1e-12);
}

}  // namespace
}  // namespace dampbench
