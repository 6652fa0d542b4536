#include "optimizers/ga/genetic.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numeric>

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench {
namespace {

constexpr std::uint64_t kSelect = hash_name("select");
constexpr std::uint64_t kCrossover = hash_name("crossover");
constexpr std::uint64_t kMutate = hash_name("mutate");

}  // namespace

void GeneticSettings::validate(std::string_view algorithm) const {
  if (population < 4)
    throw InputError(fmt::format("{}: population must be at least 4, got {}", algorithm, population));
  if (generations < 1)
    throw InputError(fmt::format("{}: iterations (generations) must be at least 1, got {}", algorithm, generations));
  if (tournament < 2 || tournament > population)
    throw InputError(fmt::format("{}: tournament must be in [2, population = {}], got {}", algorithm, population,
                                 tournament));
  if (elite_count() < 0 || elite_count() > population / 2)
    throw InputError(fmt::format("{}: elites must be in [0, population / 2 = {}], got {}", algorithm, population / 2,
                                 elite_count()));
  if (!(eta_c >= 0) || !std::isfinite(eta_c))
    throw InputError(fmt::format("{}: eta_c must be a finite number >= 0, got {}", algorithm, eta_c));
  if (!(eta_m >= 0) || !std::isfinite(eta_m))
    throw InputError(fmt::format("{}: eta_m must be a finite number >= 0, got {}", algorithm, eta_m));
}

namespace genetic {

int tournament(std::span<const double> values, int size, RandomStream& rng) {
  const int n = static_cast<int>(values.size());
  int winner = n;
  for (int e = 0; e < size; ++e) {
    const int i = std::min(static_cast<int>(rng.uniform() * n), n - 1);
    if (winner == n || values[i] < values[winner] || (values[i] == values[winner] && i < winner)) winner = i;
  }
  return winner;
}

void sbx(std::span<const double> parent_a, std::span<const double> parent_b, std::span<double> child_a,
         std::span<double> child_b, const std::vector<double>& lower, const std::vector<double>& upper,
         double eta_c, RandomStream& rng) {
  const double exponent = 1.0 / (eta_c + 1.0);
  // Spread factor for a uniform draw u, given how far the parents sit from the bound on their side.
  const auto beta_q = [&](double u, double distance_to_bound, double gap) {
    const double beta = 1.0 + 2.0 * distance_to_bound / gap;
    const double alpha = 2.0 - std::pow(beta, -(eta_c + 1.0));
    return u <= 1.0 / alpha ? std::pow(u * alpha, exponent) : std::pow(1.0 / (2.0 - u * alpha), exponent);
  };
  for (std::size_t j = 0; j < parent_a.size(); ++j) {
    const double a = parent_a[j], b = parent_b[j];
    child_a[j] = a;
    child_b[j] = b;
    if (rng.uniform() >= 0.5) continue;  // this variable is inherited unchanged
    const double y1 = std::min(a, b), y2 = std::max(a, b), gap = y2 - y1;
    if (!(gap > 1e-14)) continue;  // identical parents: nothing to spread
    const double lo = lower[j], hi = upper[j];
    const double u = rng.uniform();
    const double c1 = std::clamp(0.5 * ((y1 + y2) - beta_q(u, y1 - lo, gap) * gap), lo, hi);
    const double c2 = std::clamp(0.5 * ((y1 + y2) + beta_q(u, hi - y2, gap) * gap), lo, hi);
    const bool swap = rng.uniform() < 0.5;
    child_a[j] = swap ? c2 : c1;
    child_b[j] = swap ? c1 : c2;
  }
}

double polynomial_mutation(double x, double lower, double upper, double eta_m, RandomStream& rng) {
  const double range = upper - lower;
  const double u = rng.uniform();
  if (!(range > 0)) return x;
  const double exponent = 1.0 / (eta_m + 1.0);
  double delta_q;
  if (u < 0.5) {
    const double xy = 1.0 - (x - lower) / range;
    const double val = 2.0 * u + (1.0 - 2.0 * u) * std::pow(xy, eta_m + 1.0);
    delta_q = std::pow(val, exponent) - 1.0;
  } else {
    const double xy = 1.0 - (upper - x) / range;
    const double val = 2.0 * (1.0 - u) + 2.0 * (u - 0.5) * std::pow(xy, eta_m + 1.0);
    delta_q = 1.0 - std::pow(val, exponent);
  }
  return std::clamp(x + delta_q * range, lower, upper);
}

}  // namespace genetic

GeneticAlgorithm::GeneticAlgorithm(const GeneticSettings& settings, const Bounds& bounds, std::uint64_t run_key)
    : PopulationOptimizer(settings.population, settings.generations, bounds, run_key), settings_(settings) {
  offspring_.resize(population_.size());
  values_.assign(settings_.population, std::numeric_limits<double>::infinity());
}

void GeneticAlgorithm::ask(CandidateBatch& batch, int first) {
  if (generation_ > 0) breed();
  std::vector<double>& pool = generation_ == 0 ? population_ : offspring_;
  for (int i = 0; i < settings_.population; ++i) {
    const std::span<double> x = member(pool, i);
    for (int j = 0; j < dim_; ++j) batch.at(first + i, j) = x[j];
  }
}

void GeneticAlgorithm::breed() {
  const int n = settings_.population;
  const auto g = static_cast<std::uint64_t>(generation_);
  PopulationStats stats{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double sum = 0;
  int finite = 0;
  for (double v : values_) {
    stats.best = std::min(stats.best, v);
    if (std::isfinite(v)) {
      sum += v;
      ++finite;
    }
  }
  if (finite > 0) stats.mean_finite = sum / finite;

  std::vector<double> spare(dim_);  // the unused second child of the last pair when N is odd
  const std::uint64_t generation_key = hash_key({run_key_, g});
  for (int k = 0; k < (n + 1) / 2; ++k) {
    const std::uint64_t pair_key = extend_key(generation_key, static_cast<std::uint64_t>(k));  // (run, g, pair)
    RandomStream select(extend_key(pair_key, kSelect));
    const int a = genetic::tournament(values_, settings_.tournament, select);
    const int b = genetic::tournament(values_, settings_.tournament, select);
    const PairRates r = rates(values_[a], values_[b], stats);

    const std::array<int, 2> child{2 * k, 2 * k + 1};
    const std::span<double> child_a = member(offspring_, child[0]);
    const std::span<double> child_b = child[1] < n ? member(offspring_, child[1]) : std::span<double>(spare);
    RandomStream crossover(extend_key(pair_key, kCrossover));
    if (crossover.uniform() < r.pc) {
      genetic::sbx(member(population_, a), member(population_, b), child_a, child_b, bounds_.lower, bounds_.upper,
                   settings_.eta_c, crossover);
    } else {
      std::ranges::copy(member(population_, a), child_a.begin());
      std::ranges::copy(member(population_, b), child_b.begin());
    }
    for (int c = 0; c < 2 && child[c] < n; ++c) {
      RandomStream mutate(extend_key(extend_key(generation_key, static_cast<std::uint64_t>(child[c])), kMutate));
      const std::span<double> x = c == 0 ? child_a : child_b;
      for (int j = 0; j < dim_; ++j)
        if (mutate.uniform() < r.pm[c])
          x[j] = genetic::polynomial_mutation(x[j], bounds_.lower[j], bounds_.upper[j], settings_.eta_m, mutate);
    }
  }
}

void GeneticAlgorithm::tell(std::span<const double> values) {
  const int n = settings_.population;
  assert(static_cast<int>(values.size()) == n);
  std::vector<double>& evaluated = generation_ == 0 ? population_ : offspring_;
  std::vector<double> told(n);
  for (int i = 0; i < n; ++i) {
    told[i] = failure_as_inf(values[i]);
    if (told[i] < best_value_) {
      best_value_ = told[i];
      const std::span<double> x = member(evaluated, i);
      std::ranges::copy(x, best_position_.begin());
    }
  }
  if (generation_ > 0) {
    // Elitism: the e best parents against the e worst offspring (ties: lower index counts as better).
    std::vector<int> parents(n), offspring(n);
    std::iota(parents.begin(), parents.end(), 0);
    std::iota(offspring.begin(), offspring.end(), 0);
    const auto better = [](const std::vector<double>& v) {
      return [&v](int i, int j) { return v[i] < v[j] || (v[i] == v[j] && i < j); };
    };
    // Only the e best parents and the e worst offspring are needed: partial sorts (the order is total, so they
    // give what full sorts give).
    const int elites = settings_.elite_count();
    const auto worse = [](const std::vector<double>& v) {
      return [&v](int i, int j) { return v[j] < v[i] || (v[i] == v[j] && j < i); };
    };
    std::ranges::partial_sort(parents, parents.begin() + elites, better(values_));
    std::ranges::partial_sort(offspring, offspring.begin() + elites, worse(told));
    for (int e = 0; e < elites; ++e) {
      const int p = parents[e], o = offspring[e];
      if (values_[p] < told[o]) {
        std::ranges::copy(member(population_, p), member(offspring_, o).begin());
        told[o] = values_[p];
      }
    }
    population_.swap(offspring_);
  }
  values_ = std::move(told);
  ++generation_;
}

}  // namespace dampbench
