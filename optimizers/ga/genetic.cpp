#include "optimizers/ga/genetic.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/vector_math.hpp"
#include "engine/kernels/isa.hpp"

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
  // Which entrant wins is a coin toss to a branch predictor: the winner is chosen with selects, not branches.
  const int n = static_cast<int>(values.size());
  const auto entrant = [&] { return std::min(static_cast<int>(rng.uniform() * n), n - 1); };
  int winner = entrant();
  for (int e = 1; e < size; ++e) {
    const int i = entrant();
    const double vi = values[i], vw = values[winner];
    const bool wins = (vi < vw) | ((vi == vw) & (i < winner));
    winner = wins ? i : winner;
  }
  return winner;
}

namespace {

/// pow_each's loop, compiled per vector level (IsaClones): blocks of kBlock elements with a constant trip count,
/// so that every element goes through the vector pow of the level (no scalar remainder loop).
struct PowBlocks {
  static constexpr int kBlock = 16;
  static void run(double* x, std::size_t blocks, double exponent) {
    for (std::size_t b = 0; b < blocks; ++b) {
      double* v = x + b * kBlock;
#pragma omp simd
      for (int l = 0; l < kBlock; ++l) v[l] = std::pow(v[l], exponent);
    }
  }
};

}  // namespace

void pow_each(std::span<double> x, double exponent) {
  constexpr std::size_t kBlock = PowBlocks::kBlock;
  const std::size_t whole = x.size() / kBlock;
  if (whole > 0) IsaClones<PowBlocks>::call(x.data(), whole, exponent);
  const std::size_t rest = x.size() - whole * kBlock;
  if (rest == 0) return;
  alignas(64) double tail[kBlock];
  std::fill(std::begin(tail), std::end(tail), 1.0);
  std::copy(x.end() - static_cast<std::ptrdiff_t>(rest), x.end(), tail);
  IsaClones<PowBlocks>::call(&tail[0], std::size_t{1}, exponent);
  std::copy(tail, tail + rest, x.end() - static_cast<std::ptrdiff_t>(rest));
}

std::size_t sbx_draw(std::span<const double> parent_a, std::span<const double> parent_b, std::span<double> child_a,
                     std::span<double> child_b, const std::vector<double>& lower, const std::vector<double>& upper,
                     RandomStream& rng, std::span<SbxGene> crossed) {
  // Variable j is crossed when its first draw is below 1/2 and its parents differ (identical parents: nothing to
  // spread); its next two draws are then u and the swap. All three are computed and the variable is kept or
  // not without a branch on the draws, which no branch predictor guesses; the draws consumed are the same.
  std::size_t count = 0;
  for (std::size_t j = 0; j < parent_a.size(); ++j) {
    const double a = parent_a[j], b = parent_b[j];
    child_a[j] = a;
    child_b[j] = b;
    const double y1 = std::min(a, b), y2 = std::max(a, b);
    const bool picked = rng.peek_uniform(0) < 0.5;
    const bool crosses = picked && y2 - y1 > 1e-14;
    crossed[count] = {child_a.data(), child_b.data(), static_cast<int>(j), y1, y2, lower[j], upper[j],
                      rng.peek_uniform(1), rng.peek_uniform(2) < 0.5};
    count += crosses ? 1 : 0;
    rng.skip(crosses ? 3 : 1);
  }
  return count;
}

void sbx_finish(std::span<const SbxGene> crossed, double eta_c, std::vector<double>& scratch) {
  // Spread factor for a uniform draw u, given how far the parents sit from the bound on their side (beta):
  // alpha = 2 − beta^−(η_c + 1); beta_q = (u·alpha)^(1/(η_c + 1)) if u ≤ 1/alpha, else (1/(2 − u·alpha))^(1/(η_c + 1)).
  // Lower child at 2k, upper at 2k + 1.
  const std::size_t n = crossed.size();
  scratch.resize(2 * n);
  for (std::size_t k = 0; k < n; ++k) {
    const SbxGene& g = crossed[k];
    const double gap = g.y2 - g.y1;
    scratch[2 * k] = 1.0 + 2.0 * (g.y1 - g.lower) / gap;
    scratch[2 * k + 1] = 1.0 + 2.0 * (g.upper - g.y2) / gap;
  }
  pow_each(scratch, -(eta_c + 1.0));
  for (std::size_t i = 0; i < 2 * n; ++i) {
    const double alpha = 2.0 - scratch[i], u = crossed[i / 2].u;
    scratch[i] = u <= 1.0 / alpha ? u * alpha : 1.0 / (2.0 - u * alpha);
  }
  pow_each(scratch, 1.0 / (eta_c + 1.0));
  for (std::size_t k = 0; k < n; ++k) {
    const SbxGene& g = crossed[k];
    const double gap = g.y2 - g.y1;
    const double c1 = std::clamp(0.5 * ((g.y1 + g.y2) - scratch[2 * k] * gap), g.lower, g.upper);
    const double c2 = std::clamp(0.5 * ((g.y1 + g.y2) + scratch[2 * k + 1] * gap), g.lower, g.upper);
    g.child_a[g.j] = g.swap ? c2 : c1;
    g.child_b[g.j] = g.swap ? c1 : c2;
  }
}

