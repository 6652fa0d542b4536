#pragma once
// Helpers shared by the optimizer tests: standard test functions with known optima, the ask/tell loop that
// runs one optimizer to the end (and its refine), seeded success rates, a retry helper that can fail, and
// the checks of the conformance suite (tests/unit/optimizers/test_optimizer_conformance.cpp) that every optimizer passes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <sstream>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <tbb/task_arena.h>

#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/identification/identification.hpp"
#include "engine/identification/optimizer.hpp"
#include "engine/common/random.hpp"

namespace dampbench::testing {

// ---- standard functions (minimum 0; at the origin, Rosenbrock at (1, …, 1)) ----------------------------

inline double sphere(std::span<const double> x) {
  double s = 0;
  for (double v : x) s += v * v;
  return s;
}

/// Rosenbrock (1960), chained form; minimum 0 at (1, …, 1).
inline double rosenbrock(std::span<const double> x) {
  double s = 0;
  for (std::size_t i = 0; i + 1 < x.size(); ++i)
    s += 100 * std::pow(x[i + 1] - x[i] * x[i], 2) + std::pow(1 - x[i], 2);
  return s;
}

/// Rastrigin: 10 d + Σ (x² − 10 cos 2πx); a local minimum at every integer point.
inline double rastrigin(std::span<const double> x) {
  double s = 10.0 * static_cast<double>(x.size());
  for (double v : x) s += v * v - 10 * std::cos(2 * std::numbers::pi * v);
  return s;
}

/// Ackley (a = 20, b = 0.2, c = 2π).
inline double ackley(std::span<const double> x) {
  const double d = static_cast<double>(x.size());
  double sq = 0, cs = 0;
  for (double v : x) {
    sq += v * v;
    cs += std::cos(2 * std::numbers::pi * v);
  }
  return -20 * std::exp(-0.2 * std::sqrt(sq / d)) - std::exp(cs / d) + 20 + std::numbers::e;
}

/// Griewank: 1 + Σ x²/4000 − Π cos(x_i / √i), i = 1 … d.
inline double griewank(std::span<const double> x) {
  double s = 0, p = 1;
  for (std::size_t i = 0; i < x.size(); ++i) {
    s += x[i] * x[i] / 4000;
    p *= std::cos(x[i] / std::sqrt(static_cast<double>(i + 1)));
  }
  return 1 + s - p;
}

/// The sphere as least squares: r = x.
inline std::vector<double> sphere_residuals(std::span<const double> x) { return {x.begin(), x.end()}; }

/// Rosenbrock as least squares: r = (10 (x_{i+1} − x_i²), 1 − x_i), i = 1 … d − 1.
inline std::vector<double> rosenbrock_residuals(std::span<const double> x) {
  std::vector<double> r;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    r.push_back(10 * (x[i + 1] - x[i] * x[i]));
    r.push_back(1 - x[i]);
  }
  return r;
}

using Objective = std::function<double(std::span<const double>)>;

/// A standard function with its usual search box (the same bound in every dimension) and, for a sum of
/// squares, its residuals (Σ r² = f), which a least-squares local phase fits.
struct TestFunction {
  const char* name;
  double (*f)(std::span<const double>);
  double lower, upper;
  std::vector<double> (*residuals)(std::span<const double>) = nullptr;
};
inline constexpr TestFunction kSphere{"sphere", sphere, -5.12, 5.12, sphere_residuals};
inline constexpr TestFunction kRosenbrock{"rosenbrock", rosenbrock, -2.048, 2.048, rosenbrock_residuals};
inline constexpr TestFunction kRastrigin{"rastrigin", rastrigin, -5.12, 5.12};
inline constexpr TestFunction kAckley{"ackley", ackley, -32.768, 32.768};
inline constexpr TestFunction kGriewank{"griewank", griewank, -600, 600};

inline Bounds box(int dim, double lower, double upper) {
  return {std::vector<double>(dim, lower), std::vector<double>(dim, upper)};
}

// ---- running an optimizer -------------------------------------------------------------------------

