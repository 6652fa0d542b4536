#include "optimizers/hybrid/ga_hybrid.hpp"

#include <algorithm>

namespace dampbench {

void GaHybrid::finish_refine(const BestSeen& seen) {
  refined_ = true;
  if (seen.value < ga_.best_value()) {
    value_ = seen.value;
    position_ = seen.position;
  } else {
    value_ = ga_.best_value();
    position_.assign(ga_.best_position().begin(), ga_.best_position().end());
  }
}

}  // namespace dampbench