void sbx(std::span<const double> parent_a, std::span<const double> parent_b, std::span<double> child_a,
         std::span<double> child_b, const std::vector<double>& lower, const std::vector<double>& upper,
         double eta_c, RandomStream& rng) {
  std::vector<SbxGene> crossed(parent_a.size());
  std::vector<double> scratch;
  const std::size_t count = sbx_draw(parent_a, parent_b, child_a, child_b, lower, upper, rng, crossed);
  sbx_finish(std::span(crossed).first(count), eta_c, scratch);
}

void mutate_all(std::span<const MutationGene> genes, double eta_m, std::vector<double>& scratch) {
  // δ_q = (2u + (1 − 2u)·xy^(η_m + 1))^(1/(η_m + 1)) − 1 with xy = 1 − (x − lower)/range for u < 1/2, and
  // 1 − (2(1 − u) + 2(u − 1/2)·xy^(η_m + 1))^(1/(η_m + 1)) with xy = 1 − (upper − x)/range otherwise.
  const std::size_t n = genes.size();
  scratch.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const MutationGene& g = genes[i];
    const double range = g.upper - g.lower;
    scratch[i] = range > 0 ? 1.0 - (g.u < 0.5 ? *g.x - g.lower : g.upper - *g.x) / range : 1.0;
  }
  pow_each(scratch, eta_m + 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double u = genes[i].u;
    scratch[i] = u < 0.5 ? 2.0 * u + (1.0 - 2.0 * u) * scratch[i] : 2.0 * (1.0 - u) + 2.0 * (u - 0.5) * scratch[i];
  }
  pow_each(scratch, 1.0 / (eta_m + 1.0));
  for (std::size_t i = 0; i < n; ++i) {
    const MutationGene& g = genes[i];
    const double range = g.upper - g.lower;
    if (!(range > 0)) continue;  // a fixed parameter stays fixed
    const double delta_q = g.u < 0.5 ? scratch[i] - 1.0 : 1.0 - scratch[i];
    *g.x = std::clamp(*g.x + delta_q * range, g.lower, g.upper);
  }
}

double polynomial_mutation(double x, double lower, double upper, double eta_m, RandomStream& rng) {
  const MutationGene gene{&x, lower, upper, rng.uniform()};
  std::vector<double> scratch;
  mutate_all(std::span(&gene, 1), eta_m, scratch);
  return x;
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

  // Two passes: every random draw of the generation in stream order, then the crossed variables and the mutated
  // genes, whose powers go through one vector pow per stage (genetic::pow_each).
  const auto pairs = static_cast<std::size_t>((n + 1) / 2), genes = static_cast<std::size_t>(dim_);
  spare_child_.resize(genes);
  pair_pm_.resize(pairs);
  crossed_.resize(pairs * genes);
  std::size_t crossed = 0;
  const std::uint64_t generation_key = hash_key({run_key_, g});
  for (int k = 0; k < (n + 1) / 2; ++k) {
    const std::uint64_t pair_key = extend_key(generation_key, static_cast<std::uint64_t>(k));  // (run, g, pair)
    RandomStream select(extend_key(pair_key, kSelect));
    const int a = genetic::tournament(values_, settings_.tournament, select);
    const int b = genetic::tournament(values_, settings_.tournament, select);
    const PairRates r = rates(values_[a], values_[b], stats);
    pair_pm_[static_cast<std::size_t>(k)] = r.pm;

    const std::span<double> child_a = member(offspring_, 2 * k);
    const std::span<double> child_b = 2 * k + 1 < n ? member(offspring_, 2 * k + 1) : std::span<double>(spare_child_);
    RandomStream crossover(extend_key(pair_key, kCrossover));
    if (crossover.uniform() < r.pc) {
      crossed += genetic::sbx_draw(member(population_, a), member(population_, b), child_a, child_b, bounds_.lower,
                                   bounds_.upper, crossover, std::span(crossed_).subspan(crossed, genes));
    } else {
      std::ranges::copy(member(population_, a), child_a.begin());
      std::ranges::copy(member(population_, b), child_b.begin());
    }
  }
  genetic::sbx_finish(std::span(crossed_).first(crossed), settings_.eta_c, pow_scratch_);

  // Gene j of child c mutates when its draw is below the child's rate, and then takes the next draw as its u:
  // both are computed and the gene kept or not without a branch on the draw (as in sbx_draw).
  mutated_.resize(static_cast<std::size_t>(n) * genes);
  std::size_t mutated = 0;
  for (int c = 0; c < n; ++c) {
    RandomStream mutate(extend_key(extend_key(generation_key, static_cast<std::uint64_t>(c)), kMutate));
    const std::span<double> x = member(offspring_, c);
    const double rate = pair_pm_[static_cast<std::size_t>(c / 2)][static_cast<std::size_t>(c % 2)];
    for (int j = 0; j < dim_; ++j) {
      const bool mutates = mutate.peek_uniform(0) < rate;
      mutated_[mutated] = {&x[j], bounds_.lower[j], bounds_.upper[j], mutate.peek_uniform(1)};
      mutated += mutates ? 1 : 0;
      mutate.skip(mutates ? 2 : 1);
    }
  }
  genetic::mutate_all(std::span(mutated_).first(mutated), settings_.eta_m, pow_scratch_);
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
