#include "optimizers/ga/genetic.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench {

void GeneticSettings::validate(std::string_view algorithm) const {
  if (population < 4)
    throw InputError(fmt::format("{}: population must be at least 4, got {}", algorithm, population));
  if (generations < 1)
    throw InputError(fmt::format("{}: iterations (generations) must be at least 1, got {}", algorithm, generations));
  check_ranges(algorithm, genetic_setting_table(), *this);  // then the limits that depend on the population
  if (tournament < 2 || tournament > population)
    throw InputError(fmt::format("{}: tournament must be in [2, population = {}], got {}", algorithm, population,
                                 tournament));
  if (elite_count() < 0 || elite_count() > population / 2)
    throw InputError(fmt::format("{}: elites must be in [0, population / 2 = {}], got {}", algorithm, population / 2,
                                 elite_count()));
}

const SettingTable<GeneticSettings>& genetic_setting_table() {
  static const SettingTable<GeneticSettings> table{
      {"eta_c", &GeneticSettings::eta_c, kNonNegative, "SBX distribution index: larger keeps children nearer their parents"},
      {"eta_m", &GeneticSettings::eta_m, kNonNegative, "polynomial mutation distribution index"},
      {"tournament", &GeneticSettings::tournament, whole_at_least(2), "tournament size, at most the population"},
      {"elites", &GeneticSettings::elites, whole_at_least(0),
       "best parents kept over the worst offspring each generation, at most half the population",
       "⌈share × N⌉, at least 1 (ga's share 0.1, aga's 0)"},
  };
  return table;
}

GeneticAlgorithm::GeneticAlgorithm(const GeneticSettings& settings, const Bounds& bounds, std::uint64_t run_key)
    : PopulationOptimizer(settings.population, settings.generations, bounds, run_key), settings_(settings) {
  population_.resize(population_.size() + static_cast<std::size_t>(dim_));  // row N (genetic.hpp)
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

  // Every draw of the generation first, as vector loops; then selection and what to cross and mutate; then the
  // crossed variables' and mutated genes' values, one vector loop each (optimizers/ga/operators.hpp).
  const int pairs = (n + 1) / 2;
  const auto genes = static_cast<std::size_t>(dim_);
  const int t = settings_.tournament;
  draws_.draw(hash_key({run_key_, g}), pairs, n, 2 * t, 1 + 3 * dim_, 2 * dim_);
  pair_pm_.resize(static_cast<std::size_t>(pairs));
  crossed_.clear(static_cast<std::size_t>(pairs) * genes);
  for (int k = 0; k < pairs; ++k) {
    const std::span<const double> select = draws_.select(k);
    const int a = genetic::tournament(values_, select.first(static_cast<std::size_t>(t)));
    const int b = genetic::tournament(values_, select.subspan(static_cast<std::size_t>(t)));
    const PairRates r = rates(values_[a], values_[b], stats);
    pair_pm_[static_cast<std::size_t>(k)] = r.pm;
    // Children 2k and 2k + 1 (row N when N is odd and 2k + 1 = N): copies of the parents, some variables crossed.
    const std::span<const double> crossover = draws_.crossover(k);
    if (crossover[0] < r.pc) {
      genetic::sbx_draw(member(population_, a), member(population_, b), offspring_, 2 * k * genes,
                        (2 * k + 1) * genes, bounds_.lower, bounds_.upper, crossover.subspan(1), crossed_);
    } else {
      std::ranges::copy(member(population_, a), member(offspring_, 2 * k).begin());
      std::ranges::copy(member(population_, b), member(offspring_, 2 * k + 1).begin());
    }
  }
  genetic::sbx_finish(crossed_, settings_.eta_c, offspring_);

  mutated_.clear(static_cast<std::size_t>(n) * genes);
  for (int c = 0; c < n; ++c) {
    const double rate = pair_pm_[static_cast<std::size_t>(c / 2)][static_cast<std::size_t>(c % 2)];
    genetic::mutation_draw(c * genes, rate, bounds_.lower, bounds_.upper, draws_.mutate(c), mutated_);
  }
  genetic::mutate_all(mutated_, settings_.eta_m, offspring_);
}

void GeneticAlgorithm::tell(std::span<const double> values) {
  const int n = settings_.population;
  assert(static_cast<int>(values.size()) == n);
  std::vector<double>& evaluated = generation_ == 0 ? population_ : offspring_;
  std::vector<double>& told = told_;
  told.resize(static_cast<std::size_t>(n));
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
    const int elites = settings_.elite_count();
    const auto parent_better = [&](int i, int j) { return values_[i] < values_[j] || (values_[i] == values_[j] && i < j); };
    const auto offspring_worse = [&](int i, int j) { return told[j] < told[i] || (told[i] == told[j] && j < i); };
    genetic::first_in_order(n, elites, parent_better, best_parents_);
    genetic::first_in_order(n, elites, offspring_worse, worst_offspring_);
    for (int e = 0; e < elites; ++e) {
      const int p = best_parents_[e], o = worst_offspring_[e];
      if (values_[p] < told[o]) {
        std::ranges::copy(member(population_, p), member(offspring_, o).begin());
        told[o] = values_[p];
      }
    }
    population_.swap(offspring_);
  }
  values_.swap(told);  // told_ keeps the old values' storage for the next generation
  ++generation_;
}

}  // namespace dampbench
