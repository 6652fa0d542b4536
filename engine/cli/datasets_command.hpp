#pragma once
// `dampbench datasets generate [GRID...] [--into DIR]`: the synthetic grids presets name "@generated/...",
// written ahead of first use (datasets/synthetic/grids.hpp).
#include <cstdint>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace dampbench::cli {

struct DatasetsOptions {
  std::vector<std::string> grids;  ///< default: every grid
  std::string into;                ///< default: the cache folder `run` reads (engine/sweep/spec.hpp generated_dir)
};

void add_datasets_options(CLI::App* cmd, DatasetsOptions& options);
int datasets_command(const DatasetsOptions& options);

/// `dampbench datasets bouc-wen-benchmark [--seed S] [--into DIR]`: the hysteretic benchmark's training record
/// for a seed and the sine sweep check (datasets/synthetic/bouc_wen_benchmark.hpp).
struct BoucWenDatasetsOptions {
  std::uint64_t seed = 1;
  std::string into = ".";
};

void add_bouc_wen_datasets_options(CLI::App* cmd, BoucWenDatasetsOptions& options);
int bouc_wen_datasets_command(const BoucWenDatasetsOptions& options);

}  // namespace dampbench::cli
