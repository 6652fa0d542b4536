#pragma once
// The records a store names, read again from each part's stored sweep file: what the HTML report draws and the
// tables that need the samples themselves (the energy kind) evaluate the stored fits on.
#include <string>
#include <vector>

#include "engine/sweep/plan.hpp"
#include "engine/sweep/store.hpp"

namespace dampbench::sweep {

/// One record of a store's header (StoreHeader::datasets, same index), as read again.
struct StoreRecord {
  LoadedDataset loaded;
  /// Why the samples are not available ("" when they are): the sweep file cannot be parsed any more, the
  /// record's file is gone or fails to load, or its contents changed since the store was written (hash).
  std::string unavailable;
  [[nodiscard]] const Signals* signals() const { return unavailable.empty() ? &loaded.signals : nullptr; }
};

/// Every record of `header`, read in parallel with `loader`; never throws for a record (its `unavailable` says why).
std::vector<StoreRecord> reload_store_records(const StoreHeader& header, const Loader& loader);

}  // namespace dampbench::sweep
