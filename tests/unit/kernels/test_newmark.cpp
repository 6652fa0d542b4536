// The benchmark's Newmark step (engine/kernels/newmark.hpp) against an independent implementation of the same
// scheme, a linear structure's known steady response, and the scheme's second order.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Dense>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "engine/kernels/newmark.hpp"

namespace dampbench {
namespace {

constexpr double kPi = std::numbers::pi;

/// ż of benchmark eq. 3 written from the equation as printed, with its partial derivatives by central
/// differences: shares nothing with hysteretic_rate.
double rate_as_printed(const HystereticStructure& p, double v, double z) {
  const double beta = 1000, gamma = p.beta_gamma / beta, delta = p.beta_delta / beta;
  const double abs_z_pow = z == 0 ? 0.0 : std::pow(std::fabs(z), p.nu - 1) * z;  // |z|^(ν−1)·z
  return p.alpha_N_m * v - beta * (gamma * std::fabs(v) * abs_z_pow + delta * v * std::pow(std::fabs(z), p.nu));
}

/// The same Newmark scheme as four equations in (y₁, ẏ₁, ÿ₁, z₁), solved by Newton with a finite-difference
/// Jacobian (Eigen's LU) to a residual-free state.
struct PlainNewmark {
  HystereticStructure p;
  double h;
  double y = 0, v = 0, a = 0, z = 0;

  Eigen::Vector4d residual(const Eigen::Vector4d& x, double u1) const {
    const double zd0 = rate_as_printed(p, v, z), zd1 = rate_as_printed(p, x[1], x[3]);
    return {x[0] - y - h * v - h * h / 4 * (a + x[2]), x[1] - v - h / 2 * (a + x[2]),
            p.m_kg * x[2] + p.c_N_s_m * x[1] + p.k_N_m * x[0] + x[3] - u1, x[3] - z - h / 2 * (zd0 + zd1)};
  }

  void step(double u1) {
    Eigen::Vector4d x(y + h * v, v + h * a, a, z);
    for (int it = 0; it < 50; ++it) {
      const Eigen::Vector4d r = residual(x, u1);
      Eigen::Matrix4d J;
      for (int j = 0; j < 4; ++j) {
        const double d = 1e-7 * std::max(1.0, std::fabs(x[j]));
        Eigen::Vector4d xp = x, xm = x;
        xp[j] += d;
        xm[j] -= d;
        J.col(j) = (residual(xp, u1) - residual(xm, u1)) / (2 * d);
      }
      const Eigen::Vector4d dx = J.partialPivLu().solve(r);
      x -= dx;
      if (dx.cwiseAbs().maxCoeff() < 1e-16 * std::max(1.0, x.cwiseAbs().maxCoeff())) break;
    }
    y = x[0];
    v = x[1];
    a = x[2];
    z = x[3];
  }
};

/// A band-limited force of a few sines, N at 15 kHz.
std::vector<double> test_force(std::size_t n, double h) {
  std::vector<double> u(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * h;
    u[i] = 30 * std::sin(2 * kPi * 12 * t) + 25 * std::sin(2 * kPi * 33 * t + 1) + 10 * std::sin(2 * kPi * 71 * t + 2);
  }
  return u;
}

std::vector<double> engine_response(const HystereticStructure& p, double h, const std::vector<double>& u) {
  StructureState s = structure_at_rest(p, u[0]);
  std::vector<double> y(u.size());
  for (std::size_t i = 1; i < u.size(); ++i) {
    EXPECT_TRUE(newmark_step(p, h, u[i], s)) << "step " << i;
    y[i] = s.y_m;
  }
  return y;
}

class NewmarkAgainstPlain : public ::testing::TestWithParam<double> {};

TEST_P(NewmarkAgainstPlain, SameSchemeToOneInATrillion) {
  const HystereticStructure p{2, 10, 5e4, 5e4, 800, -1100, GetParam()};
  const double h = 1.0 / 15000;
  const std::vector<double> u = test_force(15000, h);  // one second
  const std::vector<double> y = engine_response(p, h, u);
  PlainNewmark plain{p, h};
  plain.a = u[0] / p.m_kg;
  double max_diff = 0, max_y = 0;
  for (std::size_t i = 1; i < u.size(); ++i) {
    plain.step(u[i]);
    max_diff = std::max(max_diff, std::fabs(plain.y - y[i]));
    max_y = std::max(max_y, std::fabs(y[i]));
  }
  EXPECT_GT(max_y, 1e-4);
  RecordProperty("relative_difference", fmt::format("{:.3g}", max_diff / max_y));
  EXPECT_LE(max_diff, 1e-12 * max_y) << "nu = " << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Exponents, NewmarkAgainstPlain, ::testing::Values(1.0, 1.4, 0.8));

TEST(Newmark, LinearStructureReachesItsSteadyAmplitude) {
  // βγ = βδ = 0: z = α·y exactly, so the structure is linear with stiffness k + α and its steady amplitude under
  // F·sin(ωt) is F/|k + α − mω² + icω|. Newmark's period error is O((ωh)²) ≈ 1e-5 here.
  const HystereticStructure p{2, 400, 5e4, 5e4, 0, 0, 1};
  const double h = 1.0 / 15000, f = 20, w = 2 * kPi * f, force = 40;
  std::vector<double> u(3 * 15000);
  for (std::size_t i = 0; i < u.size(); ++i) u[i] = force * std::sin(w * static_cast<double>(i) * h);
  const std::vector<double> y = engine_response(p, h, u);
  const double peak = *std::max_element(y.end() - 15000, y.end());  // the last second: the transient is e^-300 down
  const double expected = force / std::hypot(p.k_N_m + p.alpha_N_m - p.m_kg * w * w, p.c_N_s_m * w);
  EXPECT_NEAR(peak, expected, 1e-4 * expected);
}

TEST(Newmark, ErrorFallsFourfoldWhenTheStepHalves) {
  const HystereticStructure p{2, 10, 5e4, 5e4, 800, -1100, 1};
  // y every 1/7500 s over 0.25 s, stepping at `per_second`.
  const auto response = [&](int per_second) {
    const double h = 1.0 / per_second;
    const std::vector<double> y = engine_response(p, h, test_force(static_cast<std::size_t>(per_second / 4) + 1, h));
    std::vector<double> common;
    for (std::size_t i = 0; i < y.size(); i += static_cast<std::size_t>(per_second / 7500)) common.push_back(y[i]);
    return common;
  };
  const std::vector<double> reference = response(240000), coarse = response(7500), fine = response(15000);
  double coarse_sq = 0, fine_sq = 0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    coarse_sq += (coarse[i] - reference[i]) * (coarse[i] - reference[i]);
    fine_sq += (fine[i] - reference[i]) * (fine[i] - reference[i]);
  }
  const double ratio = std::sqrt(coarse_sq / fine_sq);
  EXPECT_GT(ratio, 3.5);
  EXPECT_LT(ratio, 4.5);
}

}  // namespace
}  // namespace dampbench
