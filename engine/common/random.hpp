#pragma once
// Keyed random streams (docs/design.md, "Reproducibility principles"): every random number is a pure function of
// (seed, task, run, iteration, member, draw index). There is no global or thread-local generator, so the
// numbers a particle draws do not depend on which thread asks, in which order, or how a batch is split.
//
// Generator: the SplitMix64 finalizer (Steele, Lea & Flood 2014, "Fast splittable pseudorandom number
// generators") applied to a counter mixed into a 64-bit key. Keys are built by hashing their parts one
// after the other with the same finalizer.
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <numbers>
#include <string_view>

namespace dampbench {

/// SplitMix64 finalizer: a bijective 64-bit mix with full avalanche.
constexpr std::uint64_t mix64(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

/// A key with one more part: extend_key(hash_key({a, b}), c) == hash_key({a, b, c}). Lets a loop over members
/// hash the parts they share (run, generation) once.
constexpr std::uint64_t extend_key(std::uint64_t key, std::uint64_t part) { return mix64(key ^ mix64(part)); }

/// Combines key parts in order: hash_key({seed, task, run}) differs from hash_key({seed, run, task}).
constexpr std::uint64_t hash_key(std::initializer_list<std::uint64_t> parts) {
  std::uint64_t h = 0x6A09E667F3BCC909ULL;
  for (std::uint64_t p : parts) h = extend_key(h, p);
  return h;
}

/// mix64(k) for the first draws of a stream, the same in every stream: a draw then costs one mix, not two.
inline constexpr auto kMixedCounters = [] {
  std::array<std::uint64_t, 64> t{};
  for (std::uint64_t k = 0; k < t.size(); ++k) t[k] = mix64(k);
  return t;
}();

/// mix64(k), from kMixedCounters where it has it: what draw k of a stream mixes into the stream's key.
constexpr std::uint64_t mixed_counter(std::uint64_t k) { return k < kMixedCounters.size() ? kMixedCounters[k] : mix64(k); }

/// A draw's 64 bits as a uniform in [0, 1): the top 53 bits times 2^-53 (exact).
constexpr double to_uniform(std::uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1.0p-53; }

/// Stable 64-bit hash of a name (FNV-1a), for task keys built from model and dataset names.
constexpr std::uint64_t hash_name(std::string_view s) {
  std::uint64_t h = 0xCBF29CE484222325ULL;
  for (char c : s) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001B3ULL;
  return h;
}

/// A standard normal from two uniforms u1, u2 in [0, 1) (Box–Muller): √(−2 ln(1 − u1))·cos(2π·u2), with 1 − u1 in
/// (0, 1]. RandomStream::normal() and the vector loop of first_normals() (optimizers/random_draws.hpp) share it.
inline double box_muller(double u1, double u2) {
  return std::sqrt(-2.0 * std::log(1.0 - u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

/// A stream of random numbers fixed by its key: draw k is mix64(key ^ mix64(k)).
class RandomStream {
 public:
  explicit constexpr RandomStream(std::uint64_t key) : key_(key) {}

  constexpr std::uint64_t next_u64() { return u64_at(counter_++); }
  /// Uniform in [0, 1) with 53 random bits.
  constexpr double uniform() { return to_uniform(next_u64()); }
  /// The uniform `ahead` draws past the next one, without drawing it: peek_uniform(0) is what uniform() returns
  /// next. With skip, a caller whose number of draws depends on earlier ones computes them without branching.
  [[nodiscard]] constexpr double peek_uniform(std::uint64_t ahead) const { return to_uniform(u64_at(counter_ + ahead)); }
  /// Moves past `n` draws, as n calls of uniform() would.
  constexpr void skip(std::uint64_t n) { counter_ += n; }
  /// Uniform in [lo, hi).
  constexpr double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

  /// Standard normal by the Box–Muller transform (one draw used, no cached pair: keeps draws keyed).
  double normal() {
    const double u1 = uniform();
    return box_muller(u1, uniform());
  }

 private:
  [[nodiscard]] constexpr std::uint64_t u64_at(std::uint64_t k) const {
    return mix64(key_ ^ mixed_counter(k));
  }

  std::uint64_t key_;
  std::uint64_t counter_ = 0;
};

}  // namespace dampbench
