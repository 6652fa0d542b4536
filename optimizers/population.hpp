#pragma once
// What DE (optimizers/de), the generational GAs (optimizers/ga) and PSO (optimizers/pso) share: N candidates
// per ask for a fixed number of generations (PSO: iterations), an initial population drawn uniformly in the
// box with member i from the random stream (run key, 0, i), and the best position told so far.
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "engine/identification/optimizer.hpp"

namespace dampbench {

class PopulationOptimizer : public Optimizer {
 public:
  [[nodiscard]] int batch_size() const override { return population_size_; }
  [[nodiscard]] bool finished() const override { return generation_ >= generations_; }
  [[nodiscard]] std::span<const double> best_position() const override { return best_position_; }
  [[nodiscard]] double best_value() const override { return best_value_; }

 protected:
  /// Draws the initial population (member 0 is bounds.start, clamped into the box, when it is given); the best
  /// position is its first member until a value is told.
  /// `population` and `generations` must be validated by the caller (≥ 1).
  PopulationOptimizer(int population, int generations, const Bounds& bounds, std::uint64_t run_key);

  /// Member i of a row-major N × dim pool.
  [[nodiscard]] std::span<double> member(std::vector<double>& pool, int i) const {
    return {pool.data() + static_cast<std::size_t>(i) * dim_, static_cast<std::size_t>(dim_)};
  }
  double& x(int i, int j) { return population_[static_cast<std::size_t>(i) * dim_ + j]; }

  Bounds bounds_;
  std::uint64_t run_key_;
  int dim_;
  int generation_ = 0;              ///< generations (PSO: iterations) told so far
  std::vector<double> population_;  ///< row-major N × dim (the GAs keep one more row: optimizers/ga/genetic.hpp)
  std::vector<double> best_position_;
  double best_value_ = std::numeric_limits<double>::infinity();

 private:
  int population_size_, generations_;
};

}  // namespace dampbench
