// The ODE kernel's chained power of a state (engine/kernels/ode_kernel.hpp, "Powers of a state"): the power at a
// sub-step's start comes from a series on the previous sub-step's, with the exact log and exp only at anchors. The
// same kernel with an anchor at every sub-step (kChainSteps = 1) is the reference: the forces must agree to 1e-14
// of the peak force (the chain's error is about 1e-14 relative at most, RK4's against CVODE 2e-5), when every lane
// takes the record's sub-steps (one set of inputs for all, chains across up to 4 intervals) and in a block with
// stiff lanes (each lane its own count), and must not be identical (else the test would not exercise the chain).
// That a lane's bits do not depend on its neighbours is tested for the real models at every vector level
// (tests/unit/kernels/test_isa.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/kernels/ode_kernel.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

/// A Bouc–Wen law (Wen 1976): ż = −γ|v|·sgn(z)|z|^n − β·v·|z|^n + A·v, F = c·v + α·z; its seventh parameter is
/// the stiffness estimate λ [1/s] itself, so that chosen lanes take more sub-steps than the record's.
struct ChainedBoucWen {
  static constexpr int kParams = 7, kStates = 1;
  static constexpr double kSubstepsPerStroke = 400;
  static constexpr bool kStrokeDriven = true;
  static constexpr int kPowerState = 0, kPowerExponentRow = 5;
  enum Row { c, alpha, beta, gamma, A, n, lambda };
  struct Context {};
  static Context context(const Signals&) { return {}; }
  template <class P, class Y, class DY>
  static void rhs(const P& p, int l, const Context&, double, double v, const Y& y, double zn, DY&& dy) {
    dy[0] = -p.p[gamma][l] * std::fabs(v) * sign(y[0]) * zn - p.p[beta][l] * v * zn + p.p[A][l] * v;
  }
  template <class P, class Y>
  static double force(const P& p, int l, const Context&, double, double v, const Y& y) {
    return p.p[c][l] * v + p.p[alpha][l] * y[0];
  }
  template <class P>
  static double stiffness(const P& p, int l, const Context&, const RecordScales&) {
    return p.p[lambda][l];
  }
};

/// The same law with the exact power at every sub-step's start.
struct ExactBoucWen : ChainedBoucWen {
  static constexpr int kChainSteps = 1;
};

constexpr int W = kLanes;

/// Lane l: exponents over [0.6, 3.0] and the loop's saturation (A/(β + γ))^(1/n) near the stroke; with `stiff`,
/// every other lane has λ = 4000/s, 21 sub-steps per 5 ms interval (ceil of dt·λ with the kernel's 1e-6 slack)
/// where the record asks for at most 7.
LawLanes<ChainedBoucWen, W> lanes(double stroke_m, bool stiff) {
  LawLanes<ChainedBoucWen, W> p;
  for (int l = 0; l < W; ++l) {
    const double n = 0.6 + 2.4 * l / (W - 1), A = 50.0 + 10.0 * l;
    const double spread = A / std::pow(stroke_m, n);  // β + γ
    p.p[ChainedBoucWen::c][l] = 2000.0;
    p.p[ChainedBoucWen::alpha][l] = 1e5;
    p.p[ChainedBoucWen::beta][l] = 0.4 * spread;
    p.p[ChainedBoucWen::gamma][l] = 0.6 * spread;
    p.p[ChainedBoucWen::A][l] = A;
    p.p[ChainedBoucWen::n][l] = n;
    p.p[ChainedBoucWen::lambda][l] = stiff && l % 2 == 1 ? 4000.0 : 0.0;
  }
  return p;
}

/// Forces of every lane at every sample, forces[k][l].
template <class Law>
std::vector<std::vector<double>> forces(const LawLanes<ChainedBoucWen, W>& p, const Signals& data) {
  LawLanes<Law, W> q;
  std::copy(&p.p[0][0], &p.p[0][0] + sizeof(p.p) / sizeof(double), &q.p[0][0]);
  OdeKernel<Law, W> kernel(q, data);
  std::vector<std::vector<double>> f(data.size(), std::vector<double>(W));
  for (std::size_t k = 0; k < data.size(); ++k) kernel.forces(k, f[k].data());
  for (int l = 0; l < W; ++l) EXPECT_FALSE(kernel.failed()[l]) << "lane " << l;
  return f;
}

/// Chained against exact forces of lanes first, first + step, ...: the largest difference relative to each lane's
/// peak force, checked against 1e-14, and that some differ.
void expect_close(const std::vector<std::vector<double>>& chained, const std::vector<std::vector<double>>& exact,
                  int first, int step, const char* what) {
  double worst = 0;
  int differ = 0;
  for (int l = first; l < W; l += step) {
    const auto lane = static_cast<std::size_t>(l);
    double scale = 0, diff = 0;
    for (std::size_t k = 0; k < exact.size(); ++k) {
      scale = std::max(scale, std::fabs(exact[k][lane]));
      diff = std::max(diff, std::fabs(chained[k][lane] - exact[k][lane]));
      differ += chained[k][lane] != exact[k][lane];
    }
    ASSERT_GT(scale, 0.0);
    worst = std::max(worst, diff / scale);
  }
  std::printf("%s: largest force difference %.3g of the peak force, %d samples not bit-identical\n", what, worst,
              differ);
  EXPECT_LE(worst, 1e-14) << what;
  EXPECT_GT(differ, 0) << what << ": the chain changed nothing; is it in use?";
}

/// The record: 3 cycles of 10 mm amplitude (a 20 mm stroke) at 1 Hz, sampled at 200 Hz.
constexpr double kAmplitude_m = 0.01;
Signals record() { return testing::sine_signals(kAmplitude_m, 1.0, 3.0, 200.0); }

TEST(OdePowerChain, AgreesWithTheExactPowerOnTheRecordsSubsteps) {
  const Signals data = record();
  const auto p = lanes(2 * kAmplitude_m, false);
  expect_close(forces<ChainedBoucWen>(p, data), forces<ExactBoucWen>(p, data), 0, 1, "record's sub-steps");
}

TEST(OdePowerChain, AgreesWithTheExactPowerInABlockWithStiffLanes) {
  const Signals data = record();
  const auto p = lanes(2 * kAmplitude_m, true);
  const auto chained = forces<ChainedBoucWen>(p, data), exact = forces<ExactBoucWen>(p, data);
  expect_close(chained, exact, 1, 2, "stiff lanes");
  expect_close(chained, exact, 0, 2, "lanes on the record's counts beside them");
}

}  // namespace
}  // namespace dampbench
