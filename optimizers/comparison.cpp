#include "optimizers/comparison.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"

namespace dampbench {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

int whole_setting(std::string_view entry, std::string_view key, const std::string& value) {
  const double v = parse_number(trim(value), fmt::format("--optimizer '{}': {}", entry, key));
  if (v != std::floor(v) || std::abs(v) > std::numeric_limits<int>::max())
    throw InputError(fmt::format("--optimizer '{}': {}: expected a whole number, got '{}'", entry, key, value));
  return static_cast<int>(v);
}

std::string cell(double v) { return std::isfinite(v) ? format_number(v) : (std::isnan(v) ? "nan" : "—"); }

/// The ga-sqp constraint of a spec (registry reading: a number, or off/none), nullopt for other optimizers.
std::optional<double> sqp_constraint(const OptimizerSpec& spec) {
  if (spec.name != "ga-sqp") return std::nullopt;
  const auto it = spec.settings.find("constraint");
  if (it == spec.settings.end()) return GaSqpSettings{}.constraint;
  const std::string_view t = trim(it->second);
  if (t == "off" || t == "none") return kInf;
  return parse_number(t, "ga-sqp: setting 'constraint'");
}

/// Each entry's optimizer factory, after the settings and the entries are checked (InputError naming the entry).
std::vector<OptimizerFactory> checked_factories(const std::vector<ComparisonEntry>& entries,
                                                const ComparisonSettings& settings) {
  if (entries.empty()) throw InputError("compare: give at least one --optimizer");
  if (settings.target && !std::isfinite(*settings.target))
    throw InputError(fmt::format("--target: expected a finite number, got {}", *settings.target));
  if (!(settings.success_tolerance >= 0) || !std::isfinite(settings.success_tolerance))
    throw InputError(fmt::format("compare: success tolerance must be a finite number >= 0, got {}", settings.success_tolerance));
  std::set<std::string> labels;
  std::vector<OptimizerFactory> factories;
  for (const ComparisonEntry& e : entries) {
    if (!labels.insert(e.label).second) throw InputError(fmt::format("--optimizer '{}' is given twice", e.label));
    try {
      factories.push_back(make_optimizer_factory(e.spec));
      (void)sqp_constraint(e.spec);
    } catch (const InputError& error) {
      throw InputError(fmt::format("--optimizer '{}': {}", e.label, error.what()));
    }
  }
  return factories;
}

}  // namespace

OptimizerSpec parse_optimizer_entry(std::string_view text, int default_population, int default_iterations) {
  const std::string_view entry = trim(text);
  OptimizerSpec spec;
  spec.population = default_population;
  spec.iterations = default_iterations;
  const std::size_t colon = entry.find(':');
  spec.name = std::string(trim(entry.substr(0, colon)));
  if (spec.name.empty()) throw InputError(fmt::format("--optimizer '{}': expected NAME or NAME:key=value,...", entry));
  if (colon == std::string_view::npos) return spec;
  const std::string option = fmt::format("--optimizer '{}'", entry);
  for (const auto& [key, value] : parse_key_values(entry.substr(colon + 1), option)) {
    if (key == "population") spec.population = whole_setting(entry, key, value);
    else if (key == "iterations") spec.iterations = whole_setting(entry, key, value);
    else spec.settings[key] = value;
  }
  return spec;
}

void completed_trace(const RunResult& run, std::vector<long long>& evaluations, std::vector<double>& values) {
  evaluations = run.trace_evaluations;
  values = run.trace;
  if (values.empty() || run.evaluations > evaluations.back()) {
    evaluations.push_back(run.evaluations);
    values.push_back(values.empty() ? run.best_value : std::min(values.back(), run.best_value));
  } else if (run.best_value < values.back()) {
    values.back() = run.best_value;
  }
}

