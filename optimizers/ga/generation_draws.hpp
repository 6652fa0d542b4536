#pragma once
// The random draws of one GA generation (optimizers/ga/genetic.hpp: pair k selects from stream
// (run_key, g, k, "select") and crosses from (run_key, g, k, "crossover"), child c mutates from (run_key, g, c,
// "mutate")), all computed before breeding starts as vector loops (optimizers/random_draws.hpp): the first draws
// of each stream, exactly what RandomStream gives.
#include <cstdint>
#include <span>
#include <vector>

#include "engine/common/random.hpp"

namespace dampbench {

/// Names of the GA's streams (the last key part).
inline constexpr std::uint64_t kSelectStream = hash_name("select");
inline constexpr std::uint64_t kCrossoverStream = hash_name("crossover");
inline constexpr std::uint64_t kMutateStream = hash_name("mutate");

class GenerationDraws {
 public:
  /// Draws for generation key hash_key({run_key, g}): the first select_count draws of each of `pairs` select
  /// streams and the first crossover_count of each crossover stream, the first mutate_count of each of `children`
  /// mutate streams.
  void draw(std::uint64_t generation_key, int pairs, int children, int select_count, int crossover_count,
            int mutate_count);
  [[nodiscard]] std::span<const double> select(int pair) const { return row(select_, select_count_, pair); }
  [[nodiscard]] std::span<const double> crossover(int pair) const { return row(crossover_, crossover_count_, pair); }
  [[nodiscard]] std::span<const double> mutate(int child) const { return row(mutate_, mutate_count_, child); }

 private:
  static std::span<const double> row(const std::vector<double>& draws, int count, int i) {
    return std::span(draws).subspan(static_cast<std::size_t>(i) * count, static_cast<std::size_t>(count));
  }
  std::vector<std::uint64_t> member_keys_, keys_, scratch_;
  std::vector<double> select_, crossover_, mutate_;
  int select_count_ = 0, crossover_count_ = 0, mutate_count_ = 0;
};

}  // namespace dampbench
