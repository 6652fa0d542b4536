// Differential evolution (optimizers/de): bound handling by midpoint repair, the strategies, settings checks.
// The checks every optimizer passes, each strategy (standard functions, ask/tell conformance), are in
// test_optimizer_conformance.cpp.
#include "optimizers/de/de.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string>

#include "engine/common/error.hpp"
#include "optimizer_test_support.hpp"
#include "test_support.hpp"

namespace dampbench {
namespace {

using testing::error_of;
using testing::factory_of;

constexpr DeStrategy kStrategies[] = {DeStrategy::rand1bin, DeStrategy::best1bin, DeStrategy::currenttobest1bin};

DeSettings de(DeStrategy strategy, int population, int generations) {
  DeSettings s;
  s.strategy = strategy;
  s.population = population;
  s.generations = generations;
  return s;
}

}  // namespace

// ---- bound handling, every strategy -------------------------------------------------------------------

class DeBoundHandling : public ::testing::TestWithParam<DeStrategy> {};

// Bound handling is the midpoint between the target and the violated bound, not clamping. The optimum of
// the sphere lies below the box, so many first-generation mutants cross the lower bound of x0: each such
// trial component is exactly (x_i,0 + 1) / 2 for its target x_i, and none lands on the bound (the initial
// members are not on it). Measured over seeds 1–6 with N = 20: 10 (rand1bin), 38 (best1bin) and 17
// (currenttobest1bin) repaired components; clamping would give none and put them on the bound.
TEST_P(DeBoundHandling, RepairsToTheMidpointNotTheBound) {
  const int n = 20;
  const Bounds b{{1.0, -1.0}, {2.0, 1.0}};
  int repaired = 0;
  for (std::uint64_t key = 1; key <= 6; ++key) {
    const auto opt = factory_of<De>(de(GetParam(), n, 2))(b, key);
    const auto run = testing::minimize(*opt, testing::sphere, 2, true);
    ASSERT_EQ(run.history.size(), 2u * 2 * n);
    for (int i = 0; i < n; ++i) {
      const double target = run.history[2 * i], trial = run.history[2 * (n + i)];
      ASSERT_GT(trial, 1.0) << "trial " << i << " sits on the lower bound";
      repaired += trial == 0.5 * (target + 1.0);
    }
  }
  EXPECT_GE(repaired, 5);
}

INSTANTIATE_TEST_SUITE_P(Strategies, DeBoundHandling, ::testing::ValuesIn(kStrategies),
                         [](const auto& p) { return std::string(de_strategy_name(p.param)); });

TEST(De, StrategiesDiffer) {
  const Bounds b = testing::box(3, -5, 5);
  const auto h0 = testing::minimize(factory_of<De>(de(DeStrategy::rand1bin, 10, 5)), testing::sphere, b, 1, true);
  const auto h1 = testing::minimize(factory_of<De>(de(DeStrategy::best1bin, 10, 5)), testing::sphere, b, 1, true);
  const auto h2 =
      testing::minimize(factory_of<De>(de(DeStrategy::currenttobest1bin, 10, 5)), testing::sphere, b, 1, true);
  // Generation 0 is the same uniform population; the trials differ.
  EXPECT_TRUE(std::equal(h0.history.begin(), h0.history.begin() + 30, h1.history.begin()));
  EXPECT_NE(h0.history, h1.history);
  EXPECT_NE(h0.history, h2.history);
  EXPECT_NE(h1.history, h2.history);
}

// ---- settings ---------------------------------------------------------------------------------------

TEST(De, ParsesStrategyNames) {
  for (DeStrategy s : kStrategies) EXPECT_EQ(parse_de_strategy(de_strategy_name(s)), s);
  EXPECT_EQ(de_strategy_name(DeStrategy::best1bin), "best1bin");
  EXPECT_EQ(error_of([] { (void)parse_de_strategy("rand2bin"); }),
            "de: unknown strategy 'rand2bin' (known: rand1bin, best1bin, currenttobest1bin)");
}

TEST(De, RejectsNanCrossoverRate) {  // the registry never passes NaN; it checks the other values
  DeSettings s;
  s.CR = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(error_of([&] { De(s, testing::box(1, 0, 1), 1); }), "de: CR must be in [0, 1], got nan");
}

}  // namespace dampbench
