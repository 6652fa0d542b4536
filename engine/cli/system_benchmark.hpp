#pragma once
// A system-identification benchmark preset (datasets/presets/bouc_wen_benchmark.toml), run by `dampbench run`
// when the file has a [benchmark] table: the tool makes its own training records, fits a system model to each, saves
// the model files, and only then simulates the benchmark's test set with each saved model, beside the published
// results. The test set never reaches the fit: the fits read the generated records alone.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace dampbench::cli {

struct PublishedResult {
  std::string model;
  double e_rms_m = 0;
  std::string source;
};

struct SystemBenchmarkSpec {
  std::string path;   ///< the preset file
  std::string name;
  std::string title;
  std::string generator = "bouc-wen-benchmark";   ///< the training data's generator (datasets/synthetic)
  std::vector<std::uint64_t> training_seeds{1};
  std::string model = "sys.bouc_wen";
  std::string metric = "rmse";
  std::uint64_t seed = 1;                 ///< the optimizer's
  std::optional<int> population, iterations, runs;  ///< not given: fit's defaults and automatic budget
  std::string test;                       ///< the test record (resolved path)
  bool test_periodic = true;              ///< the test record is one period of a steady periodic response
  std::vector<PublishedResult> published;
};

/// True when the TOML file at `path` has a [benchmark] table (otherwise it is a sweep file).
bool is_system_benchmark(const std::string& path);

/// Reads and checks a benchmark preset; InputError names file, line, key and what was expected.
SystemBenchmarkSpec load_system_benchmark(const std::string& path);

/// Runs it into `output_dir` (default results/<name>): data/, fit_seed<S>.json, model_seed<S>.json, results.md and
/// results.json. Prints results.md.
int run_system_benchmark(const SystemBenchmarkSpec& spec, const std::string& output_dir);

}  // namespace dampbench::cli
