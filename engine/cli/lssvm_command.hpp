#pragma once
// `dampbench lssvm`: train an LS-SVM damper model (lssvm paper) on some records, tune (c, σ) by GA and
// report one-step-ahead and free-run metrics on other records.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "engine/record/record_options.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

struct LssvmOptions {
  std::vector<std::string> train;  ///< training records
  std::vector<std::string> test;   ///< test records
  std::string lags;                ///< "d=…,v=…,y=…" lag orders (defaults documented in engine/lssvm)
  std::optional<int> max_train;    ///< at most this many training samples, evenly spaced (unset: the default
                                   ///< cap, lssvm_command.cpp; 0: all)
  std::uint64_t seed = 1;
  std::string fitness;             ///< hyperparameter fitness (validation by default; the paper's is selectable)
  std::optional<int> population;   ///< GA population (unset: the paper's 50; 16 for the free-run fitness)
  std::optional<int> generations;  ///< GA generations (unset: the paper's 500; 16 for the free-run fitness)
  double validation = 0.2;         ///< held-out tail of each training record (fitness validation)
  double c = std::numeric_limits<double>::quiet_NaN();      ///< fixed c (with sigma): no GA; NaN: tune
  double sigma = std::numeric_limits<double>::quiet_NaN();  ///< fixed σ (with c): no GA; NaN: tune
  std::string format = "md";       ///< md or json
  std::string save_model;          ///< also write the trained model here (engine/fit/lssvm_model_file.hpp)
  std::string output;              ///< folder for errors.csv and convergence.csv ("" = none)
  std::string reproduce;           ///< the paper's numbers (datasets/papers/lssvm.toml): reproduction.md/json in output
  std::string truth;               ///< what made the records, when synthetic ("": real records)
  RecordOptions data;                ///< loader options shared by every record (path unused)
};

/// Declares the subcommand's options on `cmd` (created by main).
void add_lssvm_options(CLI::App* cmd, LssvmOptions& options);

/// Runs it; bad input throws InputError (reported by main).
int lssvm_command(const LssvmOptions& options);

}  // namespace dampbench::cli
