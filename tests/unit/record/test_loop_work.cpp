// loop_work_j (engine/record/loop_work.hpp): the work of a force along a closed loop, against hand-computed areas.
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "engine/record/loop_work.hpp"

namespace dampbench {
namespace {

/// Two whole cycles of x = X sin(ωt) at 400 samples per cycle, and a force of (x, v) at each sample.
template <class Force>
double work_of(Force force, double X = 0.02, double f = 2.0) {
  const double w = 2 * std::numbers::pi * f;
  std::vector<double> x, F;
  for (int k = 0; k <= 800; ++k) {
    const double t = k / (400.0 * f);
    x.push_back(X * std::sin(w * t));
    F.push_back(force(x.back(), X * w * std::cos(w * t)));
  }
  return loop_work_j(F, x);
}

TEST(LoopWork, AViscousLoopDissipatesPiCOmegaXSquaredPerCycle) {
  const double c = 3e4, X = 0.02, w = 2 * std::numbers::pi * 2.0;
  const double per_cycle = std::numbers::pi * c * w * X * X;  // 237.0 J
  EXPECT_NEAR(work_of([&](double, double v) { return c * v; }), 2 * per_cycle, 1e-4 * per_cycle);
}

TEST(LoopWork, FrictionDissipatesFourF0XPerCycleAndASpringNothing) {
  const double F0 = 500, X = 0.02;
  // A square loop of height 2F0 and width 2X (its corners cost the trapezoid rule a sample's travel, X·(1 − cos(π/400)))
  EXPECT_NEAR(work_of([&](double, double v) { return v > 0 ? F0 : -F0; }), 2 * 4 * F0 * X, 1e-3 * F0 * X);
  // Linear and quadratic springs return on unloading what loading stored.
  EXPECT_NEAR(work_of([](double x, double) { return 4e6 * x + 3e10 * x * x; }), 0.0, 1e-6);
}

TEST(LoopWork, FewerThanTwoSamplesDoNoWork) {
  EXPECT_EQ(loop_work_j(std::vector<double>{5.0}, std::vector<double>{1.0}), 0.0);
  EXPECT_EQ(loop_work_j(std::vector<double>{}, std::vector<double>{}), 0.0);
}

}  // namespace
}  // namespace dampbench
