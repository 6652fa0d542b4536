// PSO (optimizers/pso) on standard test functions with known optima, over seeded repeats; settings
// checks; ask/tell determinism.
#include "optimizers/pso/pso.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "engine/error.hpp"
#include "engine/random.hpp"

namespace dampbench {
namespace {

using Objective = std::function<double(const std::vector<double>&)>;

double sphere(const std::vector<double>& x) {
  double s = 0;
  for (double v : x) s += v * v;
  return s;
}
double rosenbrock(const std::vector<double>& x) {
  double s = 0;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) s += 100 * std::pow(x[i + 1] - x[i] * x[i], 2) + std::pow(1 - x[i], 2);
  return s;
}
double rastrigin(const std::vector<double>& x) {
  double s = 10.0 * x.size();
  for (double v : x) s += v * v - 10 * std::cos(2 * std::numbers::pi * v);
  return s;
}

/// Runs PSO to the end through ask/tell and returns the best value found.
double minimize(const Objective& f, int dim, double lo, double hi, const PsoSettings& settings, std::uint64_t seed) {
  Bounds b{std::vector<double>(dim, lo), std::vector<double>(dim, hi)};
  Pso pso(settings, b, hash_key({seed}));
  CandidateBatch batch(dim, settings.population);
  std::vector<double> values(settings.population);
  while (!pso.finished()) {
    pso.ask(batch, 0);
    for (int i = 0; i < settings.population; ++i) values[i] = f(batch.candidate(i));
    pso.tell(values);
  }
  return pso.best_value();
}

struct Case {
  const char* name;
  Objective f;
  int dim;
  double lo, hi;
  int population, iterations;
  double target;      ///< success: best value below this (the optimum is 0 for all three)
  int min_successes;  ///< out of 20 seeded runs
};

class PsoStandardFunctions : public ::testing::TestWithParam<Case> {};

/// Names the case in test listings instead of dumping its bytes.
void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

}  // namespace

TEST_P(PsoStandardFunctions, ReachesKnownOptimum) {
  const Case& c = GetParam();
  PsoSettings s;
  s.population = c.population;
  s.iterations = c.iterations;
  int successes = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) successes += minimize(c.f, c.dim, c.lo, c.hi, s, seed) < c.target;
  EXPECT_GE(successes, c.min_successes) << c.name << " in " << c.dim << " dimensions";
}

// Targets and success rates (out of 20 seeded runs; measured on this build: sphere ≤ 4e-15, Rosenbrock
// 2-D ≤ 1e-9, 5-D ≤ 0.033, 10-D median 0.04 with some runs in the local minimum near 3.99; Rastrigin
// 2-D always 0, 5-D ≤ 1.99 (one or two basins off), 10-D ≤ 10.9). Each target has margin over what was
// measured but still fails if the swarm stops converging.
INSTANTIATE_TEST_SUITE_P(
    Functions, PsoStandardFunctions,
    ::testing::Values(Case{"sphere2", sphere, 2, -5.12, 5.12, 30, 150, 1e-12, 20},
                      Case{"sphere5", sphere, 5, -5.12, 5.12, 50, 300, 1e-12, 20},
                      Case{"sphere10", sphere, 10, -5.12, 5.12, 50, 500, 1e-12, 20},
                      Case{"rosenbrock2", rosenbrock, 2, -2.048, 2.048, 30, 300, 1e-8, 19},
                      Case{"rosenbrock5", rosenbrock, 5, -2.048, 2.048, 50, 1000, 0.05, 18},
                      Case{"rosenbrock10", rosenbrock, 10, -2.048, 2.048, 50, 2000, 0.5, 10},
                      Case{"rastrigin2", rastrigin, 2, -5.12, 5.12, 30, 200, 1e-10, 19},
                      Case{"rastrigin5", rastrigin, 5, -5.12, 5.12, 50, 500, 2.5, 18},
                      Case{"rastrigin10", rastrigin, 10, -5.12, 5.12, 50, 1000, 15.0, 18}),
    [](const auto& p) { return std::string(p.param.name); });

TEST(Pso, SameKeySameHistory) {
  PsoSettings s;
  s.population = 20;
  s.iterations = 30;
  EXPECT_EQ(minimize(rastrigin, 4, -5.12, 5.12, s, 9), minimize(rastrigin, 4, -5.12, 5.12, s, 9));
  EXPECT_NE(minimize(rastrigin, 4, -5.12, 5.12, s, 9), minimize(rastrigin, 4, -5.12, 5.12, s, 10));
}

TEST(Pso, StaysInsideBounds) {
  PsoSettings s;
  s.population = 20;
  s.iterations = 50;
  Bounds b{{1.0, -3.0}, {2.0, -2.5}};  // the optimum of the sphere (0, 0) lies outside: particles press on the walls
  Pso pso(s, b, 77);
  CandidateBatch batch(2, s.population);
  std::vector<double> values(s.population);
  while (!pso.finished()) {
    pso.ask(batch, 0);
    for (int i = 0; i < s.population; ++i) {
      for (int j = 0; j < 2; ++j) {
        ASSERT_GE(batch.at(i, j), b.lower[j]);
        ASSERT_LE(batch.at(i, j), b.upper[j]);
      }
      values[i] = sphere(batch.candidate(i));
    }
    pso.tell(values);
  }
  EXPECT_NEAR(pso.best_position()[0], 1.0, 1e-9);
  EXPECT_NEAR(pso.best_position()[1], -2.5, 1e-9);
  EXPECT_NEAR(pso.best_value(), 1.0 + 6.25, 1e-8);
}

TEST(Pso, RejectsBadSettings) {
  Bounds b{{0.0}, {1.0}};
  PsoSettings s;
  s.population = 1;
  EXPECT_THROW(Pso(s, b, 1), InputError);
  s = {};
  s.iterations = 0;
  EXPECT_THROW(Pso(s, b, 1), InputError);
  s = {};
  s.vmax_fraction = 0;
  EXPECT_THROW(Pso(s, b, 1), InputError);
  s = {};
  s.social = -1;
  EXPECT_THROW(Pso(s, b, 1), InputError);
}

TEST(Pso, EvaluationBudgetIsPopulationTimesIterations) {
  PsoSettings s;
  s.population = 7;
  s.iterations = 13;
  Bounds b{{-1.0}, {1.0}};
  Pso pso(s, b, 3);
  CandidateBatch batch(1, s.population);
  int evaluations = 0;
  while (!pso.finished()) {
    pso.ask(batch, 0);
    std::vector<double> v(s.population, 1.0);
    pso.tell(v);
    evaluations += s.population;
  }
  EXPECT_EQ(evaluations, 7 * 13);
}

}  // namespace dampbench
