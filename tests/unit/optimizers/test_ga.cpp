// GA (optimizers/ga/ga.hpp) and the operators it shares with the AGA (optimizers/ga/operators.hpp): the lssvm
// preset, operator properties, settings checks. The checks every optimizer passes (standard functions,
// ask/tell conformance) are in test_optimizer_conformance.cpp.
#include "optimizers/ga/ga.hpp"
#include "optimizers/ga/operators.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/random.hpp"
#include "engine/identification/identification.hpp"
#include "engine/kernels/isa.hpp"
#include "models/registry.hpp"
#include "optimizers/registry.hpp"
#include "optimizer_test_support.hpp"
#include "test_support.hpp"

namespace dampbench {
namespace {

using testing::error_of;
using testing::factory_of;
using testing::kSphere;
using testing::SuccessCase;

}  // namespace

// ---- defaults on a damper problem ------------------------------------------------------------------

// Issue 13: `fit --optimizer ga` with its defaults (N = 50, 100 generations) on a noisy 6-parameter Kwok
// record must reach the noise floor as DE does. crfd.kwok at {3, 25, 0.5, 6, 0.8, 0.011} on the
// two-frequency record, 0.5 % Gaussian noise; floor = the RMSE of the truth itself. Success: the best of
// 10 runs within 1.02 × the floor and at least 4 of the 10 runs there. Measured (seeds 7, 40 runs): 23 of
// 40 runs with the defaults, 6 of 40 with the former η_c = 15 and one elite (which fails this test); DE
// with the same budget 40 of 40. Re-measured 2026-11-25 (the code before and after the GAs' vector pow
// alike): 30 and 8 of 40.
TEST(Ga, DefaultsReachTheNoiseFloorOnKwok) {
  const Model& model = find_model("crfd.kwok");
  const std::vector<double> truth{3.0, 25.0, 0.5, 6.0, 0.8, 0.011};
  Dataset d = testing::two_sine_record(300, 250.0);
  d.F_N = model.simulate(truth, prepare_signals(d));
  const double floor = testing::add_force_noise(d, 0.005, 13);
  const Signals data = prepare_signals(d);

  testing::retry(2, [&](int attempt) {
    IdentificationSettings s;
    s.runs = 10;
    s.seed = 1 + static_cast<std::uint64_t>(attempt);
    s.metric = Metric::rmse;
    s.task_key = task_key("crfd.kwok", "two_sine", "ga");
    const auto id = identify(model, data, default_bounds(model), make_optimizer_factory({"ga", 50, 100}), s);
    int at_floor = 0;
    std::string values;
    for (const RunResult& r : id.runs) {
      at_floor += r.best_value <= 1.02 * floor;
      values += fmt::format(" {:.4f}", r.best_value / floor);
    }
    const bool ok = id.runs[id.best_run()].best_value <= 1.02 * floor && at_floor >= 4;
    return ok ? ::testing::AssertionSuccess()
              : ::testing::AssertionFailure() << at_floor << " of 10 runs at 1.02 x the noise floor (need 4); "
                                              << "run / floor:" << values;
  });
}

// ---- the lssvm preset --------------------------------------------------------------------------------

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

// The rates are used: pc = 0 and pm = 0 ask only copies of initial members.
TEST(Ga, WithoutCrossoverAndMutationOnlyCopiesAreAsked) {
  GaSettings s = testing::generational<GaSettings>(10, 6);
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

TEST(GeneticOperators, FirstInOrderIsWhatPartialSortGives) {
  // Values with many ties and failures (+inf), ordered as the elitism orders them: lower value first, ties to the
  // lower index; and the reverse order (the worst offspring first, ties to the higher index).
  for (std::uint64_t k = 0; k < 50; ++k) {
    RandomStream rng(hash_key({k, 7}));
    const int n = 1 + static_cast<int>(rng.uniform() * 60);
    std::vector<double> v(static_cast<std::size_t>(n));
    for (double& x : v) {
      const double u = rng.uniform();
      x = u < 0.1 ? std::numeric_limits<double>::infinity() : std::floor(u * 8);
    }
    const auto better = [&](int i, int j) { return v[i] < v[j] || (v[i] == v[j] && i < j); };
    const auto worse = [&](int i, int j) { return v[j] < v[i] || (v[i] == v[j] && j < i); };
    for (int count : {0, 1, 2, 5, n / 2, n, n + 3}) {
      for (int order = 0; order < 2; ++order) {
        std::vector<int> expected(static_cast<std::size_t>(n)), got{42};
        std::iota(expected.begin(), expected.end(), 0);
        const int m = std::min(count, n);
        if (order == 0) {
          std::partial_sort(expected.begin(), expected.begin() + m, expected.end(), better);
          genetic::first_in_order(n, count, better, got);
        } else {
          std::partial_sort(expected.begin(), expected.begin() + m, expected.end(), worse);
          genetic::first_in_order(n, count, worse, got);
        }
        expected.resize(static_cast<std::size_t>(m));
        EXPECT_EQ(got, expected) << "n " << n << ", count " << count << ", order " << order;
      }
    }
  }
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

// sbx_draw's decisions from hand-made draws: which variables are crossed, how many draws each takes (1 if not
// crossed, 3 if crossed), identical parents left alone, each variable with its own bounds, children copied to their
// pool offsets.
TEST(GeneticOperators, SbxDrawDecidesFromItsDrawsVariableByVariable) {
  const std::vector<double> lo{0, -5, 10, 0}, hi{1, 5, 20, 2};
  const std::vector<double> a{0.2, 3.0, 12.0, 1.5}, b{0.7, -1.0, 12.0, 0.5};  // variable 2: identical parents
  // Draw per variable: 0: 0.1 crosses (u 0.3, swap draw 0.9: no swap); 1: 0.6 not crossed; 2: 0.2 would cross but
  // the parents are identical, so it is not crossed and takes one draw; 3: 0.4 crosses (u 0.8, swap draw 0.1: swap).
  const std::vector<double> draws{0.1, 0.3, 0.9, 0.6, 0.2, 0.4, 0.8, 0.1, 0.0, 0.0, 0.0, 0.0};
  std::vector<double> pool(12, -1.0);  // a pair's children at offsets 2 and 7
  genetic::CrossedVariables crossed;
  crossed.clear(4);
  const std::size_t used = genetic::sbx_draw(a, b, pool, 2, 7, lo, hi, draws, crossed);
  EXPECT_EQ(used, 3u + 1u + 1u + 3u);
  ASSERT_EQ(crossed.count, 2u);
  struct Entry {
    std::size_t at_a, at_b;
    double y1, y2, lower, upper, u, swap;
  };
  const Entry expected[2] = {{2, 7, 0.2, 0.7, 0, 1, 0.3, 0}, {5, 10, 0.5, 1.5, 0, 2, 0.8, 1}};
  for (std::size_t k = 0; k < 2; ++k) {
    const Entry& e = expected[k];
    const Entry got{crossed.at_a[k],  crossed.at_b[k],  crossed.y1[k], crossed.y2[k],
                    crossed.lower[k], crossed.upper[k], crossed.u[k],  crossed.swap[k]};
    EXPECT_TRUE(got.at_a == e.at_a && got.at_b == e.at_b && got.y1 == e.y1 && got.y2 == e.y2 && got.lower == e.lower &&
                got.upper == e.upper && got.u == e.u && got.swap == e.swap)
        << "entry " << k << ": at " << got.at_a << ", " << got.at_b << "; y " << got.y1 << ", " << got.y2 << "; box "
        << got.lower << ", " << got.upper << "; u " << got.u << "; swap " << got.swap;
  }
  const std::vector<double> copies{-1, -1, 0.2, 3.0, 12.0, 1.5, -1, 0.7, -1.0, 12.0, 0.5, -1};
  EXPECT_EQ(pool, copies);  // the children start as the parents' copies; sbx_finish crosses the two variables
  genetic::sbx_finish(crossed, 2.0, pool);
  EXPECT_EQ(pool[3], 3.0);   // not crossed
  EXPECT_EQ(pool[8], -1.0);
  EXPECT_EQ(pool[4], 12.0);  // identical parents
  EXPECT_EQ(pool[9], 12.0);
  for (const std::size_t i : {2u, 5u, 7u, 10u}) EXPECT_NE(pool[i], copies[i]) << "crossed variable at " << i;
  EXPECT_GE(std::min(pool[5], pool[10]), 0.0);  // variable 3 stays in its own box [0, 2]
  EXPECT_LE(std::max(pool[5], pool[10]), 2.0);
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

// The second halves' vector loops at every vector level: each crossed variable and mutated gene within a few ulp of
// the operators' formulas computed here with glibc's scalar pow, and elementwise: an entry gives the same bits
// alone or among others at another position (the GA's results must not depend on how many variables a
// generation crosses). Hand-checkable cases: a mutation draw u = 1/2 leaves the gene where it is (δ_q = 0), and a
// fixed parameter stays fixed.
TEST(GeneticOperators, SecondHalvesAreTheFormulasElementByElementAtEveryLevel) {
  const Isa saved = active_isa();
  const std::vector<double> lower{-1, 0, 2, 5}, upper{1, 10, 3, 5};
  const double eta = 7;
  // Reference formulas (Deb's NSGA-II code), scalar.
  const auto sbx_reference = [&](double y1, double y2, double lo, double hi, double u, double* c1, double* c2) {
    const double gap = y2 - y1;
    const auto beta_q = [&](double beta) {
      const double alpha = 2.0 - std::pow(beta, -(eta + 1.0));
      return u <= 1.0 / alpha ? std::pow(u * alpha, 1.0 / (eta + 1.0)) : std::pow(1.0 / (2.0 - u * alpha), 1.0 / (eta + 1.0));
    };
    *c1 = std::clamp(0.5 * ((y1 + y2) - beta_q(1.0 + 2.0 * (y1 - lo) / gap) * gap), lo, hi);
    *c2 = std::clamp(0.5 * ((y1 + y2) + beta_q(1.0 + 2.0 * (hi - y2) / gap) * gap), lo, hi);
  };
  const auto mutation_reference = [&](double x, double lo, double hi, double u) {
    const double range = hi - lo;
    if (!(range > 0)) return x;
    const double delta_q =
        u < 0.5 ? std::pow(2.0 * u + (1.0 - 2.0 * u) * std::pow(1.0 - (x - lo) / range, eta + 1.0), 1.0 / (eta + 1.0)) - 1.0
                : 1.0 - std::pow(2.0 * (1.0 - u) + 2.0 * (u - 0.5) * std::pow(1.0 - (hi - x) / range, eta + 1.0),
                                 1.0 / (eta + 1.0));
    return std::clamp(x + delta_q * range, lo, hi);
  };
  // The vector pow may differ from glibc's scalar pow by a few ulp of the power; a child or mutated gene is a sum of
  // a parent's value and that power times the spread (gap or range), so its error is a few ulp of `scale`, the
  // magnitude of the terms.
  const auto near = [](double got, double want, double scale) {
    return std::abs(got - want) <= 4 * std::numeric_limits<double>::epsilon() * scale;
  };
  for (const Isa isa : supported_isas()) {
    select_isa(isa);
    RandomStream rng(hash_key({11}));
    // 37 mutated genes (more than two blocks) in a pool of 10 children × 4 genes.
    std::vector<double> pool(40);
    for (std::size_t i = 0; i < pool.size(); ++i) pool[i] = rng.uniform(lower[i % 4], upper[i % 4]);
    const std::vector<double> before = pool;
    genetic::MutatedGenes all;
    all.clear(40);
    std::vector<double> us;
    for (std::size_t c = 0; c < 10; ++c) {
      std::vector<double> draws;
      for (int j = 0; j < 4; ++j) {
        us.push_back(c == 1 && j == 1 ? 0.5 : rng.uniform());
        if (c == 0 && j == 0) {
          draws.push_back(0.9);  // all genes but gene 0 of child 0 mutate; a gene that does not takes one draw
        } else {
          draws.push_back(0.0);
          draws.push_back(us.back());
        }
      }
      draws.resize(8);
      genetic::mutation_draw(c * 4, 0.5, lower, upper, draws, all);
    }
    ASSERT_EQ(all.count, 39u);
    genetic::mutate_all(all, eta, pool);
    EXPECT_EQ(pool[0], before[0]);  // not mutated
    EXPECT_EQ(pool[5], before[5]);  // u = 1/2
    for (std::size_t i = 0; i < pool.size(); ++i) {
      if (i % 4 == 3) {
        EXPECT_EQ(pool[i], before[i]) << "fixed parameter, " << isa_name(isa);
      }
      if (i == 0) continue;
      EXPECT_PRED3(near, pool[i], mutation_reference(before[i], lower[i % 4], upper[i % 4], us[i]),
                   std::abs(before[i]) + (upper[i % 4] - lower[i % 4]))
          << "gene " << i << ", " << isa_name(isa);
      std::vector<double> alone{before[i]};
      const double draws[2] = {0.0, us[i]};
      genetic::MutatedGenes one;
      one.clear(1);
      genetic::mutation_draw(0, 1.0, {lower[i % 4]}, {upper[i % 4]}, draws, one);
      genetic::mutate_all(one, eta, alone);
      EXPECT_EQ(std::bit_cast<std::uint64_t>(alone[0]), std::bit_cast<std::uint64_t>(pool[i])) << isa_name(isa);
    }
    // 20 crossed pairs of one variable each (every draw crosses), against the formula and each pair alone.
    const std::vector<double> lo1{-1}, hi1{3};
    std::vector<double> parents(40), children(40), u(20), swap(20);
    genetic::CrossedVariables crossed;
    crossed.clear(20);
    for (std::size_t k = 0; k < 20; ++k) {
      parents[2 * k] = rng.uniform(-1, 3);
      parents[2 * k + 1] = rng.uniform(-1, 3);
      u[k] = rng.uniform();
      swap[k] = rng.uniform();
      const double draws[3] = {0.0, u[k], swap[k]};
      genetic::sbx_draw(std::span(parents).subspan(2 * k, 1), std::span(parents).subspan(2 * k + 1, 1), children,
                        2 * k, 2 * k + 1, lo1, hi1, draws, crossed);
    }
    ASSERT_EQ(crossed.count, 20u);
    genetic::sbx_finish(crossed, eta, children);
    for (std::size_t k = 0; k < 20; ++k) {
      double c1 = 0, c2 = 0;
      sbx_reference(std::min(parents[2 * k], parents[2 * k + 1]), std::max(parents[2 * k], parents[2 * k + 1]), -1, 3,
                    u[k], &c1, &c2);
      if (swap[k] < 0.5) std::swap(c1, c2);
      const double scale = std::abs(parents[2 * k]) + std::abs(parents[2 * k + 1]) + 4.0;  // 4: the box's width
      EXPECT_PRED3(near, children[2 * k], c1, scale) << "pair " << k << ", " << isa_name(isa);
      EXPECT_PRED3(near, children[2 * k + 1], c2, scale) << "pair " << k << ", " << isa_name(isa);
      std::vector<double> pair{parents[2 * k], parents[2 * k + 1]};
      genetic::CrossedVariables one;
      one.clear(1);
      const double draws[3] = {0.0, u[k], swap[k]};
      genetic::sbx_draw(std::span(pair).first(1), std::span(pair).last(1), pair, 0, 1, lo1, hi1, draws, one);
      genetic::sbx_finish(one, eta, pair);
      EXPECT_EQ(std::bit_cast<std::uint64_t>(pair[0]), std::bit_cast<std::uint64_t>(children[2 * k])) << isa_name(isa);
      EXPECT_EQ(std::bit_cast<std::uint64_t>(pair[1]), std::bit_cast<std::uint64_t>(children[2 * k + 1])) << isa_name(isa);
    }
  }
  select_isa(saved);
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

// The other bad values are rejected through the registry (test_optimizer_conformance.cpp), which never
// passes a non-finite number.
TEST(Ga, RejectsNonFiniteSettings) {
  GaSettings nan_pc, inf_eta_m;
  nan_pc.pc = std::numeric_limits<double>::quiet_NaN();
  inf_eta_m.eta_m = std::numeric_limits<double>::infinity();
  EXPECT_EQ(error_of([&] { Ga(nan_pc, testing::box(1, 0, 1), 1); }), "ga: pc must be in [0, 1], got nan");
  EXPECT_EQ(error_of([&] { Ga(inf_eta_m, testing::box(1, 0, 1), 1); }), "ga: eta_m must be a finite number >= 0, got inf");
}

}  // namespace dampbench
