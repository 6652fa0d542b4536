#include "optimizers/ga/operators.hpp"

#include <cmath>

#include "engine/common/vector_math.hpp"
#include "engine/kernels/isa.hpp"

// This file is compiled with -fno-trapping-math (optimizers/CMakeLists.txt): with GCC's default, the selects of
// the vector loops below stay branches and the loops vectorize only at avx512; the results are the same.

namespace dampbench::genetic {
namespace {

/// Lanes per block of the vector loops: every variable and gene goes through the vector pow of the level (the
/// arrays are padded to whole blocks, so there is no scalar remainder loop with glibc's scalar pow). The loops'
/// block() functions are always_inline: Clang's flatten inlines one level only (engine/kernels/isa.hpp).
constexpr std::size_t kBlock = 16;

std::size_t padded(std::size_t n) { return (n + kBlock - 1) / kBlock * kBlock; }

/// std::clamp(v, lo, hi) by value (the same result, NaN and signed zeros included), which the loops below vectorize.
inline double clamp(double v, double lo, double hi) {
  const double at_least_lo = v < lo ? lo : v;
  return hi < at_least_lo ? hi : at_least_lo;
}

/// Bounded SBX's second half over whole blocks, compiled per vector level (IsaClones). For a draw u and a
/// parent at distance beta from the bound on its side: alpha = 2 − beta^−(η_c + 1); the spread factor is
/// beta_q = (u·alpha)^(1/(η_c + 1)) if u ≤ 1/alpha, else (1/(2 − u·alpha))^(1/(η_c + 1)). The lower child uses the
/// lower bound, the upper child the upper one.
struct SbxBlocks {
  static void run(const double* y1, const double* y2, const double* lower, const double* upper, const double* u,
                  const double* swap, double* child_a, double* child_b, std::size_t blocks, double eta_c) {
    const double spread_power = -(eta_c + 1.0), root = 1.0 / (eta_c + 1.0);
    for (std::size_t b = 0; b < blocks; ++b) block(y1 + b * kBlock, y2 + b * kBlock, lower + b * kBlock,
                                                   upper + b * kBlock, u + b * kBlock, swap + b * kBlock,
                                                   child_a + b * kBlock, child_b + b * kBlock, spread_power, root);
  }
  [[gnu::always_inline]] static void block(const double* __restrict y1, const double* __restrict y2,
                                           const double* __restrict lower, const double* __restrict upper,
                                           const double* __restrict u, const double* __restrict swap,
                                           double* __restrict child_a, double* __restrict child_b,
                                           double spread_power, double root) {
#pragma omp simd
    for (std::size_t i = 0; i < kBlock; ++i) {
      const double gap = y2[i] - y1[i];
      const double alpha_low = 2.0 - std::pow(1.0 + 2.0 * (y1[i] - lower[i]) / gap, spread_power);
      const double alpha_high = 2.0 - std::pow(1.0 + 2.0 * (upper[i] - y2[i]) / gap, spread_power);
      const double beta_low = std::pow(spread_base(u[i], alpha_low), root);
      const double beta_high = std::pow(spread_base(u[i], alpha_high), root);
      const double c1 = clamp(0.5 * ((y1[i] + y2[i]) - beta_low * gap), lower[i], upper[i]);
      const double c2 = clamp(0.5 * ((y1[i] + y2[i]) + beta_high * gap), lower[i], upper[i]);
      child_a[i] = swap[i] != 0 ? c2 : c1;
      child_b[i] = swap[i] != 0 ? c1 : c2;
    }
  }
  /// u·alpha if u ≤ 1/alpha, else 1/(2 − u·alpha), as one division whose operands are chosen (u·alpha / 1 is
  /// u·alpha exactly), so that no division sits under a condition.
  static double spread_base(double u, double alpha) {
    const bool below = u <= 1.0 / alpha;
    return (below ? u * alpha : 1.0) / (below ? 1.0 : 2.0 - u * alpha);
  }
};

/// Bounded polynomial mutation's second half over whole blocks, compiled per vector level (IsaClones):
/// δ_q = (2u + (1 − 2u)·xy^(η_m + 1))^(1/(η_m + 1)) − 1 with xy = 1 − (x − lower)/range for u < 1/2, and
/// 1 − (2(1 − u) + 2(u − 1/2)·xy^(η_m + 1))^(1/(η_m + 1)) with xy = 1 − (upper − x)/range otherwise; x + δ_q·range,
/// clamped to the bounds. A gene with range 0 keeps its value.
struct MutationBlocks {
  static void run(double* x, const double* lower, const double* upper, const double* u, std::size_t blocks,
                  double eta_m) {
    const double power = eta_m + 1.0, root = 1.0 / (eta_m + 1.0);
    for (std::size_t b = 0; b < blocks; ++b)
      block(x + b * kBlock, lower + b * kBlock, upper + b * kBlock, u + b * kBlock, power, root);
  }
  [[gnu::always_inline]] static void block(double* __restrict x, const double* __restrict lower,
                                           const double* __restrict upper, const double* __restrict u, double power,
                                           double root) {
#pragma omp simd
    for (std::size_t i = 0; i < kBlock; ++i) {
      const double range = upper[i] - lower[i];
      const bool low = u[i] < 0.5, fixed = !(range > 0);
      const double xy = fixed ? 1.0 : 1.0 - (low ? x[i] - lower[i] : upper[i] - x[i]) / (fixed ? 1.0 : range);
      const double p = std::pow(xy, power);
      const double s = std::pow(low ? 2.0 * u[i] + (1.0 - 2.0 * u[i]) * p : 2.0 * (1.0 - u[i]) + 2.0 * (u[i] - 0.5) * p,
                                root);
      const double delta_q = low ? s - 1.0 : 1.0 - s;
      const double mutated = clamp(x[i] + delta_q * range, lower[i], upper[i]);
      x[i] = fixed ? x[i] : mutated;
    }
  }
};

}  // namespace

int tournament(std::span<const double> values, std::span<const double> draws) {
  // Which entrant wins is a coin toss to a branch predictor: the winner is chosen with selects, not branches.
  const int n = static_cast<int>(values.size());
  const auto entrant = [n](double draw) { return std::min(static_cast<int>(draw * n), n - 1); };
  int winner = entrant(draws[0]);
  for (std::size_t e = 1; e < draws.size(); ++e) {
    const int i = entrant(draws[e]);
    const double vi = values[i], vw = values[winner];
    const bool wins = (vi < vw) | ((vi == vw) & (i < winner));
    winner = wins ? i : winner;
  }
  return winner;
}

int tournament(std::span<const double> values, int size, RandomStream& rng) {
  std::vector<double> draws(static_cast<std::size_t>(size));
  for (double& d : draws) d = rng.uniform();
  return tournament(values, draws);
}

void CrossedVariables::clear(std::size_t capacity) {
  const std::size_t room = padded(capacity);
  for (auto* v : {&at_a, &at_b}) v->resize(room);
  for (auto* v : {&y1, &y2, &lower, &upper, &u, &swap, &child_a, &child_b}) v->resize(room);
  count = 0;
}

std::size_t sbx_draw(std::span<const double> parent_a, std::span<const double> parent_b, std::span<double> pool,
                     std::size_t at_a, std::size_t at_b, const std::vector<double>& lower,
                     const std::vector<double>& upper, std::span<const double> draws, CrossedVariables& crossed) {
  // Every variable's entry is written and kept or not by the count: a branch on the draws would be mispredicted
  // half the time.
  std::size_t used = 0;
  for (std::size_t j = 0; j < parent_a.size(); ++j) {
    const double a = parent_a[j], b = parent_b[j];
    pool[at_a + j] = a;
    pool[at_b + j] = b;
    const double y1 = std::min(a, b), y2 = std::max(a, b);
    const bool crosses = draws[used] < 0.5 && y2 - y1 > 1e-14;
    const std::size_t k = crossed.count;
    crossed.at_a[k] = at_a + j;
    crossed.at_b[k] = at_b + j;
    crossed.y1[k] = y1;
    crossed.y2[k] = y2;
    crossed.lower[k] = lower[j];
    crossed.upper[k] = upper[j];
    crossed.u[k] = draws[used + 1];
    crossed.swap[k] = draws[used + 2] < 0.5 ? 1.0 : 0.0;
    crossed.count += crosses ? 1 : 0;
    used += crosses ? 3 : 1;
  }
  return used;
}

void sbx_finish(CrossedVariables& crossed, double eta_c, std::span<double> pool) {
  const std::size_t n = crossed.count, whole = padded(n);
  for (std::size_t i = n; i < whole; ++i) {  // padding: a harmless variable in [0, 1]
    crossed.y1[i] = crossed.lower[i] = 0.0;
    crossed.y2[i] = crossed.upper[i] = 1.0;
    crossed.u[i] = 0.5;
    crossed.swap[i] = 0.0;
  }
  IsaClones<SbxBlocks>::call(static_cast<const double*>(crossed.y1.data()), static_cast<const double*>(crossed.y2.data()),
                             static_cast<const double*>(crossed.lower.data()),
                             static_cast<const double*>(crossed.upper.data()), static_cast<const double*>(crossed.u.data()),
                             static_cast<const double*>(crossed.swap.data()), crossed.child_a.data(),
                             crossed.child_b.data(), whole / kBlock, eta_c);
  for (std::size_t i = 0; i < n; ++i) {
    pool[crossed.at_a[i]] = crossed.child_a[i];
    pool[crossed.at_b[i]] = crossed.child_b[i];
  }
}

void sbx(std::span<const double> parent_a, std::span<const double> parent_b, std::span<double> child_a,
         std::span<double> child_b, const std::vector<double>& lower, const std::vector<double>& upper,
         double eta_c, RandomStream& rng) {
  const std::size_t dim = parent_a.size();
  std::vector<double> pool(2 * dim), draws(3 * dim);
  for (std::size_t d = 0; d < draws.size(); ++d) draws[d] = rng.peek_uniform(d);
  CrossedVariables crossed;
  crossed.clear(dim);
  rng.skip(sbx_draw(parent_a, parent_b, pool, 0, dim, lower, upper, draws, crossed));
  sbx_finish(crossed, eta_c, pool);
  std::copy(pool.begin(), pool.begin() + static_cast<std::ptrdiff_t>(dim), child_a.begin());
  std::copy(pool.begin() + static_cast<std::ptrdiff_t>(dim), pool.end(), child_b.begin());
}

void MutatedGenes::clear(std::size_t capacity) {
  const std::size_t room = padded(capacity);
  at.resize(room);
  for (auto* v : {&x, &lower, &upper, &u}) v->resize(room);
  count = 0;
}

std::size_t mutation_draw(std::size_t at, double rate, const std::vector<double>& lower,
                          const std::vector<double>& upper, std::span<const double> draws, MutatedGenes& mutated) {
  std::size_t used = 0;
  for (std::size_t j = 0; j < lower.size(); ++j) {
    const bool mutates = draws[used] < rate;
    const std::size_t k = mutated.count;
    mutated.at[k] = at + j;
    mutated.lower[k] = lower[j];
    mutated.upper[k] = upper[j];
    mutated.u[k] = draws[used + 1];
    mutated.count += mutates ? 1 : 0;
    used += mutates ? 2 : 1;
  }
  return used;
}

void mutate_all(MutatedGenes& mutated, double eta_m, std::span<double> pool) {
  const std::size_t n = mutated.count, whole = padded(n);
  for (std::size_t i = 0; i < n; ++i) mutated.x[i] = pool[mutated.at[i]];
  for (std::size_t i = n; i < whole; ++i) {  // padding: a harmless gene in [0, 1]
    mutated.x[i] = 0.5;
    mutated.lower[i] = 0.0;
    mutated.upper[i] = 1.0;
    mutated.u[i] = 0.25;
  }
  IsaClones<MutationBlocks>::call(mutated.x.data(), static_cast<const double*>(mutated.lower.data()),
                                  static_cast<const double*>(mutated.upper.data()),
                                  static_cast<const double*>(mutated.u.data()), whole / kBlock, eta_m);
  for (std::size_t i = 0; i < n; ++i) pool[mutated.at[i]] = mutated.x[i];
}

double polynomial_mutation(double x, double lower, double upper, double eta_m, RandomStream& rng) {
  const double draws[2] = {0.0, rng.uniform()};  // the gene mutates (draw 0 < rate 1) and takes u
  MutatedGenes mutated;
  mutated.clear(1);
  mutation_draw(0, 1.0, {lower}, {upper}, draws, mutated);
  mutate_all(mutated, eta_m, std::span(&x, 1));
  return x;
}

}  // namespace dampbench::genetic
