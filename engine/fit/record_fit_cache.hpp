#pragma once
// Records' own fits made once and shared: by the folds of one `fit --folds` and by the task groups of one sweep
// process whose models choose laws (laws = "auto") or start from the records' fits (start = "per-file"). A record's
// own fit depends only on the record, the model it is fitted with, the optimizer (its factory: one per optimizer
// entry, which fixes population, iterations and budget) and the fit settings; the key names all of them, so a fit
// found here has the bits the search would have made. Each fit keeps what it cost, which a search that finds it
// counts as its own: a sweep group's stored evaluations and candidate-samples (which `verify` compares bit for
// bit) and its wall time are then the same whichever group made the fit.
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/identification/identification.hpp"
#include "engine/record/signals.hpp"

namespace dampbench {

/// What records' own fits cost, and what a law search adds to them before its joint fit.
struct PreFitEffort {
  double wall_time_s = 0;
  long long evaluations = 0;
  double candidate_samples = 0;  ///< Σ evaluations × samples, and the law choice's simulated samples
  PreFitEffort& operator+=(const PreFitEffort& o) {
    wall_time_s += o.wall_time_s, evaluations += o.evaluations, candidate_samples += o.candidate_samples;
    return *this;
  }
};

/// One record's own fit: its best parameters and its cost.
struct RecordFit {
  std::vector<double> best_params;
  PreFitEffort effort;
};

class RecordFitCache {
 public:
  /// The key of `record`'s own fit with the model `model_id`, `optimizer` and `settings` (its task key aside, which
  /// the search derives from the model and the record).
  static std::string key(const Signals& record, std::string_view model_id, const void* optimizer,
                         const IdentificationSettings& settings);

  /// The fit under `key`, if one was stored.
  [[nodiscard]] std::optional<RecordFit> find(const std::string& key) const;
  /// Stores a fit. Two searches that need the same fit at once may both make it (the same bits); the first stays.
  void store(const std::string& key, const RecordFit& fit);
  [[nodiscard]] std::size_t size() const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, RecordFit> fits_;
};

}  // namespace dampbench
