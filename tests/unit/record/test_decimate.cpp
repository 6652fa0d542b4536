// Tests for engine/record/decimate: fir1 taps against their closed form and scipy's firwin, the gain at the cutoff,
// MATLAB decimate's length rules, lines and constants kept exactly to both ends, a pass-band sine scaled by |H|, the
// cascade, and reference outputs of a statement-by-statement numpy transcription of decimate.m.
#include "engine/record/decimate.hpp"

#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/test_support.hpp"

#include "engine/common/error.hpp"

namespace dampbench {
namespace {

// Made by tests/unit/record/signal_chain_reference.py: scipy.signal.firwin(31, 0.5) and firwin(31, 0.2), which
// are MATLAB's fir1(30, 1/2) and fir1(30, 1/5).
const std::vector<double> kFirwin31Half = {
    -0.0017003969036736085, 1.7580300581294008e-18, 0.0029373315708906824,
    -3.2768716144333692e-18, -0.0067300913664044126, 6.0519332237139895e-18,
    0.014093887903991929, -9.6033815230833734e-18, -0.026785035820053857,
    1.3317138837685634e-17, 0.049098960593575408, -1.6551062789400004e-17,
    -0.096938332776300803, 1.8745978547698294e-17, 0.31561956332448227,
    0.50080822694698457, 0.31561956332448227, 1.8745978547698297e-17,
    -0.096938332776300803, -1.6551062789400007e-17, 0.049098960593575422,
    1.3317138837685634e-17, -0.026785035820053864, -9.603381523083378e-18,
    0.014093887903991929, 6.0519332237139972e-18, -0.0067300913664044178,
    -3.2768716144333692e-18, 0.0029373315708906837, 1.7580300581294008e-18,
    -0.0017003969036736085,
};
const std::vector<double> kFirwin31Fifth = {
    6.2264927146063833e-19, 0.0012014263758827757, 0.0027843278479828962,
    0.0042273160854469022, 0.0039427634127764104, -2.4127659269099714e-18,
    -0.0082567772926564822, -0.01858321013023596, -0.025389820435008308,
    -0.021235308698378596, 5.9929992378086389e-18, 0.039588112570909849,
    0.091888877020527671, 0.14509908103158412, 0.184902878561821,
    0.1996606672986955, 0.184902878561821, 0.14509908103158412,
    0.091888877020527671, 0.039588112570909856, 5.9929992378086404e-18,
    -0.021235308698378596, -0.025389820435008318, -0.018583210130235967,
    -0.0082567772926564822, -2.4127659269099745e-18, 0.0039427634127764139,
    0.0042273160854469022, 0.0027843278479828975, 0.0012014263758827757,
    6.2264927146063833e-19,
};
// The same script: MATLAB's decimate.m FIR branch transcribed in numpy (lfilter with carried state, the
// list/nbeg/nlen index rules), applied to lehmer(70, 12345) with r = 3, and to lehmer(301, 777) with r = 2, 2, 5.
const std::vector<double> kDecimate3 = {
    -0.22250988008454439, 0.28405681157935281, -0.033393506402936771,
    0.012415859190673501, -0.19425669839171342, -0.40940794796427316,
    -0.10398898125039904, 0.11129935254136936, -0.29265578103284423,
    0.21836246817221022, 0.38595670683817407, 0.15222459532234539,
    -0.036120458431258433, -0.17116172511514763, -0.077549102916405266,
    0.13886198521344681, 0.074051112918405271, -0.047186747568099478,
    0.20041700320586983, 0.10973219903355574, -0.12233062221559267,
    0.14329804198491566, -0.0064774674330071343, -0.0325579307973385,
};
const std::vector<double> kCascade225 = {
    -0.48253464372828569, -0.022770468237676811, 0.037864025338342634,
    -0.079462816095106498, 0.045752886057252098, -0.097210576455212278,
    0.016506403214515786, 0.0098117277270636499, 0.022451278498634913,
    0.096557835450259852, 0.081177343769823704, 0.035850103463098582,
    0.012221947445846265, 0.052214264750300554, -0.069516355115876352,
    -0.06393108516931531,
};

/// fir1's closed form written out here: Hamming window times the ideal low-pass, normalised to unit DC gain.
std::vector<double> closed_form_taps(int order, double cutoff) {
  std::vector<double> b(order + 1);
  double sum = 0;
  for (int i = 0; i <= order; ++i) {
    const double u = cutoff * (i - order / 2.0);
    const double ideal = u == 0 ? cutoff : cutoff * std::sin(std::numbers::pi * u) / (std::numbers::pi * u);
    b[i] = (0.54 - 0.46 * std::cos(2 * std::numbers::pi * i / order)) * ideal;
    sum += b[i];
  }
  for (double& tap : b) tap /= sum;
  return b;
}

/// |H| of taps b at ω rad/sample, evaluated as Σ b_i·e^(−jωi).
double gain(const std::vector<double>& b, double omega) {
  std::complex<double> h = 0;
  for (std::size_t i = 0; i < b.size(); ++i) h += b[i] * std::polar(1.0, -omega * static_cast<double>(i));
  return std::abs(h);
}

void expect_near_all(const std::vector<double>& got, const std::vector<double>& want, double tol) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], want[i], tol) << "index " << i;
}

