// Record-scaled default bounds (engine/model/bounds.cpp): a fit of several records searches the smallest box that
// holds each record's own, so parameters shared by a short and a long stroke reach what either record alone needs,
// except the stiffening rates (the gauged beta, gamma), which stay inside each record's own box.
#include <vector>

#include <gtest/gtest.h>

#include "engine/model/bounds.hpp"
#include "engine/model/law_model.hpp"
#include "models/registry.hpp"

namespace dampbench {
namespace {

/// A record with only the scales the bounds read: peak force F [N], peak velocity V [m/s], amplitude X [m].
Signals scales(double F, double V, double X) {
  Signals s;
  s.measured_max_abs = F;
  s.velocity_max_abs = V;
  s.displacement_ptp = 2 * X;
  return s;
}

TEST(RecordBounds, SeveralRecordsSearchTheSmallestBoxHoldingEachRecordsOwn) {
  const LawModel gauged(find_model("mrd.spencer"), {});  // under the gauge: beta in ±2000/X, gamma in 0…2000/X
  const Signals short_fast = scales(1000, 0.06, 0.002), long_slow = scales(1500, 0.016, 0.025);
  const Signals* both[] = {&short_fast, &long_slow};
  const Bounds b = default_bounds(gauged, both);
  const auto lo = [&](const char* n) { return b.lower[static_cast<std::size_t>(gauged.parameter_index(n))]; };
  const auto hi = [&](const char* n) { return b.upper[static_cast<std::size_t>(gauged.parameter_index(n))]; };
  // F: the larger force, alpha ≤ 2F = 3000 N; F/X: k1 ≤ 1000/0.002 = 5e5 N/m (the largest F over the largest X
  // would give 6e4); F/V: c1 ≤ 20·1500/0.016 N·s/m; X: |x0| ≤ 0.025 m
  EXPECT_DOUBLE_EQ(hi("alpha"), 3000.0);
  EXPECT_DOUBLE_EQ(hi("k1"), 1000 / 0.002);
  EXPECT_DOUBLE_EQ(hi("c1"), 20 * 1500 / 0.016);
  EXPECT_DOUBLE_EQ(lo("x0"), -0.025);
  EXPECT_DOUBLE_EQ(hi("x0"), 0.025);
}

TEST(RecordBounds, StiffeningRatesOfSeveralRecordsStayInsideEachRecordsOwnBox) {
  const LawModel gauged(find_model("mrd.spencer"), {});
  const Signals short_fast = scales(1000, 0.06, 0.002), long_slow = scales(1500, 0.016, 0.025);
  const Signals* both[] = {&short_fast, &long_slow};
  const auto j_beta = static_cast<std::size_t>(gauged.parameter_index("beta"));
  const auto j_gamma = static_cast<std::size_t>(gauged.parameter_index("gamma"));
  // The joint fit's box: the long stroke's 2000/0.025 m = 8e4 1/m (the short stroke's own is ±1e6, which on the
  // long stroke would saturate z within 1 µm)
  const Bounds joint = default_bounds(gauged, both);
  EXPECT_DOUBLE_EQ(joint.lower[j_beta], -8e4);
  EXPECT_DOUBLE_EQ(joint.upper[j_beta], 8e4);
  EXPECT_DOUBLE_EQ(joint.lower[j_gamma], 0.0);
  EXPECT_DOUBLE_EQ(joint.upper[j_gamma], 8e4);
  // The hull of the records' own boxes (the law choice's clamp of predicted values): the short stroke's ±1e6
  const Bounds hull = default_bounds(gauged, both, RecordBox::hull);
  EXPECT_DOUBLE_EQ(hull.lower[j_beta], -1e6);
  EXPECT_DOUBLE_EQ(hull.upper[j_beta], 1e6);
  EXPECT_DOUBLE_EQ(hull.upper[j_gamma], 1e6);
  // Other rules are the same hull in both
  const auto j_alpha = static_cast<std::size_t>(gauged.parameter_index("alpha"));
  EXPECT_EQ(joint.upper[j_alpha], hull.upper[j_alpha]);
}

TEST(RecordBounds, AStartOutsideTheBoxKeepsTheGaugedSumOfBetaAndGammaAboveZero) {
  const LawModel gauged(find_model("mrd.spencer"), {});
  const Signals long_slow = scales(1500, 0.016, 0.025);
  const Signals* one[] = {&long_slow};
  const Bounds box = default_bounds(gauged, one);  // beta in ±8e4, gamma in 0…8e4
  std::vector<double> start(static_cast<std::size_t>(gauged.dim()));
  for (int j = 0; j < gauged.dim(); ++j) start[static_cast<std::size_t>(j)] = 0.5 * (box.lower[j] + box.upper[j]);
  const auto j_beta = static_cast<std::size_t>(gauged.parameter_index("beta"));
  const auto j_gamma = static_cast<std::size_t>(gauged.parameter_index("gamma"));
  const auto j_c1 = static_cast<std::size_t>(gauged.parameter_index("c1"));
  start[j_beta] = -1.2e5, start[j_gamma] = 1.6e5;  // A = 4e4; clamped one by one: -8e4 + 8e4 = 0
  start[j_c1] = 2 * box.upper[j_c1];
  clamp_into_box(gauged, box, start);
  // Both scaled by 8e4/1.6e5 = 0.5 (beta's own factor 8e4/1.2e5 is larger): -6e4, 8e4, A = 2e4
  EXPECT_DOUBLE_EQ(start[j_beta], -6e4);
  EXPECT_DOUBLE_EQ(start[j_gamma], 8e4);
  EXPECT_DOUBLE_EQ(start[j_c1], box.upper[j_c1]);  // other parameters: clamped one by one
  // Inside the box: unchanged
  std::vector<double> inside = start;
  clamp_into_box(gauged, box, inside);
  EXPECT_EQ(inside, start);
}

TEST(RecordBounds, ARecordWithoutForceOrMotionScalesNothing) {
  const LawModel gauged(find_model("mrd.spencer"), {});
  const Signals still = scales(0, 0, 0), moving = scales(1000, 0.06, 0.002);
  const Signals* both[] = {&still, &moving};
  const Signals* one[] = {&moving};
  const Bounds with_still = default_bounds(gauged, both), alone = default_bounds(gauged, one);
  EXPECT_EQ(with_still.lower, alone.lower);
  EXPECT_EQ(with_still.upper, alone.upper);
  const Signals* none[] = {&still};
  const Bounds unscaled = default_bounds(gauged, none), fixed = default_bounds(gauged);
  EXPECT_EQ(unscaled.lower, fixed.lower);
  EXPECT_EQ(unscaled.upper, fixed.upper);
}

}  // namespace
}  // namespace dampbench