/// A factory for an optimizer class constructed as Algorithm(settings, bounds, run_key).
template <class Algorithm, class Settings>
OptimizerFactory factory_of(const Settings& settings) {
  return [settings](const Bounds& bounds, std::uint64_t run_key) -> std::unique_ptr<Optimizer> {
    return std::make_unique<Algorithm>(settings, bounds, run_key);
  };
}

/// Settings of a generational optimizer (ga, aga, de, the hybrids) with its population and generations.
template <class Settings>
Settings generational(int population, int generations) {
  Settings s;
  s.population = population;
  s.generations = generations;
  return s;
}

struct Run {
  double best_value = 0;
  std::vector<double> best_position;
  long long evaluations = 0;
  int asks = 0;
  std::vector<double> history;  ///< every asked candidate, in order (only when requested)
};

/// Runs one optimizer to the end through ask/tell, evaluating f on every asked candidate.
inline Run minimize(Optimizer& opt, const Objective& f, int dim, bool keep_history = false) {
  Run run;
  CandidateBatch batch;
  std::vector<double> values, x(dim);
  while (!opt.finished()) {
    const int n = opt.batch_size();
    if (batch.count() != n) batch.resize(dim, n);
    values.resize(n);
    opt.ask(batch, 0);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < dim; ++j) x[j] = batch.at(i, j);
      if (keep_history) run.history.insert(run.history.end(), x.begin(), x.end());
      values[i] = f(x);
    }
    opt.tell(values);
    run.evaluations += n;
    ++run.asks;
  }
  run.best_value = opt.best_value();
  run.best_position.assign(opt.best_position().begin(), opt.best_position().end());
  return run;
}

inline Run minimize(const OptimizerFactory& make, const Objective& f, const Bounds& bounds, std::uint64_t seed,
                    bool keep_history = false) {
  const std::unique_ptr<Optimizer> opt = make(bounds, hash_key({seed}));
  return minimize(*opt, f, bounds.dim(), keep_history);
}

// ---- local phases as problems (hybrids: refine) ----------------------------------------------------

/// A LocalProblem over a closed-form least-squares function: residuals r(x), value Σ r² (or a plain objective
/// when built from one, or a standard function without residuals: its residuals are then {sqrt(f)}).
/// Records every point it evaluates, so a test can check that a local phase stays inside the box, and
/// counts evaluations.
class FunctionProblem final : public LocalProblem {
 public:
  using Residuals = std::function<std::vector<double>(std::span<const double>)>;
  FunctionProblem(Residuals residuals, Bounds bounds) : residuals_(std::move(residuals)), bounds_(std::move(bounds)) {}
  FunctionProblem(const Objective& f, Bounds bounds)
      : residuals_([f](std::span<const double> x) { return std::vector<double>{std::sqrt(f(x))}; }),
        bounds_(std::move(bounds)) {}
  FunctionProblem(const TestFunction& f, Bounds bounds)
      : FunctionProblem(f.residuals ? Residuals(f.residuals) : Residuals([f](std::span<const double> x) {
          return std::vector<double>{std::sqrt(f.f(x))};
        }), std::move(bounds)) {}

  [[nodiscard]] double value(std::span<const double> x) const {
    double s = 0;
    for (double r : residuals_(x)) s += r * r;
    return s;
  }
  void evaluate(const CandidateBatch& batch, std::span<double> values) const override {
    for (int i = 0; i < batch.count(); ++i) {
      const std::vector<double> x = batch.candidate(i);
      points.push_back(x);
      values[i] = value(x);
    }
    evaluations += batch.count();
  }
  [[nodiscard]] std::vector<double> residuals(std::span<const double> params) const override {
    ++residual_calls;
    ++rounds;
    return recorded_residuals(params);
  }
  /// One round for the whole batch, as a model problem's lane block.
  [[nodiscard]] std::vector<std::vector<double>> residuals_batch(std::span<const std::vector<double>> candidates) const override {
    ++rounds;
    residual_calls += static_cast<long long>(candidates.size());
    std::vector<std::vector<double>> out;
    for (const auto& c : candidates) out.push_back(recorded_residuals(c));
    return out;
  }
  /// Answers batches of up to `lanes_ahead` points (0: none, the default problem's answer); counts the first.
  [[nodiscard]] std::vector<std::vector<double>> residuals_ahead(std::span<const std::vector<double>> batch) const override {
    if (batch.empty() || batch.size() > lanes_ahead) return {};
    ++rounds;
    ++counted_ahead;
    std::vector<std::vector<double>> out;
    for (const auto& c : batch) out.push_back(recorded_residuals(c));
    return out;
  }
  void count_evaluations(long long n) const override { counted_ahead += n; }
  [[nodiscard]] const Bounds& bounds() const override { return bounds_; }

