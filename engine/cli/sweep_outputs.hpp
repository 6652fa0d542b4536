#pragma once
// Writing a sweep's tables into its output folder: tables.md (every table), one CSV per table, and
// summary.md, which names the paper's table beside each produced table (the fvd paper's Tables 3–14 and
// the other papers' tables, engine/sweep/tables.hpp). A sweep of several parts (all.toml) gets one
// subfolder per part and a top-level summary.md.
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "engine/sweep/runner.hpp"
#include "engine/sweep/tables.hpp"

namespace dampbench::cli {

struct OutputInfo {
  std::string spec_path, store_path;
  sweep::RunnerSummary summary;  ///< this session
};

/// Writes the outputs; prints the tables to `print` (when not null) for a single-part sweep. Returns the paths
/// written, relative to `out_dir` (for the folder's manifest, engine/cli/output_manifest.hpp).
std::vector<std::string> write_sweep_outputs(const sweep::StoreResults& results, const std::filesystem::path& out_dir,
                         const OutputInfo& info, std::ostream* print);

}  // namespace dampbench::cli
