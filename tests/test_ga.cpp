// GA (optimizers/ga/ga.hpp) and the operators it shares with the AGA (optimizers/ga/genetic.hpp): standard
// test functions over seeded repeats, operator properties, settings checks, ask/tell conformance.
#include "optimizers/ga/ga.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "engine/common/error.hpp"
#include "engine/common/random.hpp"
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

GaSettings ga(int population, int generations) {
  GaSettings s;
  s.population = population;
  s.generations = generations;
  return s;
}

OptimizerFactory make_ga(int population, int generations) { return factory_of<Ga>(ga(population, generations)); }

}  // namespace

// ---- standard functions ---------------------------------------------------------------------------

class GaStandardFunctions : public ::testing::TestWithParam<SuccessCase> {};

TEST_P(GaStandardFunctions, ReachesKnownOptimum) { testing::expect_success_rate(GetParam(), make_ga); }

// Defaults (pc 0.9, pm 1/d, SBX η 15, polynomial η 20, binary tournament, one elite). Grid N = 30/40/50,
// L = 100/200/400 in 2/5/10 dimensions. Measured over seeds 1–20 and 1001–1020 (18th best of 20 in each
// block; worst run):
//   sphere      3.2e-5 1.5e-5 (6.4e-5);  2.0e-4 1.1e-4 (6.3e-4);  4.9e-4 5.8e-4 (1.4e-3)
//   Rosenbrock  L = 200 in 2-D: 9.3e-5 4.2e-4 (8.4e-4);  5-D 4.0 2.1 (4.4, the local minimum near 3.99);
//               10-D 7.7 7.5 (9.5)
//   Rastrigin   3.5e-3 7.3e-3 (0.024);  0.065 0.092 (0.59);  0.30 0.17 (2.0)
//   Ackley      0.098 0.084 (0.12);  0.13 0.18 (0.24);  0.18 0.17 (0.27)
//   Griewank    0.038 0.036 (0.068);  0.17 0.15 (0.27);  0.36 0.37 (0.44)
// Targets: about three times the worse 18th best (1.5 times above 1), rounded up; every target is below
// the 10th percentile of random sampling with the same budget (e.g. 2-D Rosenbrock 0.0019 at 6 000
// samples, 10-D Rastrigin 61), so a GA that stops converging fails.
INSTANTIATE_TEST_SUITE_P(Functions, GaStandardFunctions,
                         ::testing::Values(SuccessCase{kSphere, 2, 30, 100, 1e-4, 18, 20},
                                           SuccessCase{kSphere, 5, 40, 200, 7e-4, 18, 20},
                                           SuccessCase{kSphere, 10, 50, 400, 2e-3, 18, 20},
                                           SuccessCase{kRosenbrock, 2, 30, 200, 1e-3, 18, 20},
                                           SuccessCase{kRosenbrock, 5, 40, 200, 7.0, 18, 20},
                                           SuccessCase{kRosenbrock, 10, 50, 400, 15.0, 18, 20},
                                           SuccessCase{kRastrigin, 2, 30, 100, 0.03, 18, 20},
                                           SuccessCase{kRastrigin, 5, 40, 200, 0.3, 18, 20},
                                           SuccessCase{kRastrigin, 10, 50, 400, 1.0, 18, 20},
                                           SuccessCase{kAckley, 2, 30, 100, 0.3, 18, 20},
                                           SuccessCase{kAckley, 5, 40, 200, 0.7, 18, 20},
                                           SuccessCase{kAckley, 10, 50, 400, 0.7, 18, 20},
                                           SuccessCase{kGriewank, 2, 30, 100, 0.1, 18, 20},
                                           SuccessCase{kGriewank, 5, 40, 200, 0.7, 18, 20},
                                           SuccessCase{kGriewank, 10, 50, 400, 1.5, 18, 20}),
                         [](const auto& p) { return p.param.name(); });

// The lssvm paper's settings (pc 0.6, pm 0.03, N 50, 500 generations) on a 5-D sphere: a slower GA (few
// mutations) that still converges; measured 18th best of seeds 1–20 and 1001–1020: 7.9e-7 and 2.2e-7
// (worst 9.2e-7).
TEST(Ga, LssvmPresetConverges) {
  testing::expect_success_rate(SuccessCase{kSphere, 5, 50, 500, 3e-6, 18, 20}, [](int population, int generations) {
    GaSettings s = GaSettings::lssvm();
    s.population = population;
    s.generations = generations;
    return factory_of<Ga>(s);
  });
}

// ---- conformance ------------------------------------------------------------------------------------

