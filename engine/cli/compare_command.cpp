// `dampbench compare`: several optimizers on one model and one or more records (optimizers/comparison.hpp
// defines every statistic). Prints the table (md, csv or json) and, with -o DIR, writes DIR/comparison.<fmt>
// and DIR/convergence.csv (optimizer,evaluations,q25,median,q75 of the best-so-far metric over the runs).
#include "engine/cli/compare_command.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/cli/cli_options.hpp"
#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"
#include "engine/common/text_file.hpp"
#include "engine/fit/fit_records.hpp"
#include "engine/fit/resolve_model.hpp"
#include "engine/model/metrics.hpp"
#include "optimizers/comparison.hpp"

namespace dampbench::cli {

void add_compare_options(CLI::App* cmd, CompareOptions& o) {
  cmd->add_option("--model", o.model, "model id (see `dampbench models`)")->required();
  cmd->add_option("--laws", o.laws, "parameter laws in operating variables, e.g. 'c0=poly(I,1);alpha=poly(I,1)'");
  cmd->add_option("--data", o.paths, "test record (CSV); repeat for several conditions fitted at once")->required();
  add_data_options(cmd, o.data);
  cmd->add_option("--optimizer", o.optimizers,
                  "NAME[:population=N,iterations=N,key=value,...]; repeat, e.g. --optimizer pso --optimizer "
                  "ga:population=80 --optimizer ga-sqp:population=240,constraint=0.04")
      ->required();
  cmd->add_option("--metric", o.metric, metric_names() + " (default of_abs)");
  cmd->add_option("--runs", o.runs, "independent runs per optimizer (default 10)");
  cmd->add_option("--seed", o.seed, "seed (default 1)");
  cmd->add_option("--bounds", o.bounds, "bounds in SI, name=lo:hi,...");
  cmd->add_option("--target", o.target,
                  "metric value for evaluations-to-target (default: 1.01 x the best value found by any run)");
  cmd->add_option("--max-evaluations", o.max_evaluations, "evaluation budget per run for every optimizer (default: none)");
  cmd->add_option("--format", o.format, "md (default), csv or json");
  cmd->add_option("-o,--output", o.output_dir, "folder for comparison.<format> and convergence.csv");
}

namespace {

nlohmann::ordered_json to_json(const Comparison& c, const CompareOptions& o, const Model& model, double wall_s) {
  nlohmann::ordered_json j;
  j["model"] = model.id();
  j["data"] = o.paths;
  j["metric"] = o.metric;
  j["runs"] = o.runs;
  j["seed"] = o.seed;
  j["best_found"] = json_number(c.best_found);
  j["success_threshold"] = json_number(c.success_threshold);
  j["target"] = json_number(c.target);
  j["target_given"] = c.target_given;
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const OptimizerComparison& oc : c.optimizers) {
    nlohmann::ordered_json e;
    e["optimizer"] = oc.label;
    e["name"] = oc.spec.name;
    e["population"] = oc.spec.population;
    e["iterations"] = oc.spec.iterations;
    e["settings"] = oc.spec.settings;
    e["best"] = json_number(oc.summary.min);
    e["worst"] = json_number(oc.summary.max);
    e["mean"] = json_number(oc.summary.mean);
    e["std"] = json_number(oc.summary.std);
    e["successes"] = oc.successes;
    e["success_rate"] = oc.success_rate;
    e["reached_target"] = oc.reached_target;
    e["median_evaluations_to_target"] = json_number(oc.median_evaluations_to_target);
    e["mean_evaluations"] = oc.mean_evaluations;
    if (oc.feasible_runs) {
      e["feasible_runs"] = *oc.feasible_runs;
      e["constraint"] = json_number(*oc.constraint);
    }
    e["wall_time_s"] = oc.wall_time_s;
    nlohmann::ordered_json values = nlohmann::ordered_json::array();
    for (const RunResult& r : oc.runs) values.push_back(json_number(r.best_value));
    e["run_values"] = values;
    list.push_back(e);
  }
  j["optimizers"] = list;
  j["wall_time_s"] = wall_s;
  return j;
}

void write_file(const std::filesystem::path& path, const std::string& text) { write_text_file(path.string(), text); }

}  // namespace

int compare_command(const CompareOptions& o) {
  if (o.format != "md" && o.format != "csv" && o.format != "json")
    throw InputError(fmt::format("--format: expected md, csv or json, got '{}'", o.format));
  if (o.runs < 1) throw InputError(fmt::format("--runs: expected a whole number >= 1, got {}", o.runs));
  if (o.max_evaluations < 0)
    throw InputError(fmt::format("--max-evaluations: expected a whole number >= 0, got {}", o.max_evaluations));
  if (o.optimizers.empty()) throw InputError("compare: give at least one --optimizer");

  const ResolvedModel resolved =
      resolve_model(command_line_model(o.model, o.laws, o.bounds));
  const Model* model = resolved.model;
  ComparisonSettings settings;
  settings.identification.metric = parse_metric(o.metric);
  settings.identification.runs = o.runs;
  settings.identification.seed = o.seed;
  settings.identification.budget.max_evaluations = o.max_evaluations;
  if (!o.target.empty()) settings.target = parse_number(trim(o.target), "--target");

  std::vector<ComparisonEntry> entries;
  for (const std::string& text : o.optimizers) entries.push_back({std::string(trim(text)), parse_optimizer_entry(text)});

  const FitRecords records = load_fit_records(*model, o.paths, o.data);
  settings.data_name = records.names;
  const std::vector<const Signals*> data = records.pointers();
  const Bounds bounds = resolved.bounds_for(data);

  const auto start = std::chrono::steady_clock::now();
  const Comparison c = compare_optimizers(*model, data, bounds, entries, settings);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const Table table = comparison_table(c, o.metric);
  std::string text;
  if (o.format == "json") text = to_json(c, o, *model, wall_s).dump(2) + "\n";
  else if (o.format == "csv") text = table.to_csv();
  else text = table.to_markdown();
  std::cout << text;
  if (o.format == "md")
    std::cout << fmt::format("\n{} on {}, {} runs per optimizer, seed {}: {:.3f} s\n", model->id(),
                             settings.data_name, o.runs, o.seed, wall_s);
  if (!o.output_dir.empty()) {
    const std::filesystem::path dir(o.output_dir);
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw InputError(fmt::format("-o: cannot create '{}': {}", o.output_dir, ec.message()));
    write_file(dir / ("comparison." + o.format), text);
    write_file(dir / "convergence.csv", convergence_csv(c));
  }
  return 0;
}

}  // namespace dampbench::cli
