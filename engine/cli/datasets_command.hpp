#pragma once
// `dampbench datasets generate [GRID...] [--into DIR]`: the synthetic grids presets name "@generated/...",
// written ahead of first use (datasets/synthetic/grids.hpp).
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

}  // namespace dampbench::cli