  mutable std::vector<std::vector<double>> points;
  mutable long long evaluations = 0, residual_calls = 0;
  std::size_t lanes_ahead = 0;
  mutable long long rounds = 0;         ///< sequential evaluation rounds: one per residuals call or batch
  mutable long long counted_ahead = 0;  ///< evaluations of residuals_ahead counted (its first point, and count_evaluations)

 private:
  /// residuals_(x), with x kept in `points`.
  std::vector<double> recorded_residuals(std::span<const double> x) const {
    points.emplace_back(x.begin(), x.end());
    return residuals_(x);
  }
  Residuals residuals_;
  Bounds bounds_;
};

/// Every point the problem evaluated lies inside its box.
inline ::testing::AssertionResult all_points_inside(const FunctionProblem& problem) {
  const Bounds& b = problem.bounds();
  for (const auto& x : problem.points)
    for (int j = 0; j < b.dim(); ++j)
      if (!(x[j] >= b.lower[j] && x[j] <= b.upper[j]))
        return ::testing::AssertionFailure() << "parameter " << j << " = " << x[j] << " outside [" << b.lower[j]
                                             << ", " << b.upper[j] << "]";
  return ::testing::AssertionSuccess();
}

/// A whole run as identify() makes it: the population phase through ask/tell on f, then refine(problem)
/// (a no-op but for the hybrids). The conformance checks below run every optimizer this way.
inline Run minimize_and_refine(Optimizer& opt, const Objective& f, const FunctionProblem& problem,
                               bool keep_history = false) {
  Run run = minimize(opt, f, problem.bounds().dim(), keep_history);
  opt.refine(problem);
  run.best_value = opt.best_value();
  run.best_position.assign(opt.best_position().begin(), opt.best_position().end());
  return run;
}

/// The population phase on the problem's value, then refine(problem).
inline Run minimize_and_refine(Optimizer& opt, const FunctionProblem& problem) {
  return minimize_and_refine(opt, [&](std::span<const double> x) { return problem.value(x); }, problem);
}

/// One seeded run on f over `bounds`, refine seeing f as a FunctionProblem (value f where f >= 0, NaN where
/// f = −inf: the population phase sees f itself).
inline Run minimize_and_refine(const OptimizerFactory& make, const Objective& f, const Bounds& bounds,
                               std::uint64_t seed) {
  const FunctionProblem problem(f, bounds);
  const std::unique_ptr<Optimizer> opt = make(bounds, hash_key({seed}));
  return minimize_and_refine(*opt, f, problem);
}

/// A hybrid (optimizers/hybrid) on a closed-form problem: the GA-phase best, the whole run and the local
/// phase's report.
template <class Hybrid>
struct HybridRun {
  double ga_best = 0;
  Run run;
  std::remove_cvref_t<decltype(std::declval<const Hybrid&>().report())> report;
  bool at_local_optimum = false;  ///< Optimizer::at_local_optimum after refine
};
template <class Hybrid, class Settings>
HybridRun<Hybrid> run_hybrid(const Settings& settings, const FunctionProblem& problem, std::uint64_t seed) {
  Hybrid opt(settings, problem.bounds(), hash_key({seed}));
  HybridRun<Hybrid> h;
  h.ga_best = minimize(opt, [&](std::span<const double> x) { return problem.value(x); }, problem.bounds().dim()).best_value;
  opt.refine(problem);
  h.run.best_value = opt.best_value();
  h.run.best_position.assign(opt.best_position().begin(), opt.best_position().end());
  h.report = opt.report();
  h.at_local_optimum = opt.at_local_optimum();
  return h;
}

