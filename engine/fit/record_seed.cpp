#include "engine/fit/record_seed.hpp"

#include "engine/fit/record_narrowing.hpp"
#include "engine/fit/record_start.hpp"

namespace dampbench {

void seed_start(const PreparedFit& fit, FitRequest& request, RecordFitCache* record_fits,
                const std::function<void(const std::string&)>& progress) {
  if (fit.start_narrowed) {
    NarrowedStart n = narrowed_start(fit.choice, *fit.model.model, request.records, fit.optimizer, request.settings, {});
    if (progress) progress("--start narrowed: " + n.summary);
    request.box = std::move(n.box);
    request.start = std::move(n.start);
    return;
  }
  seed_from_record_fits(fit, request, record_fits, progress);
}

}  // namespace dampbench
