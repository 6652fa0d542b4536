// The conformance suite: every optimizer of kOptimizers (built by name through optimizers/registry.hpp)
// passes the same checks — same key same history, lockstep batch = alone, 1 and 2 threads and any batch
// split through identify(), bounds (a fixed parameter included), budget, failed candidates (+inf, NaN, −inf)
// masked, a best position before the first tell, a run where everything fails, and its convergence targets
// on the standard functions. A new optimizer gets the suite by one line in kOptimizers; its own test file
// keeps only what is its own (paper settings, operators, the local phase of a hybrid).
//
// Every run here is a whole run as identify() makes it: the population phase through ask/tell, then
// refine() (a no-op but for the hybrids, which see the function as a FunctionProblem).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <map>
#include <ostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "engine/common/key_values.hpp"
#include "engine/record/excitation.hpp"
#include "models/registry.hpp"
#include "optimizer_test_support.hpp"
#include "optimizers/registry.hpp"
#include "test_support.hpp"

namespace dampbench {
namespace {

using testing::kAckley;
using testing::kGriewank;
using testing::kRastrigin;
using testing::kRosenbrock;
using testing::kSphere;
using testing::SuccessCase;

// ---- convergence targets: `repeats` seeded runs, at least `min_successes` below the target --------------

/// Targets on the common grid, per function in the order sphere, Rosenbrock, Rastrigin, Ackley, Griewank,
/// each in 2, 5 and 10 dimensions.
using GridTargets = std::array<std::array<double, 3>, 5>;

/// The cases of the common grid: each function in 2, 5 and 10 dimensions with N = 30, 40, 50 and
/// L = 100, 200, 400, 18 of 20 seeded runs below the target; a case of `except` replaces the grid's case of
/// its function and dimension.
std::vector<SuccessCase> on_grid(const GridTargets& targets, std::initializer_list<SuccessCase> except = {}) {
  const testing::TestFunction functions[] = {kSphere, kRosenbrock, kRastrigin, kAckley, kGriewank};
  const int dims[] = {2, 5, 10}, populations[] = {30, 40, 50}, iterations[] = {100, 200, 400};
  std::vector<SuccessCase> cases;
  std::size_t replaced = 0;
  for (int f = 0; f < 5; ++f)
    for (int k = 0; k < 3; ++k) {
      SuccessCase c{functions[f], dims[k], populations[k], iterations[k], targets[f][k], 18, 20};
      for (const SuccessCase& e : except)
        if (e.function.f == c.function.f && e.dim == c.dim) c = e, ++replaced;
      cases.push_back(c);
    }
  if (replaced != except.size()) throw std::logic_error("on_grid: an exception matches no case of the grid");
  return cases;
}

// pso (inertia, the default). Targets and success rates (out of 20 seeded runs; measured on this build:
// sphere ≤ 4e-15, Rosenbrock 2-D ≤ 1e-9, 5-D ≤ 0.033, 10-D median 0.04 with some runs in the local minimum
// near 3.99; Rastrigin 2-D always 0, 5-D ≤ 1.99 (one or two basins off), 10-D ≤ 10.9). Each target has
// margin over what was measured but still fails if the swarm stops converging.
// Ackley and Griewank on the grid of the other optimizers (N = 30/40/50, L = 100/200/400), measured over
// seeds 1–20 and 1001–1020 (18th best of 20 | worst): Ackley 2-D 6.2e-5 | 1.2e-4, 5-D 1.4e-6 | 2.6e-6,
// 10-D 3.6e-9 | 6.1e-9; Griewank 2-D 0.0099 | 0.02, 5-D 0.10 | 0.13, 10-D 0.14 | 0.18 (Griewank keeps
// runs in the basins next to the origin, ≈ 0.0074 apart in 2-D).
const std::vector<SuccessCase> kPso = {
    {kSphere, 2, 30, 150, 1e-12, 20, 20},    {kSphere, 5, 50, 300, 1e-12, 20, 20},
    {kSphere, 10, 50, 500, 1e-12, 20, 20},   {kRosenbrock, 2, 30, 300, 1e-8, 19, 20},
    {kRosenbrock, 5, 50, 1000, 0.05, 18, 20}, {kRosenbrock, 10, 50, 2000, 0.5, 10, 20},
    {kRastrigin, 2, 30, 200, 1e-10, 19, 20}, {kRastrigin, 5, 50, 500, 2.5, 18, 20},
    {kRastrigin, 10, 50, 1000, 15.0, 18, 20}, {kAckley, 2, 30, 100, 5e-4, 18, 20},
    {kAckley, 5, 40, 200, 1e-5, 18, 20},     {kAckley, 10, 50, 400, 2e-8, 18, 20},
    {kGriewank, 2, 30, 100, 0.05, 18, 20},   {kGriewank, 5, 40, 200, 0.3, 18, 20},
    {kGriewank, 10, 50, 400, 0.4, 18, 20}};

// The named pso variants. Grid: N = 30, 40, 50 and L = 100, 200, 400 in 2, 5, 10 dimensions; 18 of 20
// seeded runs must beat the target. Measured over seeds 1–20 and 1001–1020, 18th best of 20 (worse
// block) | worst run:
//   constriction    sphere 1.4e-11 | 1.1e-10, 3.1e-14 | 6e-14, 2.5e-20 | 1.5e-19;
//                   Rosenbrock 1.3e-5 | 9.5e-4, 0.44 | 4.0 (local minimum), 5.4 | 7.0;
//                   Rastrigin 5.5e-7 | 3.3e-5, 2.0 | 2.0, 9.6 | 15;  Ackley 8.3e-5 | 1.6e-4,
//                   1.0e-6 | 1.8e-6, 1.4e-9 | 2.4e-9;  Griewank 0.02 | 0.027, 0.13 | 0.16, 0.11 | 0.19.
//   linear_inertia  sphere 4.8e-11 | 1.4e-10, 7.5e-11 | 2.2e-10, 3.5e-11 | 9.9e-11;
//                   Rosenbrock 3.6e-4 | 0.004, 1.1 | 1.3, 6.1 | 9.2;  Rastrigin 1.0e-7 | 4.1e-7,
//                   1.0 | 2.0, 7.9 | 10;  Ackley 1.5e-4 | 2.6e-4, 1.1e-4 | 3.2e-4, 5.9e-5 | 7.6e-5;
//                   Griewank 0.032 | 0.047, 0.19 | 0.25, 0.20 | 0.34.
// Targets: about three times the 18th best, rounded up (Rastrigin: the next basin boundary above it).
const std::vector<SuccessCase> kPsoConstriction =
    on_grid({{{1e-10, 1e-10, 1e-10}, {5e-5, 2.0, 20.0}, {2e-6, 3.5, 20.0}, {5e-4, 5e-6, 1e-8}, {0.05, 0.4, 0.4}}});
const std::vector<SuccessCase> kPsoLinearInertia =
    on_grid({{{2e-10, 5e-10, 2e-10}, {2e-3, 4.0, 20.0}, {5e-7, 2.5, 20.0}, {5e-4, 5e-4, 2e-4}, {0.1, 0.5, 0.6}}});

// ga. Defaults (pc 0.9, pm 1/d, SBX η_c 2, polynomial η_m 20, binary tournament, ⌈N/10⌉ elites; see
// optimizers/ga/ga.hpp). Grid N = 30/40/50, L = 100/200/400 in 2/5/10 dimensions. Measured over seeds 1–20
// and 1001–1020 (18th best of 20 in each block; worst run):
//   sphere      6.2e-6 3.7e-6 (1.2e-5);  3.2e-6 3.5e-6 (6.6e-6);  4.7e-6 3.7e-6 (8.6e-6)
//   Rosenbrock  L = 200 in 2-D: 1.4e-4 1.2e-4 (6.4e-4);  5-D 2.0 4.0 (4.6, the local minimum near 3.99);
//               10-D 7.2 7.0 (8.8)
//   Rastrigin   1.1e-3 1.8e-3 (2.9e-3);  3.9e-3 3.0e-3 (0.031);  2.3e-3 3.9e-3 (1.0)
//   Ackley      0.045 0.044 (0.14);  0.028 0.029 (0.034);  0.013 0.013 (0.022)
//   Griewank    0.018 0.029 (0.031);  0.057 0.076 (0.087);  0.10 0.10 (0.14)
// (With the former η_c 15 and one elite: sphere 3.2e-5 … 5.8e-4, Rastrigin 7.3e-3 … 0.30, Ackley ≈ 0.1–0.18,
// Griewank 0.036 … 0.37; Rosenbrock 5-D 4.0 2.1.)
// Targets: about three times the worse 18th best (1.5 times above 1), rounded up; every target is below
// the 10th percentile of random sampling with the same budget (e.g. 2-D Rosenbrock 0.0019 at 6 000
// samples, 10-D Rastrigin 61), so a GA that stops converging fails.
const std::vector<SuccessCase> kGa =
    on_grid({{{2e-5, 2e-5, 2e-5}, {1e-3, 7.0, 15.0}, {6e-3, 0.02, 0.02}, {0.2, 0.1, 0.05}, {0.1, 0.3, 0.3}}},
            {{kRosenbrock, 2, 30, 200, 1e-3, 18, 20}});

// aga. Defaults (k1 = k3 = 1, k2 = k4 = 0.5, pm_min = 1/(2d), GA operators). Grid N = 30/40/50,
// L = 100/200/400 in 2/5/10 dimensions. Measured over seeds 1–20 and 1001–1020 (18th best of 20 in each
// block; worst run):
//   sphere      2.3e-5 2.2e-5 (4.5e-5);  1.2e-4 9.2e-5 (2.0e-4);  1.9e-4 1.3e-4 (3.2e-4)
//   Rosenbrock  L = 200 in 2-D: 9.3e-4, 1.1e-3 (1.9e-3; 18 and 17 runs below 1e-3);  5-D 2.6 2.6 (4.5);
//               10-D 7.6 8.9 (9.2)
//   Rastrigin   3.1e-3 7.3e-3 (9.5e-3);  0.031 0.028 (1.0);  0.060 0.059 (0.11)
//   Ackley      0.10 0.08 (0.19);  0.13 0.15 (0.19);  0.11 0.15 (0.16)
//   Griewank    0.035 0.026 (0.038);  0.094 0.088 (0.13);  0.17 0.17 (0.24)
// With S&P's literal pm_min = 0.005 the same grid gave 2-D Ackley 1.7 and Rastrigin 1.1 (18th best), no
// better than random sampling: see optimizers/ga/aga.hpp. Targets: about three times the worse 18th best
// (1.5 times above 1), rounded up, each below the 10th percentile of random sampling with the same budget.
const std::vector<SuccessCase> kAga =
    on_grid({{{7e-5, 4e-4, 7e-4}, {1e-3, 4.0, 15.0}, {0.03, 0.1, 0.2}, {0.3, 0.5, 0.5}, {0.1, 0.3, 0.7}}},
            {{kRosenbrock, 2, 30, 200, 1e-3, 15, 20}});

// de, F = 0.5, CR = 0.9. Grid N = 30/40/50, L = 100/200/400 in 2/5/10 dimensions. Measured over seeds 1–20
// and 1001–1020 (18th best of 20 in each block; worst run):
//   rand1bin           sphere ≤ 2.4e-16 (6.6e-16) everywhere;  Rosenbrock 1.7e-5 1.4e-15 (0.1), 0.98 0.86
//                      (1.9), 5.7 5.8 (6.3);  Rastrigin 1.2e-13 (4.6e-13), 3.5 5.0 (5.5), 30 31 (38);
//                      Ackley 8.3e-10 (1.3e-9), 1.1e-7 (1.5e-7), 2.2e-7 (3e-7);  Griewank 4.5e-5 4.5e-6
//                      (3.1e-3), 0.18 0.20 (0.29), 0.45 0.44 (0.51)
//   best1bin           sphere 4e-44, 1.3e-55 (2.2e-11), 10-D 0.021 0.040 (0.056: the population collapses
//                      early, F = 0.5 is small for best/1);  Rosenbrock 2-D 0 in 17 and 19 of 20 runs
//                      (others 0.08–0.29), 4.2 3.9 (4.5), 9.5 15 (54);  Rastrigin 2-D 0 in 15 and 16 of 20
//                      (others 0.99), 5-D 18 and 14 runs below 7.5 (worst 12), 10-D 24 27 (52);
//                      Ackley 4.4e-16 (4e-15), 1.6 4e-15 (2.3), 4.2 4.8 (7.7);  Griewank 0.0074 0.0099
//                      (0.03), 0.26 0.21 (0.3), 0.43 0.38 (0.63)
//   currenttobest1bin  sphere 5.7e-30, 2.7e-38, 10-D 1.6e-3 9.7e-4 (6.2e-3);  Rosenbrock 8.2e-20 2.8e-16
//                      (0.015), 2.9 3.8 (4.2), 8.8 8.9 (9.6);  Rastrigin 0 0 (0.99), 1 1 (2), 14 13 (20);
//                      Ackley 1.6e-12 (3.6e-12), 4e-15, 2.0 1.2 (2.3);  Griewank 5.4e-13 (1.4e-12),
//                      0.069 0.067 (0.12), 0.14 0.14 (0.17)
// Targets: about three times the worse 18th best (1.5 times above 1), rounded up, each below the 10th
// percentile of random sampling with the same budget (2-D Rosenbrock 0.0049, 5-D Rastrigin 13, 10-D
// Rastrigin 61, 10-D Ackley 15); where a strategy sometimes stops in a basin next to the optimum, a tight
// target with a stated lower success count instead.
const std::vector<SuccessCase> kDeRand1bin =
    on_grid({{{1e-10, 1e-10, 1e-10}, {7e-5, 3.0, 10.0}, {1e-10, 10.0, 40.0}, {3e-9, 4e-7, 7e-7}, {1e-4, 0.7, 1.5}}});
const std::vector<SuccessCase> kDeBest1bin =
    on_grid({{{1e-10, 1e-10, 0.15}, {1e-10, 7.0, 30.0}, {1e-10, 7.5, 40.0}, {1e-10, 3.0, 10.0}, {0.03, 1.0, 1.5}}},
            {{kRosenbrock, 2, 30, 100, 1e-10, 15, 20}, {kRastrigin, 2, 30, 100, 1e-10, 13, 20},
             {kRastrigin, 5, 40, 200, 7.5, 12, 20}});
const std::vector<SuccessCase> kDeCurrentToBest1bin =
    on_grid({{{1e-10, 1e-10, 5e-3}, {1e-10, 7.0, 15.0}, {1e-10, 1.5, 30.0}, {1e-10, 1e-10, 3.0}, {1e-10, 0.3, 0.5}}});

// cmaes, ipop (the default) and bipop; population = λ₀ (N = 30/40/50, L = 100/200/400 asks). Measured over
// seeds 1–20 and 1001–1020 (18th best of 20 in each block; worst run), the same for both restart schemes
// on this grid (BIPOP's first small run comes after the second large one, which few of these budgets reach):
//   sphere      1.3e-17 4.5e-17 (7.1e-17);  5.2e-15 3.2e-15 (6.7e-15);  2.1e-14 2.3e-14 (2.6e-14)
//               (each run ends on tolfun, its values within 1e-12; later runs do not go lower)
//   Rosenbrock  8.7e-17 2.0e-17 (0.21);  3.1e-15 4.8e-15 (8.1e-15);  2.3e-14 2.2e-14 (3.99, a run in the
//               local minimum)
//   Rastrigin   0.14 0.23 (1.0);  1.99 1.99 (2.98);  3.98 2.98 (9.95)
//   Ackley      2.8e-11 3.0e-11 (2.48);  3.5e-11 3.3e-11 (4.6e-11);  4.3e-11 4.6e-11 (4.8e-11)
//   Griewank    0.031 0.0099 (0.040);  0.025 0.027 (0.076);  3.2e-14 2.4e-14 (4.1e-8)
// Targets: about three times the worse 18th best (1.5 times above 1), rounded up.
const std::vector<SuccessCase> kCmaes =
    on_grid({{{2e-16, 2e-14, 1e-13}, {3e-16, 2e-14, 1e-13}, {0.7, 3.0, 6.0}, {1e-10, 2e-10, 2e-10}, {0.1, 0.1, 1e-13}}});

// ga-sqp and ga-lm: the population phase is the ga's, bit for bit (their own tests), so only what refine
// adds, in 2-D on the ga's grid: SLSQP on f with finite-difference gradients; LM on the residuals of the
// sphere and Rosenbrock (r = x; r = (10 (x_{i+1} − x_i²), 1 − x_i)). Measured over seeds 1–20 and
// 1001–1020 (18th best of 20 in each block; worst run):
//   ga-sqp  sphere 3.69e-13 3.72e-13 (5.12e-13);  Rosenbrock (L = 200) 1.51e-8 in both (1.51e-8: forward
//           differences end there);  Rastrigin 1.04e-10 (1.04e-10);  Ackley 8.79e-6 6.39e-6 (1.02e-5)
//   ga-lm   sphere 5.29e-26 1.53e-26 (8.32e-26);  Rosenbrock (L = 200) 4.92e-25 8.53e-25 (1.54e-24)
// where the ga alone ends near 3e-5, 4e-4, 7e-3 and 0.1. (Griewank, and ga-lm on functions without
// residuals, gain little; in 5-D and 10-D the same holds, at several times the cost.)
// ga-lm with global = cmaes (ipop) on the same two cases: 1.25e-23 4.24e-23 (4.97e-23); 3.21e-24 2.02e-24
// (5.9e-24): LM stops on ftol a little higher than from the GA's end points, at far below either phase alone.
// Targets: about three times the worse 18th best, rounded up.
const std::vector<SuccessCase> kGaSqp = {{kSphere, 2, 30, 100, 2e-12, 18, 20},
                                         {kRosenbrock, 2, 30, 200, 5e-8, 18, 20},
                                         {kRastrigin, 2, 30, 100, 4e-10, 18, 20},
                                         {kAckley, 2, 30, 100, 3e-5, 18, 20}};
const std::vector<SuccessCase> kGaLm = {{kSphere, 2, 30, 100, 2e-25, 18, 20}, {kRosenbrock, 2, 30, 200, 3e-24, 18, 20}};
const std::vector<SuccessCase> kGaLmCmaes = {{kSphere, 2, 30, 100, 2e-22, 18, 20},
                                             {kRosenbrock, 2, 30, 200, 1e-23, 18, 20}};

// ---- the optimizers ---------------------------------------------------------------------------------

struct Entry {
  const char* label;  ///< test-name suffix
  OptimizerSpec spec;  ///< registry name and settings; population and iterations are set by each check
  /// StaysInsideBounds: the best must end within 7.5 + corner_tolerance of the box corner's 7.5.
  double corner_tolerance;
  /// ConvergesBesideFailedCandidates: the best (seed 5, N = 30, L = 100) must end below this.
  double beside_failures_target;
  const std::vector<SuccessCase>* cases;  ///< StandardFunctions: its targets

