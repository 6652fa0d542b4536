#include "engine/cli/preset.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "engine/bounds.hpp"
#include "engine/cli/fvd_tables.hpp"
#include "engine/error.hpp"
#include "models/registry.hpp"

namespace dampbench::cli {
namespace {

/// "file:line: key 'k': " prefix for messages about a node.
std::string where(const std::string& path, const toml::node* node, std::string_view key) {
  if (node && node->source().begin.line > 0)
    return fmt::format("{}:{}: key '{}'", path, node->source().begin.line, key);
  return fmt::format("{}: key '{}'", path, key);
}

std::string required_string(const std::string& path, const toml::table& t, std::string_view key) {
  const toml::node* n = t.get(key);
  if (!n) throw InputError(fmt::format("{}: missing key '{}' (expected a string)", path, key));
  if (!n->is_string()) throw InputError(where(path, n, key) + ": expected a string");
  return std::string(*n->value<std::string>());
}

std::string optional_string(const std::string& path, const toml::table& t, std::string_view key, std::string fallback) {
  return t.get(key) ? required_string(path, t, key) : fallback;
}

std::int64_t optional_integer(const std::string& path, const toml::table& t, std::string_view key,
                              std::int64_t fallback, std::int64_t min) {
  const toml::node* n = t.get(key);
  if (!n) return fallback;
  if (!n->is_integer()) throw InputError(where(path, n, key) + fmt::format(": expected an integer >= {}", min));
  const auto v = *n->value<std::int64_t>();
  if (v < min) throw InputError(where(path, n, key) + fmt::format(": expected an integer >= {}, got {}", min, v));
  return v;
}

}  // namespace

Preset load_preset(const std::string& path) {
  toml::table root;
  try {
    root = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    if (!std::filesystem::exists(path)) throw InputError(fmt::format("cannot open preset file '{}'", path));
    throw InputError(fmt::format("{}:{}:{}: {}", path, e.source().begin.line, e.source().begin.column, e.description()));
  }
  Preset p;
  p.path = path;
  p.name = required_string(path, root, "name");
  p.title = optional_string(path, root, "title", p.name);
  p.tables = optional_string(path, root, "tables", "fvd");
  if (p.tables != "fvd") throw InputError(where(path, root.get("tables"), "tables") + ": expected \"fvd\"");
  p.seed = static_cast<std::uint64_t>(optional_integer(path, root, "seed", 1, 0));
  p.runs = static_cast<int>(optional_integer(path, root, "runs", 50, 1));
  try {
    p.metric = parse_metric(optional_string(path, root, "metric", "of_abs"));
  } catch (const InputError& e) {
    throw InputError(where(path, root.get("metric"), "metric") + ": " + e.what());
  }

  if (const toml::node* opt = root.get("optimizer")) {
    if (!opt->is_table()) throw InputError(where(path, opt, "optimizer") + ": expected a table [optimizer]");
    const toml::table& t = *opt->as_table();
    p.optimizer.name = optional_string(path, t, "name", "pso");
    p.optimizer.population = static_cast<int>(optional_integer(path, t, "population", 50, 2));
    p.optimizer.iterations = static_cast<int>(optional_integer(path, t, "iterations", 100, 1));
    try {
      make_optimizer_factory(p.optimizer);
    } catch (const InputError& e) {
      throw InputError(where(path, opt, "optimizer") + ": " + e.what());
    }
  }

  const toml::node* models = root.get("models");
  if (!models || !models->is_array() || models->as_array()->empty())
    throw InputError(where(path, models, "models") + ": expected a non-empty array of model ids");
  for (const toml::node& m : *models->as_array()) {
    if (!m.is_string()) throw InputError(where(path, &m, "models") + ": expected model ids as strings");
    const std::string id(*m.value<std::string>());
    try {
      find_model(id);
    } catch (const InputError& e) {
      throw InputError(where(path, &m, "models") + ": " + e.what());
    }
    p.models.push_back(id);
  }

  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  const toml::node* datasets = root.get("datasets");
  if (!datasets || !datasets->is_array_of_tables() || datasets->as_array()->empty())
    throw InputError(where(path, datasets, "datasets") + ": expected one or more [[datasets]] tables");
  for (const toml::node& d : *datasets->as_array()) {
    const toml::table& t = *d.as_table();
    PresetDataset ds;
    ds.name = required_string(path, t, "name");
    ds.label = optional_string(path, t, "label", ds.name);
    ds.data.path = (folder / required_string(path, t, "file")).lexically_normal().string();
    ds.data.units = optional_string(path, t, "units", "");
    ds.data.columns = optional_string(path, t, "columns", "");
    p.datasets.push_back(ds);
  }

  if (const toml::node* b = root.get("bounds")) {
    if (!b->is_table()) throw InputError(where(path, b, "bounds") + ": expected a table [bounds] of model = \"name=lo:hi,...\"");
    for (const auto& [key, value] : *b->as_table()) {
      const std::string id(key.str());
      if (!value.is_string()) throw InputError(where(path, &value, id) + ": expected a string \"name=lo:hi,...\"");
      try {
        Bounds bounds = default_bounds(find_model(id));
        override_bounds(bounds, find_model(id), *value.value<std::string>(), "bounds");
      } catch (const InputError& e) {
        throw InputError(where(path, &value, id) + ": " + e.what());
      }
      p.bounds[id] = *value.value<std::string>();
    }
  }
  return p;
}

int run_command(const RunOptions& options) {
  const Preset preset = load_preset(options.preset);
  // Load every dataset before any work starts: a bad file stops the run before it costs anything.
  std::vector<Signals> signals;
  for (const auto& d : preset.datasets) {
    Dataset data = load_data(d.data, true);
    data.name = d.name;
    signals.push_back(prepare_signals(data));
  }
  const OptimizerFactory factory = make_optimizer_factory(preset.optimizer);
  const std::filesystem::path out_dir = options.output_dir.empty() ? "results/" + preset.name : options.output_dir;

  std::vector<GroupResult> results;
  double candidate_samples = 0;
  const auto start = std::chrono::steady_clock::now();
  for (const auto& id : preset.models) {
    const Model& model = find_model(id);
    Bounds bounds = default_bounds(model);
    if (auto it = preset.bounds.find(id); it != preset.bounds.end()) override_bounds(bounds, model, it->second, "bounds");
    for (int d = 0; d < static_cast<int>(signals.size()); ++d) {
      IdentificationSettings settings;
      settings.runs = preset.runs;
      settings.seed = preset.seed;
      settings.metric = preset.metric;
      settings.task_key = task_key(id, preset.datasets[d].name, preset.optimizer.name);
      results.push_back({&model, d, identify(model, signals[d], bounds, factory, settings)});
      candidate_samples += results.back().identification.candidate_samples;
      std::cerr << fmt::format("  {} on {}: best {} = {:.6g} ({:.2f} s)\n", id, preset.datasets[d].name,
                               metric_name(preset.metric),
                               results.back().identification.runs[results.back().identification.best_run()].best_value,
                               results.back().identification.wall_time_s);
    }
  }
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const std::vector<Table> tables = fvd_tables(preset, results);
  std::filesystem::create_directories(out_dir);
  std::ofstream md(out_dir / "tables.md");
  md << "# " << preset.title << "\n\n";
  for (const auto& t : tables) {
    md << t.to_markdown() << "\n";
    std::ofstream(out_dir / (t.id + ".csv")) << t.to_csv();
    std::cout << t.to_markdown() << "\n";
  }
  std::ofstream(out_dir / "summary.md") << fvd_summary(preset, tables);
  std::cout << fmt::format("{}: {} models x {} datasets x {} runs, {:.3g} candidate-samples in {:.2f} s wall "
                           "({:.3g} candidate-samples/s); tables in {}\n",
                           preset.name, preset.models.size(), preset.datasets.size(), preset.runs, candidate_samples,
                           wall_s, candidate_samples / wall_s, out_dir.string());
  return 0;
}

}  // namespace dampbench::cli