TEST(Ga, SameKeySameHistory) { testing::expect_keyed_history(make_ga(20, 30)); }
TEST(Ga, LockstepEqualsAlone) { testing::expect_lockstep_equals_alone(make_ga(12, 15)); }

// SBX and polynomial mutation reach a bound only in the limit: measured 7.5 + 1.2e-10 after 50 generations.
TEST(Ga, StaysInsideBounds) { testing::expect_stays_inside_bounds(make_ga(20, 50), 1e-6); }

// Generation 0 (the initial population) is evaluated like every other: N × generations, also for odd N.
TEST(Ga, EvaluationBudgetIsPopulationTimesGenerations) {
  testing::expect_budget(make_ga(8, 13), 8, 13);
  testing::expect_budget(make_ga(7, 5), 7, 5);
}

// Measured (seed 5, N = 30, 100 generations): 5.6e-5 beside +inf, NaN and −inf alike.
TEST(Ga, ConvergesBesideFailedCandidates) {
  const OptimizerFactory make = make_ga(30, 100);
  testing::expect_converges_beside_failures(make, std::numeric_limits<double>::infinity(), 1e-3);
  testing::expect_converges_beside_failures(make, std::numeric_limits<double>::quiet_NaN(), 1e-3);
  testing::expect_converges_beside_failures(make, -std::numeric_limits<double>::infinity(), 1e-3);
}

TEST(Ga, BestPositionInsideBeforeFirstTell) { testing::expect_best_position_before_first_tell(make_ga(10, 20)); }
TEST(Ga, SurvivesAllCandidatesFailing) { testing::expect_survives_all_failures(make_ga(10, 20)); }

// The rates are used: pc = 0 and pm = 0 ask only copies of initial members.
TEST(Ga, WithoutCrossoverAndMutationOnlyCopiesAreAsked) {
  GaSettings s = ga(10, 6);
  s.pc = 0;
  s.pm = 0;
  const Bounds b = testing::box(2, -1, 1);
  const auto run = testing::minimize(factory_of<Ga>(s), testing::sphere, b, 3, true);
  const std::vector<double> initial(run.history.begin(), run.history.begin() + 2 * s.population);
  for (std::size_t k = 0; k < run.history.size(); k += 2) {
    bool found = false;
    for (std::size_t m = 0; m < initial.size() && !found; m += 2)
      found = run.history[k] == initial[m] && run.history[k + 1] == initial[m + 1];
    ASSERT_TRUE(found) << "candidate " << k / 2 << " is not a copy of an initial member";
  }
}

// ---- operators --------------------------------------------------------------------------------------

TEST(GeneticOperators, TournamentPrefersFiniteAndLowestIndex) {
  const std::vector<double> values{std::numeric_limits<double>::infinity(), 3.0, 1.0, 1.0,
                                   std::numeric_limits<double>::infinity()};
  // With 200 entrants every index is drawn: the lowest value wins, and of the tied 1.0s the lower index.
  for (std::uint64_t k = 0; k < 20; ++k) {
    RandomStream rng(hash_key({k}));
    EXPECT_EQ(genetic::tournament(values, 200, rng), 2);
  }
  // With two entrants a failed member never beats a finite one.
  int finite_wins = 0;
  for (std::uint64_t k = 0; k < 200; ++k) {
    RandomStream rng(hash_key({k, 1}));
    const int w = genetic::tournament(values, 2, rng);
    finite_wins += std::isfinite(values[w]);
  }
  EXPECT_GE(finite_wins, 200 - 200 * 4 / 25 - 20);  // both entrants fail with probability (2/5)² = 4/25
  const std::vector<double> all_failed(4, std::numeric_limits<double>::infinity());
  RandomStream rng(hash_key({5}));
  EXPECT_EQ(genetic::tournament(all_failed, 200, rng), 0);  // ties to the lowest index
}

TEST(GeneticOperators, SbxKeepsChildrenInBoundsAndCopiesIdenticalParents) {
  const std::vector<double> lo{-1, 0, 5}, hi{1, 10, 5};
  const std::vector<double> a{-1, 10, 5}, b{1, 0, 5};  // parents on the bounds
  std::vector<double> c(3), d(3);
  double spread = 0;
  for (std::uint64_t k = 0; k < 500; ++k) {
    RandomStream rng(hash_key({k}));
    genetic::sbx(a, b, c, d, lo, hi, 15, rng);
    for (int j = 0; j < 3; ++j) {
      ASSERT_GE(c[j], lo[j]);
      ASSERT_LE(c[j], hi[j]);
      ASSERT_GE(d[j], lo[j]);
      ASSERT_LE(d[j], hi[j]);
    }
    spread += std::abs(c[0] - a[0]) + std::abs(c[0] - b[0]);
  }
  EXPECT_GT(spread, 0);  // variables do get crossed
  RandomStream rng(hash_key({1}));
  const std::vector<double> p{0.3, 4, 5};
  genetic::sbx(p, p, c, d, lo, hi, 15, rng);
  EXPECT_EQ(c, p);
  EXPECT_EQ(d, p);
}