/// A hybrid refined beside a failure region (x0 < 0) hands back no failure and nothing worse than its GA best.
template <class Hybrid>
void expect_refine_avoids_failures(const HybridRun<Hybrid>& h) {
  ASSERT_TRUE(std::isfinite(h.ga_best));
  EXPECT_TRUE(std::isfinite(h.run.best_value));
  EXPECT_LE(h.run.best_value, h.ga_best);
  EXPECT_GE(h.run.best_position[0], 0.0);
}

/// Two factories ask the same candidates, bit for bit, and end at the same best (a hybrid's population
/// phase is the GA's).
inline void expect_same_run(const OptimizerFactory& a, const OptimizerFactory& b) {
  const Bounds bounds = box(3, -5, 5);
  const Run x = minimize(a, rastrigin, bounds, 4, true), y = minimize(b, rastrigin, bounds, 4, true);
  ASSERT_FALSE(x.history.empty());
  EXPECT_EQ(x.history, y.history);
  EXPECT_EQ(x.best_value, y.best_value);
}

// ---- success rates --------------------------------------------------------------------------------

/// One success-rate case: `repeats` seeded runs of f in `dim` dimensions; success = best value < target.
struct SuccessCase {
  TestFunction function;
  int dim;
  int population, iterations;
  double target;
  int min_successes;  ///< out of `repeats`
  int repeats = 10;

  [[nodiscard]] std::string name() const { return std::string(function.name) + std::to_string(dim); }
};

/// Runs the case's repeats with seeds first_seed, first_seed + 1, … and reports the success count with every
/// best value, so a failure shows what was reached.
inline ::testing::AssertionResult reaches_target(const SuccessCase& c, const std::function<OptimizerFactory(int, int)>& make,
                                                 std::uint64_t first_seed) {
  const OptimizerFactory factory = make(c.population, c.iterations);
  const Bounds bounds = box(c.dim, c.function.lower, c.function.upper);
  int successes = 0;
  std::ostringstream bests;
  bests.precision(3);
  for (int r = 0; r < c.repeats; ++r) {
    const FunctionProblem problem(c.function, bounds);
    const std::unique_ptr<Optimizer> opt = factory(bounds, hash_key({first_seed + r}));
    const double best = minimize_and_refine(*opt, c.function.f, problem).best_value;
    successes += best < c.target;
    bests << (r ? ", " : "") << best;
  }
  if (successes >= c.min_successes) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << c.name() << ": " << successes << "/" << c.repeats << " runs below "
                                       << c.target << " (need " << c.min_successes << "), seeds from "
                                       << first_seed << "; best values: " << bests.str();
}

/// Retry for stochastic tests: runs trial(attempt) for attempt = 0, 1, … and stops at the first success, but
/// the last allowed attempt is always asserted, so a trial that keeps failing fails the test (a retry
/// loop whose guard swallows the last failure can never fail). Each attempt should use
/// different seeds. Returns the number of attempts used.
template <class Trial>
int retry(int max_attempts, Trial&& trial) {
  for (int attempt = 0; attempt + 1 < max_attempts; ++attempt)
    if (trial(attempt)) return attempt + 1;
  EXPECT_TRUE(trial(max_attempts - 1)) << "(last of " << max_attempts << " attempts)";
  return max_attempts;
}

/// A success-rate check with up to `max_attempts` disjoint seed blocks (attempt a uses seeds 1000·a + 1 …).
inline void expect_success_rate(const SuccessCase& c, const std::function<OptimizerFactory(int, int)>& make,
                                int max_attempts = 2) {
  retry(max_attempts, [&](int attempt) { return reaches_target(c, make, 1000 * static_cast<std::uint64_t>(attempt) + 1); });
}

// ---- conformance checks every optimizer must pass ------------------------------------------------------

