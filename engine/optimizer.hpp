#pragma once
// The ask/tell interface every population optimizer implements (optimizers/ has one folder per
// algorithm). One Optimizer object is one independent run; R runs advance in lockstep so that each
// generation of all of them is evaluated as one batch (engine/identification.hpp).
#include <cstdint>
#include <functional>
#include <memory>
#include <span>

#include "engine/batch.hpp"
#include "engine/bounds.hpp"

namespace dampbench {

class Optimizer {
 public:
  virtual ~Optimizer() = default;
  /// Candidates per ask (the population size of a generational algorithm).
  [[nodiscard]] virtual int batch_size() const = 0;
  /// Writes the next batch_size() candidates into rows [first, first + batch_size()) of `batch`.
  virtual void ask(CandidateBatch& batch, int first) = 0;
  /// Takes the metric of each asked candidate, in the order asked (+inf for failed candidates).
  virtual void tell(std::span<const double> values) = 0;
  [[nodiscard]] virtual bool finished() const = 0;
  [[nodiscard]] virtual std::span<const double> best_position() const = 0;
  [[nodiscard]] virtual double best_value() const = 0;
};

/// Makes the optimizer of one run. `run_key` keys every random number the run draws
/// (engine/random.hpp), so a run's history depends only on it, never on threads or batch layout.
using OptimizerFactory = std::function<std::unique_ptr<Optimizer>(const Bounds& bounds, std::uint64_t run_key)>;

}  // namespace dampbench
