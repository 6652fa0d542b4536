#include "engine/cli/datasets_command.hpp"

#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "datasets/synthetic/bouc_wen_benchmark.hpp"
#include "datasets/synthetic/grids.hpp"
#include "engine/sweep/spec.hpp"

namespace dampbench::cli {

void add_datasets_options(CLI::App* cmd, DatasetsOptions& o) {
  cmd->add_option("grids", o.grids, "grids to generate: fvd, crfd, crfd-neutral, mfm, mfm-neutral, fdsp, fdsp-neutral (default: all)");
  cmd->add_option("--into", o.into, "folder (default: the cache `run` reads; env DAMPBENCH_GENERATED_DIR)");
}

int datasets_command(const DatasetsOptions& o) {
  const std::string root = o.into.empty() ? sweep::generated_dir() : o.into;
  for (const std::string& grid : o.grids.empty() ? synthetic::grid_names() : o.grids) {
    const auto state = synthetic::ensure_grid(root, grid, sweep::generator_identity());
    std::cout << fmt::format("{}: {} {}\n", grid,
                             state == synthetic::GridState::kPresent       ? "already in"
                             : state == synthetic::GridState::kGenerated   ? "generated into"
                                                                            : "regenerated (made by another build) in",
                             (std::filesystem::path(root) / grid).string());
  }
  return 0;
}

void add_bouc_wen_datasets_options(CLI::App* cmd, BoucWenDatasetsOptions& o) {
  cmd->add_option("--seed", o.seed, "seed of the multisine's phases and the output noise (default 1)");
  cmd->add_option("--into", o.into, "folder to write into (default: the current one)");
}

int bouc_wen_datasets_command(const BoucWenDatasetsOptions& o) {
  synthetic::write_bouc_wen_benchmark(o.into, o.seed);
  std::cout << fmt::format("bouc-wen-benchmark: training_seed{}.csv and sweep_40N_20-50Hz.csv written into {}\n",
                           o.seed, o.into);
  return 0;
}

}  // namespace dampbench::cli