/// Same key ⇒ the same candidates asked, bit for bit; another key ⇒ other candidates.
inline void expect_keyed_history(const OptimizerFactory& make) {
  const Bounds b = box(4, kRastrigin.lower, kRastrigin.upper);
  const Run a = minimize(make, rastrigin, b, 9, true), again = minimize(make, rastrigin, b, 9, true),
            other = minimize(make, rastrigin, b, 10, true);
  ASSERT_FALSE(a.history.empty());
  EXPECT_EQ(a.history, again.history);
  EXPECT_EQ(a.best_value, again.best_value);
  EXPECT_NE(a.history, other.history);
}

/// Two runs asked into one batch at different offsets and told their slices (the lockstep of
/// engine/identification/identification.cpp) ask exactly what each asks when run alone.
inline void expect_lockstep_equals_alone(const OptimizerFactory& make) {
  const int dim = 3;
  const Bounds b = box(dim, kSphere.lower, kSphere.upper);
  const std::uint64_t keys[2] = {hash_key({21}), hash_key({22})};
  std::vector<double> alone[2];
  for (int r = 0; r < 2; ++r) {
    const auto opt = make(b, keys[r]);
    alone[r] = minimize(*opt, sphere, dim, true).history;
  }
  std::unique_ptr<Optimizer> runs[2] = {make(b, keys[0]), make(b, keys[1])};
  std::vector<double> together[2], x(dim);
  const int n0 = runs[0]->batch_size(), n1 = runs[1]->batch_size();
  CandidateBatch batch(dim, n0 + n1);
  std::vector<double> values(n0 + n1);
  while (!runs[0]->finished()) {
    runs[1]->ask(batch, 0);  // the second run sits first in the batch
    runs[0]->ask(batch, n1);
    for (int i = 0; i < n0 + n1; ++i) {
      for (int j = 0; j < dim; ++j) x[j] = batch.at(i, j);
      values[i] = sphere(x);
      std::vector<double>& h = together[i < n1 ? 1 : 0];
      h.insert(h.end(), x.begin(), x.end());
    }
    runs[1]->tell(std::span<const double>(values.data(), n1));
    runs[0]->tell(std::span<const double>(values.data() + n1, n0));
  }
  EXPECT_TRUE(runs[1]->finished());
  EXPECT_EQ(together[0], alone[0]);
  EXPECT_EQ(together[1], alone[1]);
}

/// Every asked candidate, and every point refine evaluates, inside the box (including a parameter with
/// lower == upper) while the optimum of the sphere lies outside it: the best ends near the nearest corner
/// (1, −2.5, 0.5), value 7.5.
inline void expect_stays_inside_bounds(const OptimizerFactory& make, double value_tolerance) {
  const Bounds b{{1.0, -3.0, 0.5}, {2.0, -2.5, 0.5}};
  const FunctionProblem problem(sphere, b);
  const auto opt = make(b, 77);
  const Run run = minimize_and_refine(*opt, sphere, problem, true);
  for (std::size_t k = 0; k < run.history.size(); ++k) {
    const std::size_t j = k % 3;
    ASSERT_GE(run.history[k], b.lower[j]) << "parameter " << j;
    ASSERT_LE(run.history[k], b.upper[j]) << "parameter " << j;
  }
  EXPECT_TRUE(all_points_inside(problem)) << "refine";
  EXPECT_GE(run.best_value, 7.5);
  EXPECT_LT(run.best_value, 7.5 + value_tolerance) << "best − 7.5 = " << run.best_value - 7.5;
  EXPECT_EQ(run.best_position[2], 0.5);
}

/// A run costs batch_size × iterations evaluations in `iterations` asks of a constant size.
inline void expect_budget(const OptimizerFactory& make, int population, int iterations) {
  const Bounds b = box(2, -1, 1);
  const auto opt = make(b, 3);
  int asks = 0;
  long long evaluations = 0;
  CandidateBatch batch(2, population);
  std::vector<double> values(population, 1.0);
  while (!opt->finished()) {
    ASSERT_EQ(opt->batch_size(), population);
    opt->ask(batch, 0);
    opt->tell(values);
    evaluations += population;
    ++asks;
  }
  EXPECT_EQ(asks, iterations);
  EXPECT_EQ(evaluations, static_cast<long long>(population) * iterations);
}