  [[nodiscard]] OptimizerFactory make(int population, int iterations) const {
    return make_optimizer_factory({spec.name, population, iterations, spec.settings});
  }
};
void PrintTo(const Entry& e, std::ostream* os) { *os << e.label; }

OptimizerSpec named(const char* name, std::map<std::string, std::string> settings = {}) {
  return {name, 50, 100, std::move(settings)};
}

// Corner tolerances, measured 7.5 + … after 50 generations: pso's absorbing walls put particles exactly on
// the bounds (rounding); ga 1.2e-10 and aga 2.1e-9 (SBX and polynomial mutation reach a bound only in the
// limit); de 5.8e-6 (rand1bin), 3.6e-15 (best1bin), 3.3e-9 (currenttobest1bin): midpoint repair approaches
// a bound geometrically, and only when a mutant crosses it.
// Beside failures, measured (seed 5, N = 30, L = 100), the same beside +inf, NaN and −inf: pso 8.2e-10
// (inertia), 2.5e-11 (constriction), 8.1e-9 (linear_inertia); ga 5.6e-5; aga 7.2e-5; de 1.9e-14
// (rand1bin), 0 (best1bin), 1.7e-25 (currenttobest1bin). The hybrids, refine included: corner 7.5 + 0 for
// both; beside failures 3.6e-13 (ga-sqp) and 4.9e-5 (ga-lm: this function has no residual form); ga-lm with
// global = cmaes keeps ga-lm's two tolerances (its cmaes phase alone is within cmaes's). cmaes
// (ipop and bipop): corner 7.5 + 0 (the boundary transformation reaches a bound exactly); beside failures
// 2.4e-17.
// A new optimizer: one line here (its registry name and settings, the two tolerances, its targets above).
const Entry kOptimizers[] = {
    {"pso", named("pso"), 1e-9, 1e-6, &kPso},
    {"pso_constriction", named("pso", {{"variant", "constriction"}}), 1e-9, 1e-6, &kPsoConstriction},
    {"pso_linear_inertia", named("pso", {{"variant", "linear_inertia"}}), 1e-9, 1e-6, &kPsoLinearInertia},
    {"ga", named("ga"), 1e-6, 1e-3, &kGa},
    {"aga", named("aga"), 1e-6, 1e-3, &kAga},
    {"de_rand1bin", named("de", {{"strategy", "rand1bin"}}), 1e-4, 1e-8, &kDeRand1bin},
    {"de_best1bin", named("de", {{"strategy", "best1bin"}}), 1e-4, 1e-8, &kDeBest1bin},
    {"de_currenttobest1bin", named("de", {{"strategy", "currenttobest1bin"}}), 1e-4, 1e-8, &kDeCurrentToBest1bin},
    {"cmaes_ipop", named("cmaes"), 1e-12, 1e-15, &kCmaes},
    {"cmaes_bipop", named("cmaes", {{"restarts", "bipop"}}), 1e-12, 1e-15, &kCmaes},
    {"ga_sqp", named("ga-sqp"), 1e-9, 1e-10, &kGaSqp},
    {"ga_lm", named("ga-lm"), 1e-9, 1e-3, &kGaLm},
    {"ga_lm_cmaes", named("ga-lm", {{"global", "cmaes"}}), 1e-9, 1e-3, &kGaLmCmaes},
};

std::string label_of(const ::testing::TestParamInfo<Entry>& info) { return info.param.label; }

/// fvd.gv_linear_elastic on two sines with a friction force it cannot follow, so that runs end apart.
struct SmallIdentification {
  const Model& model = find_model("fvd.gv_linear_elastic");
  Signals data;
  SmallIdentification() {
    Dataset record = testing::two_sine_record(400);
    const std::vector<double> truth{300, 9e5, 0.4, 5e6};
    record.F_N = model.simulate(truth, prepare_signals(record));
    for (std::size_t k = 0; k < record.F_N.size(); ++k) record.F_N[k] += 1.5e4 * std::tanh(record.v_m_s[k] / 0.02);
    data = prepare_signals(record);
  }
};

// ---- every check, every optimizer -------------------------------------------------------------------

class Conformance : public ::testing::TestWithParam<Entry> {
 protected:
  [[nodiscard]] OptimizerFactory make(int population, int iterations) const {
    return GetParam().make(population, iterations);
  }
};

TEST_P(Conformance, SameKeySameHistory) { testing::expect_keyed_history(make(20, 30)); }

TEST_P(Conformance, LockstepEqualsAlone) { testing::expect_lockstep_equals_alone(make(12, 15)); }

TEST_P(Conformance, SameBitsForAnyThreadCountBatchSplitAndOneByOne) {
  const SmallIdentification p;
  testing::expect_reproducible_identification(make(16, 5), p.model, p.data, default_bounds(p.model), 16 * 5);
}

TEST_P(Conformance, StaysInsideBounds) {
  testing::expect_stays_inside_bounds(make(20, 50), GetParam().corner_tolerance);
}

// Generation 0 (the initial population) is evaluated like every other: N × iterations, also for odd N.
TEST_P(Conformance, EvaluationBudgetIsPopulationTimesIterations) {
  for (const auto& [population, iterations] : {std::pair{8, 13}, std::pair{7, 5}, std::pair{7, 13}, std::pair{10, 8}}) {
    SCOPED_TRACE(::testing::Message() << "N = " << population << ", L = " << iterations);
    testing::expect_budget(make(population, iterations), population, iterations);
  }
}

TEST_P(Conformance, ConvergesBesideFailedCandidates) {
  const OptimizerFactory f = make(30, 100);
  for (const double failure : {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN(),
                               -std::numeric_limits<double>::infinity()}) {
    SCOPED_TRACE(::testing::Message() << "failure = " << failure);
    testing::expect_converges_beside_failures(f, failure, GetParam().beside_failures_target);
  }
}

TEST_P(Conformance, BestPositionInsideBeforeFirstTell) { testing::expect_best_position_before_first_tell(make(10, 20)); }

TEST_P(Conformance, SurvivesAllCandidatesFailing) { testing::expect_survives_all_failures(make(10, 20)); }

INSTANTIATE_TEST_SUITE_P(Optimizers, Conformance, ::testing::ValuesIn(kOptimizers), label_of);

// ---- convergence on the standard functions, every optimizer's own targets ------------------------------

/// One optimizer's cases on one function (every dimension: one test, as each test is a process of its own).
struct FunctionCases {
  const Entry* optimizer;
  std::vector<SuccessCase> cases;
  [[nodiscard]] std::string name() const { return std::string(optimizer->label) + "_" + cases.front().function.name; }
};
void PrintTo(const FunctionCases& k, std::ostream* os) { *os << k.name(); }

std::vector<FunctionCases> convergence_cases() {
  std::vector<FunctionCases> out;
  for (const Entry& e : kOptimizers)
    for (const SuccessCase& c : *e.cases) {
      if (out.empty() || out.back().optimizer != &e || out.back().cases.front().function.f != c.function.f)
        out.push_back({&e, {}});
      out.back().cases.push_back(c);
    }
  return out;
}

class StandardFunctions : public ::testing::TestWithParam<FunctionCases> {};

TEST_P(StandardFunctions, ReachesKnownOptimum) {
  const Entry& e = *GetParam().optimizer;
  for (const SuccessCase& c : GetParam().cases)
    testing::expect_success_rate(c, [&e](int population, int iterations) { return e.make(population, iterations); });
}

INSTANTIATE_TEST_SUITE_P(Optimizers, StandardFunctions, ::testing::ValuesIn(convergence_cases()),
                         [](const auto& p) { return p.param.name(); });

// ---- settings: each optimizer rejects a bad value with a message that names it and the setting ------------

struct Rejection {
  const char* optimizer;
  int population, iterations;
  const char* settings;  ///< "name=value,name=value"
  const char* message;   ///< of the InputError make_optimizer_factory throws, or "no error"
};

/// φ = 4 exactly: χ would be 1 and the swarm would not converge.
constexpr const char* kPhiOfFour =
    "pso: the constriction variant needs phi = cognitive + social > 4 (Clerc & Kennedy 2002), got 4";
/// The hybrids take the ga's settings but its preset, and only their own local-phase settings.
constexpr const char* kGaSqpUnknownPreset =
    "ga-sqp: unknown setting 'preset' (known: global, pc, pm, eta_c, eta_m, tournament, elites, constraint, "
    "sqp_iterations, fd_step, xtol, ftol)";
constexpr const char* kGaLmUnknownConstraint =
    "ga-lm: unknown setting 'constraint' (known: global, pc, pm, eta_c, eta_m, tournament, elites, lm_iterations, "
    "fd_step, ftol, xtol, gtol, lambda0, geodesic, geodesic_ratio)";

// 50 and 100 are each optimizer's default population and iterations. Non-finite numbers never come through
// the registry (its parser rejects "nan" and "inf"), so each optimizer's own file gives one to its class.
const Rejection kRejections[] = {
    {"pso", 1, 100, "", "pso: population must be at least 2, got 1"},
    {"pso", 50, 0, "", "pso: iterations must be at least 1, got 0"},
    {"pso", 50, 100, "vmax_fraction=0", "pso: vmax_fraction must be a finite number > 0, got 0"},
    {"pso", 50, 100, "social=-1", "pso: social must be a finite number >= 0, got -1"},
    {"ga", 2, 100, "", "ga: population must be at least 4, got 2"},
    {"ga", 50, 0, "", "ga: iterations (generations) must be at least 1, got 0"},
    {"ga", 50, 100, "pc=1.5", "ga: pc must be in [0, 1], got 1.5"},
    {"ga", 50, 100, "pm=-0.1", "ga: pm must be in [0, 1], got -0.1"},
    {"ga", 50, 100, "tournament=1", "ga: tournament must be at least 2, got 1"},
    {"ga", 50, 100, "tournament=51", "ga: tournament must be in [2, population = 50], got 51"},
    {"ga", 50, 100, "elites=26", "ga: elites must be in [0, population / 2 = 25], got 26"},
    {"ga", 50, 100, "elites=-1", "ga: elites must be at least 0, got -1"},
    {"ga", 50, 100, "eta_c=-1", "ga: eta_c must be a finite number >= 0, got -1"},
    {"ga", 50, 100, "", "no error"},
    {"aga", 3, 100, "", "aga: population must be at least 4, got 3"},
    {"aga", 50, 100, "k1=2", "aga: k1 must be in [0, 1], got 2"},
    {"aga", 50, 100, "k2=-0.5", "aga: k2 must be in [0, 1], got -0.5"},
    {"aga", 50, 100, "k3=1.1", "aga: k3 must be in [0, 1], got 1.1"},
    {"aga", 50, 100, "pm_min=3", "aga: pm_min must be in [0, 1], got 3"},
    {"aga", 50, 100, "tournament=60", "aga: tournament must be in [2, population = 50], got 60"},
    {"aga", 50, 100, "eta_c=-2", "aga: eta_c must be a finite number >= 0, got -2"},
    {"aga", 50, 100, "", "no error"},
    {"de", 3, 100, "", "de: population must be at least 4, got 3"},
    {"de", 50, 0, "", "de: iterations (generations) must be at least 1, got 0"},
    {"de", 50, 100, "F=0", "de: F must be in (0, 2], got 0"},
    {"de", 50, 100, "F=2.5", "de: F must be in (0, 2], got 2.5"},
    {"de", 50, 100, "CR=1.2", "de: CR must be in [0, 1], got 1.2"},
    {"de", 50, 100, "F=2,CR=0", "no error"},  // both ends included
    {"cmaes", 1, 100, "", "cmaes: population must be 0 (the default 4 + floor(3 ln n)) or at least 2, got 1"},
    {"cmaes", 50, 0, "", "cmaes: iterations must be at least 1, got 0"},
    {"cmaes", 50, 100, "restarts=sometimes", "cmaes: unknown restarts 'sometimes' (known: none, ipop, bipop)"},
    {"cmaes", 50, 100, "sigma0=0", "cmaes: sigma0 must be in (0, 1], got 0"},
    {"cmaes", 50, 100, "sigma0=1.5", "cmaes: sigma0 must be in (0, 1], got 1.5"},
    {"cmaes", 50, 100, "tolfun=-1", "cmaes: tolfun must be a finite number >= 0, got -1"},
    {"cmaes", 50, 100, "tolx=-1e-3", "cmaes: tolx must be a finite number >= 0, got -0.001"},
    {"cmaes", 50, 100, "lambda=10", "cmaes: unknown setting 'lambda' (known: restarts, sigma0, tolfun, tolx)"},
    {"cmaes", 0, 100, "restarts=none,sigma0=1,tolx=0", "no error"},
    {"ga-sqp", 3, 10, "", "ga-sqp: population must be at least 4, got 3"},
    {"ga-sqp", 20, 10, "pc=1.5", "ga-sqp: pc must be in [0, 1], got 1.5"},
    {"ga-sqp", 20, 10, "pm=-0.1", "ga-sqp: pm must be in [0, 1], got -0.1"},
    {"ga-sqp", 20, 10, "constraint=-1", "ga-sqp: constraint must be a number > 0 or off, got -1"},
    {"ga-sqp", 20, 10, "constraint=four", "ga-sqp: setting 'constraint': expected a number, got 'four'"},
    {"ga-sqp", 20, 10, "sqp_iterations=0", "ga-sqp: sqp_iterations must be at least 1, got 0"},
    {"ga-sqp", 20, 10, "sqp_iterations=2.5", "ga-sqp: setting 'sqp_iterations': expected a whole number, got '2.5'"},
    {"ga-sqp", 20, 10, "fd_step=0", "ga-sqp: fd_step must be in (0, 0.1], got 0"},
    {"ga-sqp", 20, 10, "xtol=-1", "ga-sqp: xtol must be a finite number >= 0, got -1"},
    {"ga-sqp", 20, 10, "constraint=off", "no error"},
    {"ga-lm", 2, 10, "", "ga-lm: population must be at least 4, got 2"},
    {"ga-lm", 20, 0, "", "ga-lm: iterations (generations) must be at least 1, got 0"},
    {"ga-lm", 20, 10, "pc=-0.5", "ga-lm: pc must be in [0, 1], got -0.5"},
    {"ga-lm", 20, 10, "lm_iterations=0", "ga-lm: lm_iterations must be at least 1, got 0"},
    {"ga-lm", 20, 10, "fd_step=0.5", "ga-lm: fd_step must be in (0, 0.1], got 0.5"},
    {"ga-lm", 20, 10, "lambda0=0", "ga-lm: lambda0 must be a finite number > 0, got 0"},
    {"ga-lm", 20, 10, "gtol=-1", "ga-lm: gtol must be a finite number >= 0, got -1"},
    {"ga-lm", 20, 10, "geodesic=2", "ga-lm: geodesic must be 0 or 1, got 2"},
    {"ga-lm", 20, 10, "geodesic_ratio=0", "ga-lm: geodesic_ratio must be a finite number > 0, got 0"},
    {"ga-lm", 20, 10, "ftol=x", "ga-lm: setting 'ftol': expected a number, got 'x'"},
    {"pso", 50, 100, "variant=constriction,cognitive=1.5,social=2.5", kPhiOfFour},
    {"ga-sqp", 20, 10, "preset=lssvm", kGaSqpUnknownPreset},
    {"ga-lm", 20, 10, "constraint=4", kGaLmUnknownConstraint},
};

TEST(OptimizerSettings, RejectsBadValuesWithTheirMessages) {
  for (const Rejection& r : kRejections) {
    OptimizerSpec spec{r.optimizer, r.population, r.iterations};
    for (const auto& [name, value] : parse_key_values(r.settings, "settings")) spec.settings[name] = value;
    EXPECT_EQ(testing::error_of([&] { (void)make_optimizer_factory(spec); }), r.message)
        << r.optimizer << " " << r.settings;
  }
}

}  // namespace
}  // namespace dampbench