TEST(Fir1Lowpass, MatchesClosedFormAndSumsToOne) {
  for (int r : {2, 3, 5, 20}) {
    const std::vector<double> b = fir1_lowpass(30, 1.0 / r);
    expect_near_all(b, closed_form_taps(30, 1.0 / r), 1e-16);
    double sum = 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
      sum += b[i];
      EXPECT_EQ(b[i], b[b.size() - 1 - i]) << "r " << r << " tap " << i;
    }
    EXPECT_NEAR(sum, 1.0, 4e-16) << "r " << r;
  }
  EXPECT_EQ(fir1_lowpass(7, 0.3).size(), 8U);
}

TEST(Fir1Lowpass, MatchesScipyFirwin) {
  expect_near_all(fir1_lowpass(30, 0.5), kFirwin31Half, 1e-16);
  expect_near_all(fir1_lowpass(30, 0.2), kFirwin31Fifth, 1e-16);
}

// A half-band filter's taps at even non-zero offsets from the centre vanish, and the odd ones meet cos(kπ/2) = 0 at
// the cutoff (ω = π/2): only the centre tap is left, and the window and the normalisation put it 8e-4 above the
// ideal 0.5 (−6 dB).
TEST(Fir1Lowpass, HalfBandGainAtCutoffIsCentreTap) {
  const std::vector<double> b = fir1_lowpass(30, 0.5);
  for (std::size_t i = 2; i <= 14; i += 2) EXPECT_EQ(b[15 + i], 0.0) << "offset " << i;
  EXPECT_NEAR(gain(b, std::numbers::pi / 2), b[15], 1e-15);
  EXPECT_NEAR(gain(b, std::numbers::pi / 2), 0.5, 1e-3);
  EXPECT_NEAR(gain(b, 0), 1.0, 4e-16);
}

TEST(Fir1Lowpass, RefusesBadDesign) {
  EXPECT_THROW(fir1_lowpass(0, 0.5), InputError);
  EXPECT_THROW(fir1_lowpass(30, 0.0), InputError);
  EXPECT_THROW(fir1_lowpass(30, 1.0), InputError);
}

TEST(DecimateFir, LengthIsCeilOfNOverFactor) {
  for (std::size_t n : {63U, 64U, 65U, 100U, 101U, 1000U})
    for (int r : {2, 3, 5, 20})
      EXPECT_EQ(decimate_fir(std::vector<double>(n, 1.0), r).size(), (n + r - 1) / r) << "n " << n << " r " << r;
}

