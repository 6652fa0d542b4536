// Adaptive GA (optimizers/ga/aga.hpp): the Srinivas & Patnaik rates, standard test functions over seeded
// repeats, settings checks, ask/tell conformance.
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
using testing::kAckley;
using testing::kGriewank;
using testing::kRastrigin;
using testing::kRosenbrock;
using testing::kSphere;
using testing::SuccessCase;

constexpr double kInf = std::numeric_limits<double>::infinity();

OptimizerFactory make_aga(int population, int generations) {
  AgaSettings s;
  s.population = population;
  s.generations = generations;
  return factory_of<Aga>(s);
}

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

// ---- standard functions ---------------------------------------------------------------------------

class AgaStandardFunctions : public ::testing::TestWithParam<SuccessCase> {};

TEST_P(AgaStandardFunctions, ReachesKnownOptimum) { testing::expect_success_rate(GetParam(), make_aga); }

// Defaults (k1 = k3 = 1, k2 = k4 = 0.5, pm_min = 1/(2d), GA operators). Grid N = 30/40/50, L = 100/200/400
// in 2/5/10 dimensions. Measured over seeds 1–20 and 1001–1020 (18th best of 20 in each block; worst run):
//   sphere      2.3e-5 2.2e-5 (4.5e-5);  1.2e-4 9.2e-5 (2.0e-4);  1.9e-4 1.3e-4 (3.2e-4)
//   Rosenbrock  L = 200 in 2-D: 9.3e-4, 1.1e-3 (1.9e-3; 18 and 17 runs below 1e-3);  5-D 2.6 2.6 (4.5);
//               10-D 7.6 8.9 (9.2)
//   Rastrigin   3.1e-3 7.3e-3 (9.5e-3);  0.031 0.028 (1.0);  0.060 0.059 (0.11)
//   Ackley      0.10 0.08 (0.19);  0.13 0.15 (0.19);  0.11 0.15 (0.16)
//   Griewank    0.035 0.026 (0.038);  0.094 0.088 (0.13);  0.17 0.17 (0.24)
// With S&P's literal pm_min = 0.005 the same grid gave 2-D Ackley 1.7 and Rastrigin 1.1 (18th best), no
// better than random sampling: see the header. Targets: about three times the worse 18th best (1.5 times
// above 1), rounded up, each below the 10th percentile of random sampling with the same budget.
INSTANTIATE_TEST_SUITE_P(Functions, AgaStandardFunctions,
                         ::testing::Values(SuccessCase{kSphere, 2, 30, 100, 7e-5, 18, 20},
                                           SuccessCase{kSphere, 5, 40, 200, 4e-4, 18, 20},
                                           SuccessCase{kSphere, 10, 50, 400, 7e-4, 18, 20},
                                           SuccessCase{kRosenbrock, 2, 30, 200, 1e-3, 15, 20},
                                           SuccessCase{kRosenbrock, 5, 40, 200, 4.0, 18, 20},
                                           SuccessCase{kRosenbrock, 10, 50, 400, 15.0, 18, 20},
                                           SuccessCase{kRastrigin, 2, 30, 100, 0.03, 18, 20},
                                           SuccessCase{kRastrigin, 5, 40, 200, 0.1, 18, 20},
                                           SuccessCase{kRastrigin, 10, 50, 400, 0.2, 18, 20},
                                           SuccessCase{kAckley, 2, 30, 100, 0.3, 18, 20},
                                           SuccessCase{kAckley, 5, 40, 200, 0.5, 18, 20},
                                           SuccessCase{kAckley, 10, 50, 400, 0.5, 18, 20},
                                           SuccessCase{kGriewank, 2, 30, 100, 0.1, 18, 20},
                                           SuccessCase{kGriewank, 5, 40, 200, 0.3, 18, 20},
                                           SuccessCase{kGriewank, 10, 50, 400, 0.7, 18, 20}),
                         [](const auto& p) { return p.param.name(); });

// ---- conformance ------------------------------------------------------------------------------------

TEST(Aga, SameKeySameHistory) { testing::expect_keyed_history(make_aga(20, 30)); }
TEST(Aga, LockstepEqualsAlone) { testing::expect_lockstep_equals_alone(make_aga(12, 15)); }
// Measured 7.5 + 2.1e-9 after 50 generations.
TEST(Aga, StaysInsideBounds) { testing::expect_stays_inside_bounds(make_aga(20, 50), 1e-6); }

TEST(Aga, EvaluationBudgetIsPopulationTimesGenerations) {
  testing::expect_budget(make_aga(8, 13), 8, 13);
  testing::expect_budget(make_aga(7, 5), 7, 5);
}

// Measured (seed 5, N = 30, 100 generations): 7.2e-5 beside +inf, NaN and −inf alike.
TEST(Aga, ConvergesBesideFailedCandidates) {
  const OptimizerFactory make = make_aga(30, 100);
  testing::expect_converges_beside_failures(make, kInf, 1e-3);
  testing::expect_converges_beside_failures(make, std::numeric_limits<double>::quiet_NaN(), 1e-3);
  testing::expect_converges_beside_failures(make, -kInf, 1e-3);
}

TEST(Aga, BestPositionInsideBeforeFirstTell) { testing::expect_best_position_before_first_tell(make_aga(10, 20)); }
TEST(Aga, SurvivesAllCandidatesFailing) { testing::expect_survives_all_failures(make_aga(10, 20)); }

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

// ---- settings ---------------------------------------------------------------------------------------

TEST(Aga, RejectsBadSettings) {
  const Bounds b{{0.0}, {1.0}};
  const auto message = [&](const AgaSettings& s) { return error_of([&] { Aga(s, b, 1); }); };
  AgaSettings s;
  s.population = 3;
  EXPECT_EQ(message(s), "aga: population must be at least 4, got 3");
  s = {};
  s.k1 = 2;
  EXPECT_EQ(message(s), "aga: k1 must be in [0, 1], got 2");
  s = {};
  s.k2 = -0.5;
  EXPECT_EQ(message(s), "aga: k2 must be in [0, 1], got -0.5");
  s = {};
  s.k3 = 1.1;
  EXPECT_EQ(message(s), "aga: k3 must be in [0, 1], got 1.1");
  s = {};
  s.k4 = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message(s), "aga: k4 must be in [0, 1], got nan");
  s = {};
  s.pm_min = 3;
  EXPECT_EQ(message(s), "aga: pm_min must be in [0, 1], got 3");
  s = {};
  s.tournament = 60;
  EXPECT_EQ(message(s), "aga: tournament must be in [2, population = 50], got 60");
  s = {};
  s.eta_c = -2;
  EXPECT_EQ(message(s), "aga: eta_c must be a finite number >= 0, got -2");
  EXPECT_EQ(message(AgaSettings{}), "no error");
}

}  // namespace dampbench
