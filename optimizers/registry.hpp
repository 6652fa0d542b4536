#pragma once
// Optimizers by name (`--optimizer NAME` and sweep files).
#include <string>

#include "engine/optimizer.hpp"
#include "optimizers/pso/pso.hpp"

namespace dampbench {

/// What the command line and presets say about the optimizer.
struct OptimizerSpec {
  std::string name = "pso";
  int population = 50;  ///< fvd paper N
  int iterations = 100; ///< fvd paper L
};

/// Validates the spec (InputError: unknown optimizer, bad population or iterations) and returns a
/// factory that makes one run's optimizer from its bounds and run key.
OptimizerFactory make_optimizer_factory(const OptimizerSpec& spec);

}  // namespace dampbench