TEST(DecimateFir, RefusesBadFactorAndShortInput) {
  EXPECT_THROW(decimate_fir(std::vector<double>(100, 1.0), 0), InputError);
  EXPECT_THROW(decimate_fir(std::vector<double>(62, 1.0), 2), InputError);
  EXPECT_NO_THROW(decimate_fir(std::vector<double>(63, 1.0), 2));
  EXPECT_THROW(decimate_fir(std::vector<double>(22, 1.0), 2, 10), InputError);
  EXPECT_NO_THROW(decimate_fir(std::vector<double>(23, 1.0), 2, 10));
  try {
    decimate_fir_cascade(std::vector<double>(200, 1.0), std::vector<int>{2, 2, 5});
    ADD_FAILURE() << "200 samples decimated by 20";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("step 3 of 3 (factor 5): decimate: 50 samples, expected at least 63"),
              std::string::npos) << e.what();
  }
}

TEST(DecimateFir, FactorOneIsIdentity) {
  const std::vector<double> x = testing::lehmer(10, 5);
  EXPECT_EQ(decimate_fir(x, 1), x);
}

// The odd reflection continues a straight line, and a symmetric filter with unit DC gain passes one unchanged: the
// output is the line at the kept samples, the first and last included.
TEST(DecimateFir, KeepsConstantsAndLinesToBothEnds) {
  for (std::size_t n : {63U, 64U, 97U, 200U}) {
    for (int r : {2, 3, 5, 20}) {
      std::vector<double> constant(n, -2.75), line(n);
      for (std::size_t k = 0; k < n; ++k) line[k] = 3.0 + 0.25 * static_cast<double>(k);
      const std::vector<double> flat = decimate_fir(constant, r);
      const std::vector<double> straight = decimate_fir(line, r);
      for (std::size_t j = 0; j < flat.size(); ++j) {
        EXPECT_NEAR(flat[j], -2.75, 4e-15) << "n " << n << " r " << r << " j " << j;
        EXPECT_NEAR(straight[j], line[j * r], 1e-13) << "n " << n << " r " << r << " j " << j;
      }
    }
  }
}

// sin(2πk/50) over k = 0…200 starts and ends on zero crossings, where the odd reflection is the sine itself; so every
// output, the padded ends included, is the sine at the kept instant times H(ω) (real: the taps are symmetric).
TEST(DecimateFir, PassBandSineIsScaledByGain) {
  const double omega = 2 * std::numbers::pi / 50;
  std::vector<double> x(201);
  for (std::size_t k = 0; k < x.size(); ++k) x[k] = std::sin(omega * static_cast<double>(k));
  for (int r : {2, 5}) {
    const double h = gain(fir1_lowpass(30, 1.0 / r), omega);
    EXPECT_NEAR(h, 1.0, 3e-3);  // inside the pass band, whose ripple is 2.3e-3 here
    const std::vector<double> y = decimate_fir(x, r);
    for (std::size_t j = 0; j < y.size(); ++j)
      EXPECT_NEAR(y[j], h * std::sin(omega * static_cast<double>(j * r)), 1e-14) << "r " << r << " j " << j;
  }
}

TEST(DecimateFir, MatchesMatlabTranscription) {
  expect_near_all(decimate_fir(testing::lehmer(70, 12345), 3), kDecimate3, 1e-15);
}

TEST(DecimateFirCascade, MatchesStepsLengthAndTranscription) {
  const std::vector<int> factors = {2, 2, 5};
  for (std::size_t n : {301U, 1000U, 1001U, 4003U}) {
    const std::vector<double> x = testing::lehmer(n, 31 + n);
    const std::vector<double> y = decimate_fir_cascade(x, factors);
    EXPECT_EQ(y.size(), (((n + 1) / 2 + 1) / 2 + 4) / 5) << "n " << n;
    EXPECT_EQ(y, decimate_fir(decimate_fir(decimate_fir(x, 2), 2), 5)) << "n " << n;
  }
  expect_near_all(decimate_fir_cascade(testing::lehmer(301, 777), factors), kCascade225, 1e-15);
  EXPECT_THROW(decimate_fir_cascade(std::vector<double>(200, 1.0), factors), InputError);
}

}  // namespace
}  // namespace dampbench
