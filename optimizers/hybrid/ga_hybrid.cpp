#include "optimizers/hybrid/ga_hybrid.hpp"

#include <algorithm>

namespace dampbench {

namespace {

/// The cmaes settings of a hybrid with its population and generations.
CmaesSettings cmaes_of(const HybridSettings& s) {
  CmaesSettings c = s.cmaes;
  c.population = s.population;
  c.generations = s.generations;
  return c;
}

std::unique_ptr<Optimizer> make_global(const HybridSettings& s, const Bounds& bounds, std::uint64_t run_key) {
  if (s.global == GlobalStage::ga) return std::make_unique<Ga>(s, bounds, run_key);
  return std::make_unique<Cmaes>(cmaes_of(s), bounds, run_key);
}

}  // namespace

void HybridSettings::validate_shared(std::string_view hybrid) const {
  GeneticSettings::validate(hybrid);
  if (global == GlobalStage::cmaes) cmaes_of(*this).validate();
  check_ranges<GaSettings>(hybrid, ga_setting_table(), *this);
}

GaHybrid::GaHybrid(const HybridSettings& settings, const Bounds& bounds, std::uint64_t run_key)
    : bounds_(bounds), global_(make_global(settings, bounds, run_key)) {}

void GaHybrid::finish_refine(const BestSeen& seen) {
  refined_ = true;
  if (seen.value < global_->best_value()) {
    value_ = seen.value;
    position_ = seen.position;
  } else {
    value_ = global_->best_value();
    position_.assign(global_->best_position().begin(), global_->best_position().end());
  }
}

}  // namespace dampbench
