#pragma once
// The fvd paper's tables from a preset's results (fvd Tables 3–14, MODELS.md §1).
#include <string>
#include <vector>

#include "engine/cli/preset.hpp"
#include "engine/table.hpp"

namespace dampbench::cli {

/// Per model: Tables 3–6 (Mean, Max, Min, Std of the metric over the runs, per test), Tables 7–10 (each
/// parameter's mean, max, min, std over the runs per test, in the paper's units), Tables 11–14 (p̄ = mean
/// over tests of the per-test mean, Δp̄ = max − min of the per-test means, Δp̄/p̄); then a ranking table
/// (best and mean metric per model and test).
std::vector<Table> fvd_tables(const Preset& preset, const std::vector<GroupResult>& results);

/// summary.md: which produced table stands for which table of the paper.
std::string fvd_summary(const Preset& preset, const std::vector<Table>& tables);

}  // namespace dampbench::cli