/// Failed candidates: `failure` (+inf, NaN or −inf) on the half x0 < 0 of [−5, 5]^3; the shifted sphere
/// Σ (x − 1)² elsewhere. The run, refine included, must converge in the valid half (best < target) and
/// never report a failure as its best.
inline void expect_converges_beside_failures(const OptimizerFactory& make, double failure, double target) {
  const auto f = [failure](std::span<const double> x) {
    if (x[0] < 0) return failure;
    double s = 0;
    for (double v : x) s += (v - 1) * (v - 1);
    return s;
  };
  const Run run = minimize_and_refine(make, f, box(3, -5, 5), 5);
  EXPECT_TRUE(std::isfinite(run.best_value));
  EXPECT_LT(run.best_value, target);
  EXPECT_GE(run.best_position[0], 0.0);
}

/// A run stopped before its first tell (engine budgets stop runs between generations) still reports a best
/// position of the right size inside the box, with value +inf.
inline void expect_best_position_before_first_tell(const OptimizerFactory& make) {
  const Bounds b{{1.0, -3.0}, {2.0, -2.5}};  // the origin is outside
  const auto opt = make(b, 6);
  EXPECT_EQ(opt->best_value(), std::numeric_limits<double>::infinity());
  ASSERT_EQ(opt->best_position().size(), 2u);
  for (int j = 0; j < 2; ++j) {
    EXPECT_GE(opt->best_position()[j], b.lower[j]);
    EXPECT_LE(opt->best_position()[j], b.upper[j]);
  }
}

