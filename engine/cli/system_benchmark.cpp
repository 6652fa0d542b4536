#include "engine/cli/system_benchmark.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "datasets/synthetic/bouc_wen_benchmark.hpp"
#include "engine/cli/evaluate_command.hpp"
#include "engine/cli/fit_run.hpp"
#include "engine/common/table.hpp"
#include "engine/common/text_file.hpp"
#include "engine/sweep/spec/reader.hpp"

namespace dampbench::cli {

namespace fs = std::filesystem;
using sweep::spec_file::Reader;

namespace {

std::vector<PublishedResult> read_published(const Reader& r, const toml::table& bench) {
  std::vector<PublishedResult> out;
  const toml::node* node = bench.get("published");
  if (!node) return out;
  if (!node->is_array_of_tables()) r.fail(node, "benchmark.published", "expected [[benchmark.published]] tables");
  int i = 0;
  for (const toml::node& entry : *node->as_array()) {
    const auto& t = *entry.as_table();
    const std::string key = fmt::format("benchmark.published[{}]", i++);
    r.only_keys(t, key, {"model", "e_rms_m", "source"});
    const auto e = r.number(t, "e_rms_m", key);
    if (!e || !(*e > 0)) r.fail(&t, key + ".e_rms_m", "expected a positive number (metres)");
    out.push_back({r.required_string(t, "model", key), *e, r.string(t, "source", key).value_or("")});
  }
  return out;
}

std::optional<int> optional_count(const Reader& r, const toml::table& t, std::string_view key) {
  if (!t.get(key)) return std::nullopt;
  return static_cast<int>(r.integer(t, key, "benchmark", 1, 1));
}

/// The index of rmse among an evaluation's metrics.
std::size_t rmse_column() {
  return static_cast<std::size_t>(std::find(kAllMetrics.begin(), kAllMetrics.end(), Metric::rmse) - kAllMetrics.begin());
}

/// e_RMS [m] of a saved model on one record (evaluate --model-file).
double model_rmse(const std::string& model_file, const std::string& record, bool periodic) {
  EvaluateOptions o;
  o.model_file = model_file;
  o.paths = {record};
  o.data.periodic = periodic;
  return run_evaluate(o).metrics.at(0)[rmse_column()];
}

struct SeedResult {
  std::uint64_t seed = 0;
  nlohmann::ordered_json fit;  ///< fit --format json
  std::string model_file;
  double test_rms_m = 0, sweep_rms_m = 0;
};

/// Generates seed's training record and fits the spec's model to it alone; writes the fit and its model file.
SeedResult fit_seed(const SystemBenchmarkSpec& spec, const fs::path& out, std::uint64_t seed) {
  const fs::path data = out / "data";
  synthetic::write_bouc_wen_benchmark(data, seed);
  FitOptions o;
  o.fit.model.model = spec.model;
  o.fit.model.option_prefix = "benchmark.";
  o.fit.paths = {(data / fmt::format("training_seed{}.csv", seed)).string()};
  o.fit.metric = spec.metric;
  o.fit.seed = spec.seed;
  o.fit.population = spec.population;
  o.fit.iterations = spec.iterations;
  o.fit.runs = spec.runs;
  o.format = "json";
  SeedResult r;
  r.seed = seed;
  r.model_file = (out / fmt::format("model_seed{}.json", seed)).string();
  o.save_model = r.model_file;
  r.fit = fit_json(o, run_fit_options(o));
  write_text_file((out / fmt::format("fit_seed{}.json", seed)).string(), r.fit.dump(2) + "\n");
  return r;
}

Table error_table(const SystemBenchmarkSpec& spec, const std::vector<SeedResult>& results) {
  Table t{"benchmark_errors", fmt::format("{}: e_RMS of simulated y on the test set", spec.title),
          {"model", "e_RMS test [m]", "e_RMS sweep [m]", "source"}, {}};
  for (const auto& p : spec.published) t.rows.push_back({p.model, format_number(p.e_rms_m), "", p.source});
  for (const auto& r : results)
    t.rows.push_back({fmt::format("dampbench {} (grey box: knows the structure), training seed {}, {}", spec.model,
                                  r.seed, r.fit["convergence"]["verdict"].get<std::string>()),
                      format_number(r.test_rms_m), format_number(r.sweep_rms_m),
                      fmt::format("this run: {} evaluations, {:.0f} s", r.fit["evaluations"].get<long long>(),
                                  r.fit["wall_time_s"].get<double>())});
  t.note = "The fits read only the generated training records; the test record is simulated afterwards from u alone "
           "by each saved model (evaluate --model-file). The sweep is the tool's own 40 N, 20-50 Hz sweep from rest.";
  return t;
}

/// Identified values against the benchmark's Table 1, compared after the fits (the generator's truth).
Table parameter_table(const std::vector<SeedResult>& results) {
  const HystereticStructure& truth = synthetic::BoucWenBenchmark::kTruth;
  const std::vector<std::pair<std::string, double>> table1{
      {"m", truth.m_kg},           {"c", truth.c_N_s_m},           {"k", truth.k_N_m},  {"alpha", truth.alpha_N_m},
      {"beta_gamma", truth.beta_gamma}, {"beta_delta", truth.beta_delta}, {"nu", truth.nu}};
  Table t{"benchmark_parameters", "Identified parameters: value (deviation from the benchmark's Table 1)", {"seed"}, {}};
  for (const auto& [name, value] : table1) t.columns.push_back(fmt::format("{} ({:g})", name, value));
  for (const auto& r : results) {
    std::vector<Cell> row{std::to_string(r.seed)};
    for (const auto& [name, value] : table1) {
      const double fitted = r.fit["best_params"][name].get<double>();
      row.push_back(fmt::format("{:.6g} ({:+.3f} %)", fitted, 100 * (fitted - value) / std::fabs(value)));
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

}  // namespace

bool is_system_benchmark(const std::string& path) {
  try {
    const toml::table doc = toml::parse_file(path);
    return doc.contains("benchmark");
  } catch (const toml::parse_error&) {
    return false;  // the sweep reader reports the syntax error with its context
  }
}

SystemBenchmarkSpec load_system_benchmark(const std::string& path) {
  const Reader r(path);
  toml::table doc;
  try {
    doc = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    throw InputError(fmt::format("{}:{}: {}", path, e.source().begin.line, e.description()));
  }
  r.only_keys(doc, "", {"name", "title", "benchmark"});
  SystemBenchmarkSpec s;
  s.path = path;
  s.name = r.required_string(doc, "name", "");
  s.title = r.string(doc, "title", "").value_or(s.name);
  const toml::node* node = doc.get("benchmark");
  if (!node->is_table()) r.fail(node, "benchmark", "expected a table");
  const toml::table& b = *node->as_table();
  r.only_keys(b, "benchmark", {"generator", "training_seeds", "model", "metric", "seed", "population", "iterations",
                               "runs", "test", "test_periodic", "published"});
  s.generator = r.string(b, "generator", "benchmark").value_or(s.generator);
  if (s.generator != "bouc-wen-benchmark")
    r.fail(b.get("generator"), "benchmark.generator", fmt::format("expected \"bouc-wen-benchmark\", got '{}'", s.generator));
  if (const toml::node* seeds = b.get("training_seeds")) {
    s.training_seeds.clear();
    for (double v : r.numbers(*seeds, "benchmark.training_seeds")) {
      if (!(v >= 0) || v != std::floor(v)) r.fail(seeds, "benchmark.training_seeds", "expected whole numbers >= 0");
      s.training_seeds.push_back(static_cast<std::uint64_t>(v));
    }
  }
  s.model = r.string(b, "model", "benchmark").value_or(s.model);
  s.metric = r.string(b, "metric", "benchmark").value_or(s.metric);
  s.seed = static_cast<std::uint64_t>(r.integer(b, "seed", "benchmark", 1, 0));
  s.population = optional_count(r, b, "population");
  s.iterations = optional_count(r, b, "iterations");
  s.runs = optional_count(r, b, "runs");
  s.test = sweep::resolve_path(r.required_string(b, "test", "benchmark"), fs::path(path).parent_path().string());
  s.test_periodic = r.boolean(b, "test_periodic", "benchmark", true);
  s.published = read_published(r, b);
  if (!fs::exists(s.test))
    r.fail(b.get("test"), "benchmark.test", fmt::format("the test record '{}' does not exist", s.test));
  return s;
}

int run_system_benchmark(const SystemBenchmarkSpec& spec, const std::string& output_dir) {
  const fs::path out = output_dir.empty() ? fs::path("results") / spec.name : fs::path(output_dir);
  fs::create_directories(out);
  std::vector<SeedResult> results;
  for (std::uint64_t seed : spec.training_seeds) {
    std::cerr << fmt::format("{}: training seed {}: generating and fitting {}\n", spec.name, seed, spec.model);
    results.push_back(fit_seed(spec, out, seed));
  }
  // Only now does the test record come in: each saved model simulates it, and the tool's sweep, from u alone.
  for (SeedResult& r : results) {
    r.test_rms_m = model_rmse(r.model_file, spec.test, spec.test_periodic);
    r.sweep_rms_m = model_rmse(r.model_file, (out / "data" / "sweep_40N_20-50Hz.csv").string(), false);
  }
  const Table errors = error_table(spec, results), parameters = parameter_table(results);
  const std::string text = errors.to_markdown() + "\n" + parameters.to_markdown();
  write_text_file((out / "results.md").string(), text);
  nlohmann::ordered_json j;
  for (const auto& r : results)
    j[std::to_string(r.seed)] = {{"test_e_rms_m", r.test_rms_m},
                                 {"sweep_e_rms_m", r.sweep_rms_m},
                                 {"model_file", r.model_file},
                                 {"verdict", r.fit["convergence"]["verdict"]},
                                 {"best_params", r.fit["best_params"]}};
  write_text_file((out / "results.json").string(), j.dump(2) + "\n");
  std::cout << text;
  return 0;
}

}  // namespace dampbench::cli