// SBX with a large distribution index keeps children near their parents (Deb & Agrawal 1995): the spread
// factor β concentrates at 1, so children land near the parents, not between them.
TEST(GeneticOperators, SbxDistributionIndexControlsSpread) {
  const std::vector<double> lo{-10}, hi{10}, a{-1}, b{1};
  std::vector<double> c(1), d(1);
  double near_parents_tight = 0, near_parents_wide = 0;
  for (std::uint64_t k = 0; k < 2000; ++k) {
    RandomStream r1(hash_key({k})), r2(hash_key({k}));
    genetic::sbx(a, b, c, d, lo, hi, 100, r1);
    near_parents_tight += std::abs(std::abs(c[0]) - 1) < 0.1;
    genetic::sbx(a, b, c, d, lo, hi, 1, r2);
    near_parents_wide += std::abs(std::abs(c[0]) - 1) < 0.1;
  }
  EXPECT_GT(near_parents_tight, 1900);  // half the variables are not crossed, the rest land within 0.1
  EXPECT_LT(near_parents_wide, 1400);
}

TEST(GeneticOperators, PolynomialMutationStaysInBoundsAndIsCentred) {
  double sum = 0;
  for (std::uint64_t k = 0; k < 4000; ++k) {
    RandomStream rng(hash_key({k}));
    const double x = genetic::polynomial_mutation(0.0, -1, 1, 20, rng);
    ASSERT_GE(x, -1);
    ASSERT_LE(x, 1);
    sum += x;
    RandomStream edge(hash_key({k, 1}));
    const double y = genetic::polynomial_mutation(1.0, -1, 1, 20, edge);
    ASSERT_GE(y, -1);
    ASSERT_LE(y, 1);
  }
  EXPECT_NEAR(sum / 4000, 0.0, 0.01);  // symmetric perturbation of a centred gene
  RandomStream rng(hash_key({2}));
  EXPECT_EQ(genetic::polynomial_mutation(3.0, 3.0, 3.0, 20, rng), 3.0);  // a fixed parameter stays fixed
}

// ---- settings ---------------------------------------------------------------------------------------

TEST(Ga, LssvmPresetHasThePapersSettings) {
  const GaSettings s = GaSettings::lssvm();
  EXPECT_EQ(s.pc, 0.6);
  EXPECT_EQ(s.pm, 0.03);
  EXPECT_EQ(s.population, 50);
  EXPECT_EQ(s.generations, 500);
  EXPECT_EQ(s.tournament, GaSettings{}.tournament);
}

TEST(Ga, RejectsBadSettings) {
  const Bounds b{{0.0}, {1.0}};
  const auto message = [&](const GaSettings& s) { return error_of([&] { Ga(s, b, 1); }); };
  GaSettings s;
  s.population = 2;
  EXPECT_EQ(message(s), "ga: population must be at least 4, got 2");
  s = {};
  s.generations = 0;
  EXPECT_EQ(message(s), "ga: iterations (generations) must be at least 1, got 0");
  s = {};
  s.pc = 1.5;
  EXPECT_EQ(message(s), "ga: pc must be in [0, 1], got 1.5");
  s = {};
  s.pc = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message(s), "ga: pc must be in [0, 1], got nan");
  s = {};
  s.pm = -0.1;
  EXPECT_EQ(message(s), "ga: pm must be in [0, 1], got -0.1");
  s = {};
  s.tournament = 1;
  EXPECT_EQ(message(s), "ga: tournament must be in [2, population = 50], got 1");
  s = {};
  s.tournament = 51;
  EXPECT_EQ(message(s), "ga: tournament must be in [2, population = 50], got 51");
  s = {};
  s.elites = 26;
  EXPECT_EQ(message(s), "ga: elites must be in [0, population / 2 = 25], got 26");
  s = {};
  s.elites = -1;
  EXPECT_EQ(message(s), "ga: elites must be in [0, population / 2 = 25], got -1");
  s = {};
  s.eta_c = -1;
  EXPECT_EQ(message(s), "ga: eta_c must be a finite number >= 0, got -1");
  s = {};
  s.eta_m = std::numeric_limits<double>::infinity();
  EXPECT_EQ(message(s), "ga: eta_m must be a finite number >= 0, got inf");
  EXPECT_EQ(message(GaSettings{}), "no error");
}

}  // namespace dampbench
