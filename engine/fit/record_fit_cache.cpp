#include "engine/fit/record_fit_cache.hpp"

#include <fmt/format.h>

namespace dampbench {

std::string RecordFitCache::key(const Signals& record, std::string_view model_id, const void* optimizer,
                                const IdentificationSettings& settings) {
  // The record by address: one Signals per record in a fit or a sweep part, alive for the whole run.
  const Budget& b = settings.budget;
  return fmt::format("{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}", static_cast<const void*>(&record), model_id, optimizer,
                     settings.runs, settings.seed, static_cast<int>(settings.metric), b.max_evaluations, b.target,
                     b.stall_iterations, b.max_wall_time_s, static_cast<int>(settings.search_precision));
}

std::optional<RecordFit> RecordFitCache::find(const std::string& key) const {
  const std::lock_guard lock(mutex_);
  const auto it = fits_.find(key);
  if (it == fits_.end()) return std::nullopt;
  return it->second;
}

void RecordFitCache::store(const std::string& key, const RecordFit& fit) {
  const std::lock_guard lock(mutex_);
  fits_.emplace(key, fit);
}

std::size_t RecordFitCache::size() const {
  const std::lock_guard lock(mutex_);
  return fits_.size();
}

}  // namespace dampbench
