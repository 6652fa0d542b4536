#pragma once
// Helpers shared by the sweep tests.
#include "engine/record/csv_loader.hpp"
#include "engine/sweep/plan.hpp"

namespace dampbench::testing {

/// The sweep's record loader for plain CSV files (no options).
inline sweep::Loader csv_loader() {
  return [](const RecordOptions& o) { return load_csv(o.path, CsvOptions{}); };
}

}  // namespace dampbench::testing
