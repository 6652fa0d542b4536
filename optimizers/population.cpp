#include "optimizers/population.hpp"

#include <algorithm>

#include "engine/common/random.hpp"

namespace dampbench {

PopulationOptimizer::PopulationOptimizer(int population, int generations, const Bounds& bounds,
                                         std::uint64_t run_key)
    : bounds_(bounds), run_key_(run_key), dim_(bounds.dim()), population_size_(population),
      generations_(generations) {
  population_.resize(static_cast<std::size_t>(population) * dim_);
  for (int i = 0; i < population; ++i) {
    RandomStream rng(hash_key({run_key_, 0, static_cast<std::uint64_t>(i)}));
    for (int j = 0; j < dim_; ++j) x(i, j) = rng.uniform(bounds_.lower[j], bounds_.upper[j]);
  }
  if (static_cast<int>(bounds_.start.size()) == dim_ && population > 0)
    for (int j = 0; j < dim_; ++j) x(0, j) = std::clamp(bounds_.start[j], bounds_.lower[j], bounds_.upper[j]);
  best_position_.assign(population_.begin(), population_.begin() + dim_);
}

}  // namespace dampbench
