#include "engine/cli/commands.hpp"

#include <cmath>
#include <fstream>
#include <iostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/bounds.hpp"
#include "engine/error.hpp"
#include "engine/excitation.hpp"
#include "engine/identification.hpp"
#include "engine/key_values.hpp"
#include "engine/random.hpp"
#include "engine/statistics.hpp"
#include "engine/table.hpp"
#include "models/registry.hpp"
#include "optimizers/registry.hpp"

namespace dampbench::cli {

Dataset load_data(const DataOptions& options, bool require_force) {
  CsvOptions csv;
  csv.require_force = require_force;
  if (!options.units.empty()) csv.units = parse_units_option(options.units);
  if (!options.columns.empty()) csv.columns = split_list(options.columns, "--columns");
  return load_csv(options.path, csv);
}

namespace {

/// JSON number that stays valid JSON: non-finite values become null.
nlohmann::json json_number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

void check_format(const std::string& format) {
  if (format != "md" && format != "json")
    throw InputError(fmt::format("--format: expected md or json, got '{}'", format));
}

/// Every parameter of the model from "name=value,..." (all required, SI).
std::vector<double> parse_params(const Model& model, const std::string& text) {
  std::vector<double> values(model.dim(), std::nan(""));
  for (const auto& [name, value] : parse_key_values(text, "--params"))
    values[model.parameter_index(name)] = parse_number(value, "--params " + name);
  for (int j = 0; j < model.dim(); ++j)
    if (std::isnan(values[j]))
      throw InputError(fmt::format("--params: missing parameter '{}' of model {}", model.parameters()[j].name, model.id()));
  return values;
}

}  // namespace

int models_command(const std::string& format) {
  check_format(format);
  if (format == "json") {
    nlohmann::ordered_json models = nlohmann::ordered_json::object();
    for (const Model* m : all_models()) {
      nlohmann::ordered_json params = nlohmann::ordered_json::array();
      for (const auto& p : m->parameters())
        params.push_back({{"name", p.name}, {"unit", p.unit}, {"lower", p.lower}, {"upper", p.upper},
                          {"paper_unit", p.paper_unit}});
      models[std::string(m->id())] = {{"citation", m->citation()}, {"law", m->law()}, {"parameters", params}};
    }
    std::cout << nlohmann::ordered_json{{"models", models}}.dump(2) << "\n";
    return 0;
  }
  for (const Model* m : all_models()) {
    Table t{std::string(m->id()), fmt::format("{} ({}): {}", m->id(), m->citation(), m->law()),
            {"parameter", "unit (SI)", "lower", "upper"}, {}};
    for (const auto& p : m->parameters())
      t.rows.push_back({p.name, p.unit, format_number(p.lower), format_number(p.upper)});
    std::cout << t.to_markdown() << "\n";
  }
  return 0;
}

int simulate_command(const SimulateOptions& o) {
  const Model& model = find_model(o.model);
  const std::vector<double> params = parse_params(model, o.params);
  if (o.sine.empty() == o.input.path.empty())
    throw InputError("simulate: give exactly one of --input FILE or --sine amp=...,freq=...,cycles=...,fs=...");
  if (!(o.noise_rel >= 0) || !std::isfinite(o.noise_rel))
    throw InputError(fmt::format("--noise-rel: expected a number >= 0, got {}", o.noise_rel));
  const Dataset data = o.sine.empty() ? load_data(o.input, false) : make_sine(parse_sine_option(o.sine));
  const Signals signals = prepare_signals(data);
  std::vector<double> force = model.simulate(params, signals);

  if (o.noise_rel > 0) {  // Gaussian noise, std = noise_rel × RMS of the simulated force
    double sum_sq = 0;
    for (double f : force) sum_sq += f * f;
    const double noise_std = o.noise_rel * std::sqrt(sum_sq / static_cast<double>(force.size()));
    RandomStream rng(hash_key({o.seed, hash_name("simulate-noise")}));
    for (double& f : force) f += noise_std * rng.normal();
  }

  std::ofstream file;
  if (!o.output.empty()) {
    file.open(o.output);
    if (!file) throw InputError(fmt::format("-o: cannot write '{}'", o.output));
  }
  std::ostream& out = o.output.empty() ? std::cout : file;
  out << "t,x,v,a,F\n";
  for (std::size_t k = 0; k < force.size(); ++k)
    out << fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", data.t_s[k], data.x_m[k], data.v_m_s[k],
                       data.a_m_s2[k], force[k]);
  return 0;
}

