// Record-scaled default bounds (engine/model/bounds.cpp): a fit of several records searches the smallest box that
// holds each record's own, so parameters shared by a short and a long stroke reach what either record alone needs.
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
  // 1/X: the short stroke's box, 2000/0.002 m = 1e6 1/m (the long stroke's own is ±8e4)
  EXPECT_DOUBLE_EQ(lo("beta"), -1e6);
  EXPECT_DOUBLE_EQ(hi("beta"), 1e6);
  EXPECT_DOUBLE_EQ(lo("gamma"), 0.0);
  EXPECT_DOUBLE_EQ(hi("gamma"), 1e6);
  // F: the larger force, alpha ≤ 2F = 3000 N; F/X: k1 ≤ 1000/0.002 = 5e5 N/m (the largest F over the largest X
  // would give 6e4); F/V: c1 ≤ 20·1500/0.016 N·s/m; X: |x0| ≤ 0.025 m
  EXPECT_DOUBLE_EQ(hi("alpha"), 3000.0);
  EXPECT_DOUBLE_EQ(hi("k1"), 1000 / 0.002);
  EXPECT_DOUBLE_EQ(hi("c1"), 20 * 1500 / 0.016);
  EXPECT_DOUBLE_EQ(lo("x0"), -0.025);
  EXPECT_DOUBLE_EQ(hi("x0"), 0.025);
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