Comparison compare_optimizers(const Model& model, const std::vector<const Signals*>& data, const Bounds& bounds,
                              const std::vector<ComparisonEntry>& entries, const ComparisonSettings& settings) {
  const std::vector<OptimizerFactory> factories = checked_factories(entries, settings);
  Comparison out;
  out.best_found = kInf;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    IdentificationSettings s = settings.identification;
    s.task_key = task_key(model.id(), settings.data_name, entries[i].label);
    Identification id = identify(model, data, bounds, factories[i], s);
    OptimizerComparison oc;
    oc.label = entries[i].label;
    oc.spec = entries[i].spec;
    oc.wall_time_s = id.wall_time_s;
    oc.runs = std::move(id.runs);
    for (const RunResult& r : oc.runs) out.best_found = std::min(out.best_found, r.best_value);
    out.optimizers.push_back(std::move(oc));
  }
  out.success_tolerance = settings.success_tolerance;
  out.success_threshold = out.best_found + settings.success_tolerance * std::abs(out.best_found);
  out.target_given = settings.target.has_value();
  out.target = settings.target.value_or(out.success_threshold);

  for (OptimizerComparison& oc : out.optimizers) {
    const int R = static_cast<int>(oc.runs.size());
    std::vector<double> values, to_target;
    std::vector<std::vector<long long>> evs(R);
    std::vector<std::vector<double>> trs(R);
    std::set<long long> grid;
    double evaluations = 0;
    oc.constraint = sqp_constraint(oc.spec);
    if (oc.constraint) oc.feasible_runs = 0;
    for (int r = 0; r < R; ++r) {
      const RunResult& run = oc.runs[r];
      values.push_back(run.best_value);
      evaluations += static_cast<double>(run.evaluations);
      oc.successes += run.best_value <= out.success_threshold ? 1 : 0;
      if (oc.constraint && run.best_value <= *oc.constraint) ++*oc.feasible_runs;
      completed_trace(run, evs[r], trs[r]);
      double reached = kInf;
      for (std::size_t k = 0; k < trs[r].size(); ++k)
        if (trs[r][k] <= out.target) {
          reached = static_cast<double>(evs[r][k]);
          break;
        }
      oc.reached_target += std::isfinite(reached) ? 1 : 0;
      to_target.push_back(reached);
      grid.insert(evs[r].begin(), evs[r].end());
    }
    oc.summary = summarize(values);
    oc.success_rate = R > 0 ? static_cast<double>(oc.successes) / R : 0;
    oc.mean_evaluations = R > 0 ? evaluations / R : 0;
    std::sort(to_target.begin(), to_target.end());
    oc.median_evaluations_to_target = sorted_quantile(to_target, 0.5);

    std::vector<std::size_t> at(R, 0);  // per run: trace points with evaluations ≤ the grid point
    std::vector<double> column(R);
    for (long long e : grid) {
      for (int r = 0; r < R; ++r) {
        while (at[r] < evs[r].size() && evs[r][at[r]] <= e) ++at[r];
        column[r] = at[r] == 0 ? kInf : trs[r][at[r] - 1];
      }
      std::sort(column.begin(), column.end());
      oc.curve.push_back({e, sorted_quantile(column, 0.25), sorted_quantile(column, 0.5), sorted_quantile(column, 0.75)});
    }
  }
  return out;
}

Table comparison_table(const Comparison& c, std::string_view metric) {
  Table t{"comparison",
          fmt::format("{} per optimizer; success: best ≤ {} (within {:g} % of the best found, {}); evaluations to "
                      "target {}{}: median over the runs (— when fewer than half reach it)",
                      metric, cell(c.success_threshold), 100 * c.success_tolerance, cell(c.best_found), cell(c.target),
                      c.target_given ? "" : " (default: the success threshold)"),
          {"optimizer", "runs", "best", "worst", "mean", "std", "success", "evals to target (median)", "reached",
           "evals/run (mean)", "feasible", "wall time s"},
          {}};
  for (const OptimizerComparison& o : c.optimizers) {
    const int R = static_cast<int>(o.runs.size());
    t.rows.push_back({o.label, std::to_string(R), cell(o.summary.min), cell(o.summary.max), cell(o.summary.mean),
                      cell(o.summary.std), fmt::format("{}/{} ({:.0f} %)", o.successes, R, 100 * o.success_rate),
                      cell(o.median_evaluations_to_target), fmt::format("{}/{}", o.reached_target, R),
                      format_number(o.mean_evaluations),
                      o.feasible_runs ? fmt::format("{}/{} (≤ {})", *o.feasible_runs, R, cell(*o.constraint)) : "",
                      fmt::format("{:.3f}", o.wall_time_s)});
  }
  return t;
}

std::string convergence_csv(const Comparison& c) {
  std::string out = "optimizer,evaluations,q25,median,q75\n";
  auto number = [](double v) { return std::isfinite(v) ? fmt::format("{:.17g}", v) : std::string(v > 0 ? "inf" : "nan"); };
  for (const OptimizerComparison& o : c.optimizers) {
    const bool quote = o.label.find_first_of(",\"") != std::string::npos;
    std::string label = o.label;
    if (quote) {
      std::string q = "\"";
      for (char ch : label) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
      label = q + "\"";
    }
    for (const CurvePoint& p : o.curve)
      out += fmt::format("{},{},{},{},{}\n", label, p.evaluations, number(p.q25), number(p.median), number(p.q75));
  }
  return out;
}

}  // namespace dampbench
