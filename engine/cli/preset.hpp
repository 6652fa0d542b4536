#pragma once
// Presets (datasets/presets/*.toml): which models to identify on which datasets, with which optimizer,
// how many runs and which tables to print. The sweep files of later work extend this format.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "engine/cli/commands.hpp"
#include "engine/identification.hpp"
#include "engine/metrics.hpp"
#include "engine/model.hpp"
#include "optimizers/registry.hpp"

namespace dampbench::cli {

struct PresetDataset {
  std::string name;   ///< column label in tables, e.g. "Test 1"
  std::string label;  ///< longer description, e.g. "±20 mm, 92 mm/s, 3 cycles"
  DataOptions data;   ///< file path resolved against the preset's folder
};

struct Preset {
  std::string path;
  std::string name;
  std::string title;
  std::string tables;  ///< table set: "fvd" (fvd Tables 3–14)
  std::uint64_t seed = 1;
  int runs = 50;
  Metric metric = Metric::of_abs;
  OptimizerSpec optimizer;
  std::vector<std::string> models;
  std::vector<PresetDataset> datasets;
  std::map<std::string, std::string> bounds;  ///< model id → "name=lo:hi,..." overrides
};

/// Reads and validates a preset; errors name the file, line, key and what was expected.
Preset load_preset(const std::string& path);

/// One (model, dataset) group's repeated runs.
struct GroupResult {
  const Model* model = nullptr;
  int dataset = 0;  ///< index into Preset::datasets
  Identification identification;
};

}  // namespace dampbench::cli
