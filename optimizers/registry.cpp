#include "optimizers/registry.hpp"

#include <fmt/format.h>

#include "engine/error.hpp"

namespace dampbench {

OptimizerFactory make_optimizer_factory(const OptimizerSpec& spec) {
  if (spec.name == "pso") {
    PsoSettings settings;
    settings.population = spec.population;
    settings.iterations = spec.iterations;
    settings.validate();
    return [settings](const Bounds& bounds, std::uint64_t run_key) {
      return std::make_unique<Pso>(settings, bounds, run_key);
    };
  }
  throw InputError(fmt::format("unknown optimizer '{}' (known: pso)", spec.name));
}

}  // namespace dampbench