/// Every candidate fails (+inf, then NaN): the run still ends, its best value is +inf, its best position is
/// in the box, and refine has nothing to refine (it evaluates nothing).
inline void expect_survives_all_failures(const OptimizerFactory& make) {
  const Bounds b = box(2, -1, 1);
  for (const double failure : {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    SCOPED_TRACE(::testing::Message() << "every value " << failure);
    const Objective fail = [failure](std::span<const double>) { return failure; };
    const FunctionProblem problem(fail, b);
    const auto opt = make(b, hash_key({4}));
    const Run run = minimize_and_refine(*opt, fail, problem, true);
    EXPECT_EQ(run.best_value, std::numeric_limits<double>::infinity());
    for (double v : run.history) {
      ASSERT_TRUE(std::isfinite(v));
      ASSERT_GE(v, -1.0);
      ASSERT_LE(v, 1.0);
    }
    ASSERT_EQ(run.best_position.size(), 2u);
    for (double v : run.best_position) EXPECT_TRUE(v >= -1 && v <= 1);
    EXPECT_TRUE(problem.points.empty()) << "refine evaluated " << problem.points.size() << " points";
  }
}

// ---- identification on a model: thread counts, batch splits, one by one ----------------------------

/// A LocalProblem on a model through a BatchEvaluator, with residuals as engine/identification/identification.cpp builds
/// them. `one_by_one` evaluates every candidate of a batch as its own batch of one.
class ModelProblem final : public LocalProblem {
 public:
  ModelProblem(const BatchEvaluator& evaluator, Metric metric, Bounds bounds, bool one_by_one)
      : evaluator_(evaluator), metric_(metric), bounds_(std::move(bounds)), one_by_one_(one_by_one) {}
  void evaluate(const CandidateBatch& batch, std::span<double> values) const override {
    if (!one_by_one_) {
      evaluator_.evaluate(batch, metric_, values);
      return;
    }
    CandidateBatch one(batch.dim(), 1);
    for (int i = 0; i < batch.count(); ++i) {
      one.set_candidate(0, batch.candidate(i));
      evaluator_.evaluate(one, metric_, values.subspan(i, 1));
    }
  }
  [[nodiscard]] std::vector<double> residuals(std::span<const double> params) const override {
    return scaled_residuals(evaluator_.model(), evaluator_.datasets(), params);
  }
  [[nodiscard]] const Bounds& bounds() const override { return bounds_; }

 private:
  const BatchEvaluator& evaluator_;
  Metric metric_;
  Bounds bounds_;
  bool one_by_one_;
};

/// One run of an optimizer on a model: population phase and refine, every batch evaluated as one batch or
/// candidate by candidate. Returns the best position followed by the best value.
inline std::vector<double> run_on_model(const OptimizerFactory& make, const BatchEvaluator& evaluator, Metric metric,
                                        const Bounds& bounds, std::uint64_t key, bool one_by_one) {
  const auto opt = make(bounds, key);
  const ModelProblem problem(evaluator, metric, bounds, one_by_one);
  CandidateBatch batch;
  std::vector<double> values;
  while (!opt->finished()) {
    const int n = opt->batch_size();
    if (batch.count() != n) batch.resize(bounds.dim(), n);
    values.resize(n);
    opt->ask(batch, 0);
    problem.evaluate(batch, values);
    opt->tell(values);
  }
  opt->refine(problem);
  std::vector<double> out(opt->best_position().begin(), opt->best_position().end());
  out.push_back(opt->best_value());
  return out;
}

/// Settings of `runs` identification runs from `seed`, on the nrmse.
inline IdentificationSettings nrmse_runs(int runs, std::uint64_t seed) {
  IdentificationSettings s;
  s.runs = runs;
  s.seed = seed;
  s.metric = Metric::nrmse;
  return s;
}

/// identify() with `threads` worker threads and `grain` lane blocks per task.
inline Identification identify_with(const Model& model, const std::vector<const Signals*>& data, const Bounds& bounds,
                                    const OptimizerFactory& make, IdentificationSettings settings, int threads, int grain) {
  settings.grain_blocks = grain;
  tbb::task_arena arena(threads);
  Identification out;
  arena.execute([&] { out = identify(model, data, bounds, make, settings); });
  return out;
}

/// Two identifications agree bit for bit: parameters, values, every metric, traces and evaluation counts.
inline void expect_identical(const Identification& a, const Identification& b) {
  ASSERT_EQ(a.runs.size(), b.runs.size());
  for (std::size_t r = 0; r < a.runs.size(); ++r) {
    EXPECT_EQ(a.runs[r].best_params, b.runs[r].best_params) << "run " << r;
    EXPECT_EQ(a.runs[r].best_value, b.runs[r].best_value) << "run " << r;
    EXPECT_EQ(a.runs[r].best_metrics, b.runs[r].best_metrics) << "run " << r;
    EXPECT_EQ(a.runs[r].trace, b.runs[r].trace) << "run " << r;
    EXPECT_EQ(a.runs[r].evaluations, b.runs[r].evaluations) << "run " << r;
  }
}

/// identify() of a model gives the same bits with 1 and 2 threads and with another grain (3 runs in one
/// lockstep batch), another seed gives other runs, every run costs at least `min_evaluations`, and a run
/// whose batches (refine's included) are evaluated candidate by candidate ends with the same bits.
inline void expect_reproducible_identification(const OptimizerFactory& make, const Model& model, const Signals& data,
                                               const Bounds& bounds, long long min_evaluations) {
  IdentificationSettings s = nrmse_runs(3, 8);
  const std::vector<const Signals*> datasets{&data};
  const Identification one = identify_with(model, datasets, bounds, make, s, 1, 1);
  expect_identical(one, identify_with(model, datasets, bounds, make, s, 2, 1));
  expect_identical(one, identify_with(model, datasets, bounds, make, s, 2, 3));
  for (const RunResult& r : one.runs) EXPECT_GE(r.evaluations, min_evaluations);
  s.seed = 9;
  EXPECT_NE(one.runs[0].best_params, identify_with(model, datasets, bounds, make, s, 2, 1).runs[0].best_params);

  const BatchEvaluator evaluator(model, data);
  EXPECT_EQ(run_on_model(make, evaluator, s.metric, bounds, 4, false), run_on_model(make, evaluator, s.metric, bounds, 4, true));
}

}  // namespace dampbench::testing
