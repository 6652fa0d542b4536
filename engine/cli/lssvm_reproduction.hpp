#pragma once
// The lssvm paper's numbers beside a run of `dampbench lssvm --reproduce FILE` (datasets/papers/lssvm.toml): the run's
// training set, hyperparameters and test errors as tables, judged by the reproduction report of the presets
// (engine/sweep/reproduction.hpp), and written as reproduction.md and reproduction.json into the run's -o folder.
#include <cstddef>
#include <string>
#include <vector>

#include "engine/common/table.hpp"
#include "engine/sweep/reproduction.hpp"
#include "engine/lssvm/lssvm.hpp"

namespace dampbench::cli {

/// One test record's errors, one step ahead (fed the measured past force) and in free run (its own).
struct LssvmRecordErrors {
  std::string name;
  lssvm::ErrorMetrics one_step, free_run;
};

/// What of a run the paper's numbers stand beside.
struct LssvmRunFigures {
  std::size_t train_samples = 0;
  double c = 0, sigma = 0;
  std::vector<std::string> trained_on;     ///< the training records' names
  std::vector<LssvmRecordErrors> records;  ///< each test record, in the order given
  LssvmRecordErrors all;                   ///< pooled over them, named "all"
};

/// Our tables: lssvm_training (training samples), lssvm_hyperparameters (c, sigma), lssvm_errors (MAE, max abs, MSE in
/// N and N², one step and free run; a row per test record and "all", pooled) and lssvm_relative_errors (max rel in
/// %; a row per test record and "largest", the largest of them).
std::vector<Table> lssvm_reproduction_tables(const LssvmRunFigures& run);

/// The paper file's text parsed (the checks of engine/sweep/paper_file.hpp), before a run spends its time.
void check_lssvm_paper_file(const std::string& published);

/// The report of `published` against the run: `truth` names what made synthetic records ("" for real ones, whose
/// errors in N are another damper's and left unjudged beside the relative ones). Writes reproduction.md and
/// reproduction.json into `dir`; InputError naming the file for a malformed paper file.
sweep::Reproduction write_lssvm_reproduction(const std::string& dir, const std::string& published,
                                             const std::string& truth, const LssvmRunFigures& run);

}  // namespace dampbench::cli
