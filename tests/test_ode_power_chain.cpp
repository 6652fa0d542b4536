// The ODE kernel's chained power of a state (engine/kernels/ode_kernel.hpp, "Powers of a state"): the power at a
// sub-step's start comes from a series on the previous sub-step's, with the exact log and exp only at anchors. The
// same kernel with an anchor at every sub-step (kChainSteps = 1, the kernel before chaining) is the reference: the
// forces must agree to 1e-12 relative (the chain's error is below 1e-14 by construction, RK4's against CVODE 2e-5),
// on lanes that share the record's sub-steps and on stiff lanes with their own counts, and must not be identical
// (else the test would not exercise the chain).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/kernels/ode_kernel.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

/// A Bouc–Wen law (Wen 1976): ż = −γ|v|·sgn(z)|z|^n − β·v·|z|^n + A·v, F = c·v + α·z; its seventh parameter is the
/// stiffness estimate λ [1/s] itself, so that chosen lanes take more sub-steps than the record's.
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

/// Lane l: exponents over [0.6, 3.0], the loop's saturation (A/(β + γ))^(1/n) near the stroke X, and every other lane
/// stiff (λ = 4000/s: 20 sub-steps per 5 ms interval, more than the record's 7 at peak velocity).
LawLanes<ChainedBoucWen, W> lanes(double stroke_m) {
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
    p.p[ChainedBoucWen::lambda][l] = l % 2 == 0 ? 0.0 : 4000.0;
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

TEST(OdePowerChain, AgreesWithTheExactPowerAtEverySubstep) {
  const double stroke_m = 0.01;
  const Signals data = testing::sine_signals(stroke_m, 1.0, 3.0, 200.0);
  const auto p = lanes(2 * stroke_m);
  const auto chained = forces<ChainedBoucWen>(p, data);
  const auto exact = forces<ExactBoucWen>(p, data);
  for (int stiff = 0; stiff < 2; ++stiff) {
    double worst = 0;
    int differ = 0;
    for (int l = stiff; l < W; l += 2) {
      double scale = 0, diff = 0;
      for (std::size_t k = 0; k < data.size(); ++k) {
        scale = std::max(scale, std::fabs(exact[k][static_cast<std::size_t>(l)]));
        diff = std::max(diff, std::fabs(chained[k][static_cast<std::size_t>(l)] - exact[k][static_cast<std::size_t>(l)]));
        differ += chained[k][static_cast<std::size_t>(l)] != exact[k][static_cast<std::size_t>(l)];
      }
      ASSERT_GT(scale, 0.0);
      worst = std::max(worst, diff / scale);
    }
    std::printf("%s lanes: largest force difference %.3g of the peak force, %d samples not bit-identical\n",
                stiff ? "stiff" : "record's sub-step", worst, differ);
    EXPECT_LE(worst, 1e-12) << (stiff ? "stiff lanes" : "lanes on the record's sub-steps");
    EXPECT_GT(differ, 0) << "the chain changed nothing: is it in use?";
  }
}

}  // namespace
}  // namespace dampbench
