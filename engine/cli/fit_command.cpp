#include "engine/cli/commands.hpp"
#include "engine/cli/fit_defaults.hpp"
#include "engine/cli/report_command.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/model/bounds.hpp"
#include "engine/common/error.hpp"
#include "engine/record/excitation.hpp"
#include "engine/identification/convergence.hpp"
#include "engine/identification/identifiability.hpp"
#include "engine/identification/identification.hpp"
#include "engine/common/key_values.hpp"
#include "engine/model/law_model.hpp"
#include "engine/record/record_transforms.hpp"
#include "engine/evaluation/sensitivity.hpp"
#include "models/fixtures.hpp"
#include "engine/common/random.hpp"
#include "engine/common/statistics.hpp"
#include "engine/common/table.hpp"
#include "models/registry.hpp"
#include "optimizers/registry.hpp"

namespace dampbench::cli {

void add_data_options(CLI::App* cmd, RecordOptions& d) {
  cmd->add_option("--units", d.units, "units of the file's columns, e.g. x=mm,F=kN (default: header, else SI)");
  cmd->add_option("--columns", d.columns, "column names of a file without header, e.g. t,x,v,F");
  cmd->add_option("--transform", d.transform, "slider-crank or slider-crank-printed: crfd rig MTS record to angle and torque");
  cmd->add_option("--average-cycles", d.average, "cycles=N,drop=K: average cycles K+1..N-K into one (crfd: cycles=10,drop=3)");
  cmd->add_option("--conditions", d.conditions, "utfsm: operating variables from the file name (25mm0x25Hz0x75A)");
  cmd->add_option("--set", d.set, "operating variables, e.g. I=1,amp=0.01,freq=1 (for parameter laws)");
}

namespace {

/// JSON number that stays valid JSON: non-finite values become null.
nlohmann::json json_number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

void check_format(const std::string& format) {
  if (format != "md" && format != "json")
    throw InputError(fmt::format("--format: expected md or json, got '{}'", format));
}

/// Every parameter of the model from "name=value,..." (SI); all required unless `defaults` gives them.
std::vector<double> parse_params(const Model& model, const std::string& text, const std::vector<double>& defaults = {}) {
  std::vector<double> values = defaults.empty() ? std::vector<double>(model.dim(), std::nan("")) : defaults;
  for (const auto& [name, value] : parse_key_values(text, "--params"))
    values[model.parameter_index(name)] = parse_number(value, "--params " + name);
  for (int j = 0; j < model.dim(); ++j)
    if (std::isnan(values[j]))
      throw InputError(fmt::format("--params: missing parameter '{}' of model {}", model.parameters()[j].name, model.id()));
  return values;
}

/// A model from the command line: a registered model, optionally with parameter laws.
struct ResolvedModel {
  std::unique_ptr<LawModel> owned;  ///< set when laws or a fixture built a law model
  const Model* model = nullptr;
  std::vector<double> defaults;     ///< a fixture's published coefficients
};

ResolvedModel resolve_model(const std::string& id, const std::string& laws) {
  ResolvedModel r;
  r.model = &find_model(id);
  if (!laws.empty()) {
    r.owned = std::make_unique<LawModel>(*r.model, parse_laws(laws, "--laws"));
    r.model = r.owned.get();
  }
  return r;
}

ResolvedModel resolve_fixture(const std::string& name) {
  FixtureModel fx = make_fixture_model(find_fixture(name));
  ResolvedModel r;
  r.owned = std::move(fx.model);
  r.model = r.owned.get();
  r.defaults = std::move(fx.coefficients);
  return r;
}

}  // namespace

int models_command(const std::string& format) {
  check_format(format);
  // The record rule of a parameter, if any ("" otherwise): its default box when a record is fitted.
  auto rule_of = [](const Model& m, const ParameterInfo& p) {
    for (const RecordBoundsRule& r : m.record_bounds_rules())
      if (r.name == p.name) return r.describe();
    return std::string();
  };
  if (format == "json") {
    nlohmann::ordered_json models = nlohmann::ordered_json::object();
    for (const Model* m : all_models()) {
      nlohmann::ordered_json params = nlohmann::ordered_json::array();
      for (const auto& p : m->parameters()) {
        params.push_back({{"name", p.name}, {"unit", p.unit}, {"lower", p.lower}, {"upper", p.upper},
                          {"paper_unit", p.paper_unit}});
        if (const std::string rule = rule_of(*m, p); !rule.empty()) params.back()["record_rule"] = rule;
      }
      models[std::string(m->id())] = {{"citation", m->citation()}, {"law", m->law()}, {"parameters", params}};
    }
    std::cout << nlohmann::ordered_json{{"models", models}}.dump(2) << "\n";
    return 0;
  }
  for (const Model* m : all_models()) {
    Table t{std::string(m->id()), fmt::format("{} ({}): {}", m->id(), m->citation(), m->law()),
            {"parameter", "unit (SI)", "lower", "upper", "when fitting a record (F, V, X: its peak force, peak velocity, amplitude)"}, {}};
    for (const auto& p : m->parameters())
      t.rows.push_back({p.name, p.unit, format_number(p.lower), format_number(p.upper), rule_of(*m, p)});
    std::cout << t.to_markdown() << "\n";
  }
  return 0;
}

int simulate_command(const SimulateOptions& o) {
  if (o.model.empty() == o.fixture.empty()) throw InputError("simulate: give exactly one of --model M or --fixture NAME");
  if (o.sine.empty() == o.input.path.empty())
    throw InputError("simulate: give exactly one of --input FILE or --sine amp=...,freq=...,cycles=...,fs=...");
  if (!(o.noise_rel >= 0) || !std::isfinite(o.noise_rel))
    throw InputError(fmt::format("--noise-rel: expected a number >= 0, got {}", o.noise_rel));
  const ResolvedModel resolved = o.fixture.empty() ? resolve_model(o.model, o.laws) : resolve_fixture(o.fixture);
  const Model& model = *resolved.model;
  const std::vector<double> params = parse_params(model, o.params, resolved.defaults);
  Dataset data = o.sine.empty() ? load_record(o.input, false) : make_sine(parse_sine_option(o.sine));
  if (!o.sine.empty() && !o.input.set.empty()) set_operating(data, o.input.set);
  const Signals signals = prepare_signals(data);
  if (const auto* law = dynamic_cast<const LawModel*>(&model)) law->check_variables(signals);
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
    if (!file) throw StoreError(fmt::format("-o: cannot write '{}'", o.output));
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
  if (!o.report.empty()) {  // before the fit, not after it
    const auto folder = std::filesystem::absolute(o.report).parent_path();
    if (!std::filesystem::is_directory(folder))
      throw InputError(fmt::format("--report: the folder of '{}' does not exist", o.report));
  }
  const ResolvedModel resolved = resolve_model(o.model, o.laws);
  const Model& model = *resolved.model;
  const Metric metric = parse_metric(o.metric);
  const FitPlan plan = fit_plan(model, o.optimizer, o.population, o.iterations, o.runs);
  OptimizerSpec spec{plan.optimizer, plan.population, plan.iterations};
  for (const auto& [key, value] : parse_key_values(o.optimizer_settings, "--optimizer-settings")) spec.settings[key] = value;
  const OptimizerFactory factory = make_optimizer_factory(spec);
  if (o.paths.empty()) throw InputError("fit: give at least one --data FILE");
  std::vector<Signals> signals;
  std::string names;
  for (const auto& path : o.paths) {
    RecordOptions d = o.data;
    d.path = path;
    signals.push_back(prepare_signals(load_record(d, true)));
    if (const auto* law = dynamic_cast<const LawModel*>(&model)) law->check_variables(signals.back());
    names += (names.empty() ? "" : "+") + signals.back().name;
  }
  std::vector<const Signals*> data;
  for (const auto& s : signals) data.push_back(&s);
  Bounds bounds = default_bounds(model, data);
  if (!o.bounds.empty()) override_bounds(bounds, model, o.bounds);
  double samples = 0;
  for (const auto& s : signals) samples += static_cast<double>(s.size());

  IdentificationSettings settings;
  settings.runs = plan.runs;
  settings.seed = o.seed;
  settings.metric = metric;
  settings.task_key = task_key(model.id(), names, plan.optimizer);
  const Identification id = identify(model, data, bounds, factory, settings);

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
  const Convergence convergence = assess_convergence(id);
  const ConvergenceRule rule;
  const Identifiability identifiability = assess_identifiability(model, data, bounds, best.best_params);

  const auto paper = model.to_paper_units(best.best_params);
  Table params_table{"best_params", fmt::format("{} on {} — best of {} runs", model.id(), names, plan.runs),
          {"parameter", "value (SI)", "unit", "value (paper units)", "paper unit", "std. error (SI)", "rel. error",
           "identifiable"},
          {}};
  for (int i = 0; i < model.dim(); ++i) {
    std::string flags;
    for (const auto& f : identifiability.flags[i]) flags += (flags.empty() ? "" : "; ") + f;
    params_table.rows.push_back({params[i].name, format_number(best.best_params[i]), params[i].unit, format_number(paper[i]),
                      params[i].paper_unit, format_number(identifiability.std_error[i]),
                      format_number(identifiability.relative_error[i]), flags.empty() ? "yes" : "NO: " + flags});
  }
  Table metrics_table{"metrics", "Metrics of the best run", {"metric", "value"}, {}};
  for (int i = 0; i < kMetricCount; ++i)
    metrics_table.rows.push_back({std::string(metric_name(kAllMetrics[i])), format_number(best.best_metrics[i])});
  Table runs_table{"runs", fmt::format("{} over {} runs", o.metric, s.count), {"best", "worst", "mean", "std"},
          {{format_number(s.min), format_number(s.max), format_number(s.mean), format_number(s.std)}}};
  if (!o.report.empty()) {
    FitReport report{&model, plan.optimizer, std::string(DAMPBENCH_VERSION) + " (" + DAMPBENCH_BUILD_FLAGS + ")", metric, data, &id,
                     {params_table, metrics_table, runs_table}};
    write_fit_report(o.report, report);
  }
  if (o.format == "json") {
    nlohmann::ordered_json j;
    j["model"] = model.id();
    j["data"] = o.paths;
    j["samples"] = samples;
    j["metric"] = o.metric;
    j["optimizer"] = {{"name", plan.optimizer}, {"population", plan.population}, {"iterations", plan.iterations},
                      {"settings", spec.settings}};
    j["seed"] = o.seed;
    nlohmann::ordered_json bp = nlohmann::ordered_json::object();
    for (int i = 0; i < model.dim(); ++i) bp[params[i].name] = best.best_params[i];
    j["best_params"] = bp;
    nlohmann::ordered_json metrics = nlohmann::ordered_json::object();
    for (int i = 0; i < kMetricCount; ++i) metrics[std::string(metric_name(kAllMetrics[i]))] = json_number(best.best_metrics[i]);
    j["metrics"] = metrics;
    j["runs"] = {{"count", s.count}, {"best", json_number(s.min)}, {"worst", json_number(s.max)},
                 {"mean", json_number(s.mean)}, {"std", json_number(s.std)}};
    j["convergence"] = {{"converged", convergence.converged},
                        {"verdict", convergence.verdict()},
                        {"runs_agree", convergence.runs_agree},
                        {"stalled", convergence.stalled},
                        {"median_above_best_rel", json_number(convergence.median_above_best_rel)},
                        {"worst_above_best_rel", json_number(convergence.worst_above_best_rel)},
                        {"late_gain_rel", json_number(convergence.late_gain_rel)},
                        {"rule", {{"agree_rel", rule.agree_rel}, {"late_gain_rel", rule.late_gain_rel},
                                  {"late_fraction", rule.late_fraction}, {"abs_tol", rule.abs_tol}}}};
    // Best-so-far history of every run: [evaluations, value] where it improved, and at its end.
    nlohmann::ordered_json history = nlohmann::ordered_json::array();
    for (const RunResult& r : id.runs) {
      nlohmann::ordered_json points = nlohmann::ordered_json::array();
      for (const TracePoint& p : improvement_points(r)) points.push_back({p.evaluations, json_number(p.value)});
      history.push_back(points);
    }
    j["history"] = history;
    nlohmann::ordered_json ident = nlohmann::ordered_json::object();
    for (int i = 0; i < model.dim(); ++i)
      ident[params[i].name] = {{"std_error", json_number(identifiability.std_error[i])},
                               {"relative_error", json_number(identifiability.relative_error[i])},
                               {"flags", identifiability.flags[i]}};
    nlohmann::ordered_json corr = nlohmann::ordered_json::array();
    for (const auto& row : identifiability.correlation) {
      nlohmann::ordered_json r = nlohmann::ordered_json::array();
      for (double c : row) r.push_back(nlohmann::ordered_json(json_number(c)));
      corr.push_back(r);
    }
    j["identifiability"] = {{"identifiable", identifiability.all_identifiable()}, {"parameters", ident},
                            {"correlation", corr}};
    j["evaluations"] = evaluations;
    j["wall_time_s"] = id.wall_time_s;
    j["candidate_samples_per_s"] = rate;
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  if (!plan.why.empty()) std::cout << plan.why << "\n\n";
  std::cout << params_table.to_markdown() << "\n" << metrics_table.to_markdown() << "\n" << runs_table.to_markdown() << "\n";
  std::cout << fmt::format("{}: the median run ends {:.3g} % above the best, the worst {:.3g} %; the best run "
                           "improved {:.3g} % over its last {:.0f} % of evaluations{}{}\n",
                           convergence.converged ? "Converged" : "NOT CONVERGED (" + convergence.verdict() + ")",
                           100 * convergence.median_above_best_rel, 100 * convergence.worst_above_best_rel,
                           100 * convergence.late_gain_rel, 100 * rule.late_fraction,
                           convergence.best_at_local_optimum ? ", in its local stage, which ended at its optimum" : "",
                           convergence.converged ? "" : ": do not trust this fit; raise --runs, --pop or --iters");
  std::cout << fmt::format("{} evaluations × {} samples in {:.3f} s ({:.3g} candidate-samples/s)\n", evaluations,
                           samples, id.wall_time_s, rate);
  return 0;
}

int evaluate_command(const EvaluateOptions& o) {
  check_format(o.format);
  const ResolvedModel resolved = resolve_model(o.model, o.laws);
  const Model& model = *resolved.model;
  const std::vector<double> params = parse_params(model, o.params);
  if (o.paths.empty()) throw InputError("evaluate: give at least one --data FILE");
  CandidateBatch batch(model.dim(), 1);
  batch.set_candidate(0, params);
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  std::vector<std::string> cols{"record"};
  for (Metric m : kAllMetrics) cols.emplace_back(metric_name(m));
  Table t{"evaluate", fmt::format("{} at the given parameters", model.id()), cols, {}};
  for (const auto& path : o.paths) {
    RecordOptions d = o.data;
    d.path = path;
    const Signals s = prepare_signals(load_record(d, true));
    if (const auto* law = dynamic_cast<const LawModel*>(&model)) law->check_variables(s);
    std::vector<MetricRow> row(1);
    BatchEvaluator(model, s).evaluate_all(batch, row);
    std::vector<std::string> cells{s.name};
    for (int m = 0; m < kMetricCount; ++m) {
      j[path][std::string(metric_name(kAllMetrics[m]))] = json_number(row[0][m]);
      cells.push_back(format_number(row[0][m]));
    }
    t.rows.push_back(std::move(cells));
  }
  if (o.format == "json") std::cout << j.dump(2) << "\n";
  else std::cout << t.to_markdown();
  return 0;
}

int sensitivity_command(const SensitivityOptions& o) {
  check_format(o.format);
  const Model& model = find_model(o.model);
  const std::size_t cases = o.params.size();
  const auto& inputs = o.sines.empty() ? o.paths : o.sines;
  if (cases == 0) throw InputError("sensitivity: give --params (once per case)");
  if (o.sines.empty() == o.paths.empty())
    throw InputError("sensitivity: give --sine or --data (not both), once or once per --params");
  if (inputs.size() != 1 && inputs.size() != cases)
    throw InputError(fmt::format("sensitivity: {} --params but {} inputs; give one input or one per case", cases, inputs.size()));
  SensitivitySettings settings;
  settings.points = o.points;
  settings.range = o.range;
  settings.normalized = o.normalized;
  if (o.objective != "rms") settings.metric = parse_metric(o.objective);

  std::vector<std::vector<double>> values;
  std::vector<Sensitivity> results;
  for (std::size_t c = 0; c < cases; ++c) {
    const std::string& input = inputs[inputs.size() == 1 ? 0 : c];
    Dataset data;
    if (o.sines.empty()) {
      RecordOptions d = o.data;
      d.path = input;
      data = load_record(d, settings.metric.has_value());
    } else {
      data = make_sine(parse_sine_option(input));
    }
    values.push_back(parse_params(model, o.params[c]));
    results.push_back(differential_sensitivity(model, values.back(), prepare_signals(data), settings));
  }
  const auto params = model.parameters();
  std::vector<std::string> cols{"parameter"};
  for (std::size_t c = 0; c < cases; ++c) {
    cols.push_back(fmt::format("value ({})", c + 1));
    cols.push_back(fmt::format("S_z ({})", c + 1));
    cols.push_back(fmt::format("SP_z % ({})", c + 1));
  }
  cols.push_back("SP_z % (mean)");
  Table t{"sensitivity",
          fmt::format("Differential sensitivity of {} (crfd eqs. 4.1-4.3), f = {}, ±{:g} %, {} points{}", model.id(),
                      o.objective == "rms" ? "RMS of the model force" : o.objective, 100 * o.range, o.points,
                      o.normalized ? ", S_z·|z|" : ""),
          cols, {}};
  for (int j = 0; j < model.dim(); ++j) {
    std::vector<std::string> row{params[j].name};
    double mean = 0;
    for (std::size_t c = 0; c < cases; ++c) {
      row.push_back(format_number(values[c][j]));
      row.push_back(format_number(results[c].S[j]));
      row.push_back(fmt::format("{:.2f}", results[c].SP[j]));
      mean += results[c].SP[j] / static_cast<double>(cases);
    }
    row.push_back(fmt::format("{:.2f}", mean));
    t.rows.push_back(std::move(row));
  }
  if (o.format == "json") {
    nlohmann::ordered_json j;
    j["model"] = model.id();
    for (int p = 0; p < model.dim(); ++p) {
      double mean = 0;
      for (const auto& r : results) mean += r.SP[p] / static_cast<double>(cases);
      j["SP_mean_percent"][params[p].name] = mean;
    }
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << t.to_markdown();
  }
  return 0;
}

}  // namespace dampbench::cli
