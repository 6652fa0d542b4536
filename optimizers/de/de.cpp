#include "optimizers/de/de.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/random.hpp"

namespace dampbench {

DeStrategy parse_de_strategy(std::string_view name) {
  if (name == "rand1bin") return DeStrategy::rand1bin;
  if (name == "best1bin") return DeStrategy::best1bin;
  if (name == "currenttobest1bin") return DeStrategy::currenttobest1bin;
  throw InputError(
      fmt::format("de: unknown strategy '{}' (known: rand1bin, best1bin, currenttobest1bin)", name));
}

std::string_view de_strategy_name(DeStrategy strategy) {
  switch (strategy) {
    case DeStrategy::rand1bin: return "rand1bin";
    case DeStrategy::best1bin: return "best1bin";
    case DeStrategy::currenttobest1bin: return "currenttobest1bin";
  }
  return "?";
}

void DeSettings::validate() const {
  if (population < 4) throw InputError(fmt::format("de: population must be at least 4, got {}", population));
  if (generations < 1)
    throw InputError(fmt::format("de: iterations (generations) must be at least 1, got {}", generations));
  check_ranges("de", de_setting_table(), *this);
}

const SettingTable<DeSettings>& de_setting_table() {
  static const SettingTable<DeSettings> table{
      {"F", &DeSettings::F, {0, 2, true}, "differential weight"},
      {"CR", &DeSettings::CR, kProbability, "crossover rate"},
  };
  return table;
}

De::De(const DeSettings& settings, const Bounds& bounds, std::uint64_t run_key)
    : PopulationOptimizer(validated(settings).population, settings.generations, bounds, run_key),
      settings_(settings) {
  trials_.resize(population_.size());
  values_.assign(settings_.population, std::numeric_limits<double>::infinity());
}

void De::ask(CandidateBatch& batch, int first) {
  if (generation_ > 0) make_trials();
  const std::vector<double>& pool = generation_ == 0 ? population_ : trials_;
  for (int i = 0; i < settings_.population; ++i)
    for (int j = 0; j < dim_; ++j) batch.at(first + i, j) = pool[static_cast<std::size_t>(i) * dim_ + j];
}

void De::make_trials() {
  const int n = settings_.population;
  const double F = settings_.F;
  int best = 0;  // lowest value, ties to the lowest index
  for (int i = 1; i < n; ++i)
    if (values_[i] < values_[best]) best = i;
  const std::uint64_t generation_key = hash_key({run_key_, static_cast<std::uint64_t>(generation_)});
  for (int i = 0; i < n; ++i) {
    RandomStream rng(extend_key(generation_key, static_cast<std::uint64_t>(i)));  // (run, generation, i)
    const auto draw_index = [&] { return std::min(static_cast<int>(rng.uniform() * n), n - 1); };
    int r1, r2, r3;
    do r1 = draw_index(); while (r1 == i);
    do r2 = draw_index(); while (r2 == i || r2 == r1);
    do r3 = draw_index(); while (r3 == i || r3 == r1 || r3 == r2);
    const int j_rand = std::min(static_cast<int>(rng.uniform() * dim_), dim_ - 1);
    for (int j = 0; j < dim_; ++j) {
      const bool from_mutant = rng.uniform() < settings_.CR || j == j_rand;
      if (!from_mutant) {
        u(i, j) = x(i, j);
        continue;
      }
      double v = 0;
      switch (settings_.strategy) {
        case DeStrategy::rand1bin: v = x(r1, j) + F * (x(r2, j) - x(r3, j)); break;
        case DeStrategy::best1bin: v = x(best, j) + F * (x(r1, j) - x(r2, j)); break;
        case DeStrategy::currenttobest1bin:
          v = x(i, j) + F * (x(best, j) - x(i, j)) + F * (x(r1, j) - x(r2, j));
          break;
      }
      const double lo = bounds_.lower[j], hi = bounds_.upper[j];
      if (v < lo) v = 0.5 * (x(i, j) + lo);
      if (v > hi) v = 0.5 * (x(i, j) + hi);
      u(i, j) = v;
    }
  }
}

void De::tell(std::span<const double> values) {
  const int n = settings_.population;
  assert(static_cast<int>(values.size()) == n);
  const bool initial = generation_ == 0;
  for (int i = 0; i < n; ++i) {
    const double v = std::isfinite(values[i]) ? values[i] : std::numeric_limits<double>::infinity();
    const double* evaluated = (initial ? population_ : trials_).data() + static_cast<std::size_t>(i) * dim_;
    if (v < best_value_) {
      best_value_ = v;
      std::copy_n(evaluated, dim_, best_position_.begin());
    }
    if (initial) {
      values_[i] = v;
    } else if (v <= values_[i]) {  // Storn & Price: the trial replaces its target when no worse
      std::copy_n(evaluated, dim_, population_.begin() + static_cast<std::ptrdiff_t>(i) * dim_);
      values_[i] = v;
    }
  }
  ++generation_;
}

}  // namespace dampbench
