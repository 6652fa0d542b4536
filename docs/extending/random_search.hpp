#pragma once
// docs/extending.md, example 2: a new optimizer in 28 lines. Pure random search: every ask draws
// `population` candidates uniformly in the box from the run's keyed stream; the best one seen is kept.
#include <limits>
#include <vector>

#include "engine/common/random.hpp"
#include "engine/identification/optimizer.hpp"

namespace dampbench::example {

class RandomSearch final : public Optimizer {
 public:
  RandomSearch(int population, int iterations, const Bounds& bounds, std::uint64_t run_key)
      : population_(population), left_(iterations), bounds_(bounds), key_(run_key), best_(bounds.lower) {}
  int batch_size() const override { return population_; }
  void ask(CandidateBatch& batch, int first) override {
    asked_.assign(population_ * bounds_.dim(), 0.0);
    for (int i = 0; i < population_; ++i) {
      RandomStream rng(hash_key({key_, static_cast<std::uint64_t>(left_), static_cast<std::uint64_t>(i)}));
      for (int j = 0; j < bounds_.dim(); ++j)
        batch.at(first + i, j) = asked_[i * bounds_.dim() + j] = rng.uniform(bounds_.lower[j], bounds_.upper[j]);
    }
  }
  void tell(std::span<const double> values) override {
    for (int i = 0; i < population_; ++i)
      if (values[i] < best_value_)  // a failed candidate is +inf (or NaN) and never wins
        best_value_ = values[i], best_.assign(asked_.begin() + i * bounds_.dim(), asked_.begin() + (i + 1) * bounds_.dim());
    --left_;
  }
  bool finished() const override { return left_ <= 0; }
  std::span<const double> best_position() const override { return best_; }
  double best_value() const override { return best_value_; }

 private:
  int population_, left_;
  Bounds bounds_;
  std::uint64_t key_;
  std::vector<double> best_, asked_;
  double best_value_ = std::numeric_limits<double>::infinity();
};

}  // namespace dampbench::example
