// Adaptive GA (optimizers/ga/aga.hpp): the Srinivas & Patnaik rates and settings checks. The checks every
// optimizer passes (standard functions, ask/tell conformance) are in test_optimizer_conformance.cpp.
#include "optimizers/ga/aga.hpp"

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

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

// ---- the adaptive rates (S&P 1994, minimization form), values worked by hand ----------------------------

TEST(AgaRates, CrossoverFollowsSrinivasAndPatnaik) {
  const AgaSettings s;  // k1 = k3 = 1
  // f_min = 1, f_avg = 5: a pair whose better value is 2 sits a quarter of the way from best to mean.
  EXPECT_DOUBLE_EQ(aga_crossover_probability(s, 2, 1, 5), 0.25);
  EXPECT_DOUBLE_EQ(aga_crossover_probability(s, 1, 1, 5), 0.0);  // the best pair is not crossed
  EXPECT_DOUBLE_EQ(aga_crossover_probability(s, 5, 1, 5), 1.0);  // an average pair: k1
  EXPECT_DOUBLE_EQ(aga_crossover_probability(s, 6, 1, 5), 1.0);  // below average: k3
  AgaSettings t;
  t.k1 = 0.8;
  t.k3 = 0.6;
  EXPECT_DOUBLE_EQ(aga_crossover_probability(t, 3, 1, 5), 0.4);
  EXPECT_DOUBLE_EQ(aga_crossover_probability(t, 9, 1, 5), 0.6);
  EXPECT_DOUBLE_EQ(aga_crossover_probability(t, kInf, 1, 5), 0.6);      // a failed pair: k3
  EXPECT_DOUBLE_EQ(aga_crossover_probability(t, kInf, kInf, kInf), 0.6);  // nothing finite: k3
  EXPECT_DOUBLE_EQ(aga_crossover_probability(t, 2, 2, 2), 0.8);         // collapsed population: average
}

TEST(AgaRates, MutationFollowsSrinivasAndPatnaikWithAFloor) {
  AgaSettings s;  // k2 = k4 = 0.5, pm_min unset: 1/(2d)
  EXPECT_DOUBLE_EQ(aga_mutation_probability(s, 3, 1, 5, 10), 0.25);  // 0.5 · (3 − 1)/(5 − 1)
  EXPECT_DOUBLE_EQ(aga_mutation_probability(s, 7, 1, 5, 10), 0.5);   // below average: k4
  EXPECT_DOUBLE_EQ(aga_mutation_probability(s, 3, 1, 5, 1), 0.5);    // 1-D: the floor 1/2 is higher
  EXPECT_DOUBLE_EQ(aga_mutation_probability(s, 1, 1, 5, 10), 0.05);  // the best: the floor 1/(2·10)
  EXPECT_DOUBLE_EQ(aga_mutation_probability(s, 1, 1, 5, 2), 0.25);   // floor 1/(2·2)
  EXPECT_DOUBLE_EQ(aga_mutation_probability(s, kInf, 1, 5, 10), 0.5);
  s.pm_min = 0.005;  // S&P's literal default rate
  EXPECT_DOUBLE_EQ(aga_mutation_probability(s, 1, 1, 5, 10), 0.005);
  s.k2 = 0.2;
  s.k4 = 0.3;
  EXPECT_DOUBLE_EQ(aga_mutation_probability(s, 4, 0, 8, 10), 0.1);
  EXPECT_DOUBLE_EQ(aga_mutation_probability(s, 9, 0, 8, 10), 0.3);
}

// ---- settings ---------------------------------------------------------------------------------------

// The rates come from AgaSettings: another k4 gives another history.
TEST(Aga, RatesComeFromItsSettings) {
  AgaSettings a, b;
  a.population = b.population = 20;
  a.generations = b.generations = 10;
  b.k4 = 0.1;
  const Bounds box = testing::box(3, -5, 5);
  EXPECT_NE(testing::minimize(factory_of<Aga>(a), testing::sphere, box, 1, true).history,
            testing::minimize(factory_of<Aga>(b), testing::sphere, box, 1, true).history);
}

// Through the class: the registry, which checks the other values (test_optimizer_conformance.cpp), never
// passes NaN.
TEST(Aga, RejectsNanRates) {
  AgaSettings s;
  s.k4 = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(error_of([&] { Aga(s, testing::box(1, 0, 1), 1); }), "aga: k4 must be in [0, 1], got nan");
}

}  // namespace dampbench
