// PSO (optimizers/pso): the constants of its variants and settings checks. The checks every optimizer passes,
// each variant (standard functions, determinism, bounds, budget, failed candidates), are in
// test_optimizer_conformance.cpp.
#include "optimizers/pso/pso.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "engine/common/error.hpp"
#include "optimizer_test_support.hpp"
#include "test_support.hpp"

namespace dampbench {
namespace {

using testing::error_of;
using testing::factory_of;

}  // namespace

// ---- settings -------------------------------------------------------------------------------------

// Clerc & Kennedy (2002): φ = 4.1 gives χ ≈ 0.7298 (0.72984378…), c = χ·2.05 ≈ 1.49618.
TEST(Pso, ConstrictionFactorOfClercAndKennedy) {
  const PsoSettings s = PsoSettings::constriction();
  EXPECT_EQ(s.variant, PsoVariant::constriction);
  EXPECT_EQ(s.cognitive + s.social, 4.1);
  EXPECT_NEAR(s.constriction_factor(), 0.7298437881, 1e-9);
  EXPECT_NEAR(s.constriction_factor() * 2.05, 1.49618, 1e-5);
}

TEST(Pso, LinearInertiaOfShiAndEberhart) {
  const PsoSettings s = PsoSettings::linear_inertia();
  EXPECT_EQ(s.variant, PsoVariant::inertia);
  EXPECT_EQ(s.inertia, 0.9);
  EXPECT_EQ(s.inertia_end, 0.4);
  EXPECT_EQ(s.cognitive, 2.0);
  EXPECT_EQ(s.social, 2.0);
}

// The constriction variant and the default inertia form with w = χ, c = χ·φ/2 are the same algorithm
// (Eberhart & Shi 2000): both converge on the sphere (measured 1.4e-5 and 1.2e-5 with N = 20, L = 40 in
// 3-D), but the histories differ (rounding of the two formulas), which shows the variant setting is used.
TEST(Pso, ConstrictionVariantUsesItsOwnUpdate) {
  PsoSettings c = PsoSettings::constriction(), w;
  c.population = w.population = 20;
  c.iterations = w.iterations = 40;
  const Bounds b = testing::box(3, -5.12, 5.12);
  const auto hc = testing::minimize(factory_of<Pso>(c), testing::sphere, b, 1, true);
  const auto hw = testing::minimize(factory_of<Pso>(w), testing::sphere, b, 1, true);
  EXPECT_NE(hc.history, hw.history);
  EXPECT_LT(hc.best_value, 1e-3);
}

// A NaN coefficient, which only code can set (the registry's parser rejects "nan"; the other bad values
// are rejected through it in test_optimizer_conformance.cpp).
TEST(Pso, RejectsNanCoefficients) {
  PsoSettings s;
  s.inertia_end = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(error_of([&] { Pso(s, testing::box(1, 0, 1), 1); }),
            "pso: inertia_end must be a finite number >= 0, got nan");
}

}  // namespace dampbench