int fit_command(const FitOptions& o) {
  check_format(o.format);
  const Model& model = find_model(o.model);
  const Metric metric = parse_metric(o.metric);
  Bounds bounds = default_bounds(model);
  if (!o.bounds.empty()) override_bounds(bounds, model, o.bounds);
  const OptimizerFactory factory = make_optimizer_factory({o.optimizer, o.population, o.iterations});
  const Dataset data = load_data(o.data, true);
  const Signals signals = prepare_signals(data);

  IdentificationSettings settings;
  settings.runs = o.runs;
  settings.seed = o.seed;
  settings.metric = metric;
  settings.task_key = task_key(model.id(), data.name, o.optimizer);
  const Identification id = identify(model, signals, bounds, factory, settings);

  const RunResult& best = id.runs[id.best_run()];
  std::vector<double> values;
  long long evaluations = 0;
  for (const auto& r : id.runs) {
    values.push_back(r.best_value);
    evaluations += r.evaluations;
  }
  const Summary s = summarize(values);
  const auto params = model.parameters();
  const double rate = id.candidate_samples / id.wall_time_s;

  if (o.format == "json") {
    nlohmann::ordered_json j;
    j["model"] = model.id();
    j["data"] = o.data.path;
    j["samples"] = data.size();
    j["metric"] = o.metric;
    j["optimizer"] = {{"name", o.optimizer}, {"population", o.population}, {"iterations", o.iterations}};
    j["seed"] = o.seed;
    nlohmann::ordered_json bp = nlohmann::ordered_json::object();
    for (int i = 0; i < model.dim(); ++i) bp[params[i].name] = best.best_params[i];
    j["best_params"] = bp;
    nlohmann::ordered_json metrics = nlohmann::ordered_json::object();
    for (int i = 0; i < kMetricCount; ++i) metrics[std::string(metric_name(kAllMetrics[i]))] = json_number(best.best_metrics[i]);
    j["metrics"] = metrics;
    j["runs"] = {{"count", s.count}, {"best", json_number(s.min)}, {"worst", json_number(s.max)},
                 {"mean", json_number(s.mean)}, {"std", json_number(s.std)}};
    j["evaluations"] = evaluations;
    j["wall_time_s"] = id.wall_time_s;
    j["candidate_samples_per_s"] = rate;
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  const auto paper = model.to_paper_units(best.best_params);
  Table p{"best_params", fmt::format("{} on {} — best of {} runs", model.id(), data.name, o.runs),
          {"parameter", "value (SI)", "unit", "value (paper units)", "paper unit"}, {}};
  for (int i = 0; i < model.dim(); ++i)
    p.rows.push_back({params[i].name, format_number(best.best_params[i]), params[i].unit, format_number(paper[i]),
                      params[i].paper_unit});
  Table m{"metrics", "Metrics of the best run", {"metric", "value"}, {}};
  for (int i = 0; i < kMetricCount; ++i)
    m.rows.push_back({std::string(metric_name(kAllMetrics[i])), format_number(best.best_metrics[i])});
  Table r{"runs", fmt::format("{} over {} runs", o.metric, s.count), {"best", "worst", "mean", "std"},
          {{format_number(s.min), format_number(s.max), format_number(s.mean), format_number(s.std)}}};
  std::cout << p.to_markdown() << "\n" << m.to_markdown() << "\n" << r.to_markdown() << "\n";
  std::cout << fmt::format("{} evaluations × {} samples in {:.3f} s ({:.3g} candidate-samples/s)\n", evaluations,
                           data.size(), id.wall_time_s, rate);
  return 0;
}

}  // namespace dampbench::cli
