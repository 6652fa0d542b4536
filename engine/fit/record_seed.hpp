#pragma once
// Where a fit on several records starts, when it asks to start from the records themselves: `--start per-file`
// (the laws fitted to each record's own fit, engine/fit/record_start.hpp) or `--start narrowed` (the box and start of
// the mfm paper's bound narrowing, engine/fit/record_narrowing.hpp). One decision for `fit` and its held-out folds.
#include <functional>
#include <string>

#include "engine/fit/fit.hpp"
#include "engine/fit/prepared_fit.hpp"
#include "engine/fit/record_fit_cache.hpp"

namespace dampbench {

/// `request` (of `fit`, on some of its records) with the start, and for `narrowed` the box, its spec asks for; the
/// per-file fits go through `record_fits` (may be null); `progress` (may be empty) is told each step.
void seed_start(const PreparedFit& fit, FitRequest& request, RecordFitCache* record_fits,
                const std::function<void(const std::string&)>& progress);

}  // namespace dampbench
