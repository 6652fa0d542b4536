#include "engine/sweep/tables.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/common/error.hpp"
#include "engine/identification/convergence.hpp"
#include "engine/common/random.hpp"
#include "engine/common/statistics.hpp"
#include "engine/sweep/analysis.hpp"
#include "engine/common/table.hpp"

namespace dampbench::sweep {

std::vector<std::string> table_kinds() {
  return {"runs",    "param-stats", "variability", "ranking",   "fvd",      "params",   "errors",  "regression",
          "sensitivity", "ranksum", "bootstrap",   "runtime",  "failures", "overview"};
}

StoreResults::StoreResults(const Store& store) : header(store.header()) {
  GroupQuery q;
  q.traces = true;
  groups = store.groups(q);
  for (const auto& p : header.parts) {
    SpecOptions o;
    o.check_files = false;
    parts.push_back(std::move(parse_sweep(p.source, p.path, o).parts.at(0)));
  }
  models_.resize(header.parts.size());
  for (const auto& m : header.models) {
    ModelSpec s;
    s.name = m.name;
    s.model = m.model_id;
    s.fixture = m.fixture;
    s.laws = m.laws;
    models_[static_cast<std::size_t>(m.part)].push_back(resolve_model(s));
  }
}

const Model& StoreResults::model(int part, int m) const {
  return *models_.at(static_cast<std::size_t>(part)).at(static_cast<std::size_t>(m)).model;
}

namespace {

Cell num(double v) { return {format_number(v), v}; }
Cell txt(std::string s) { return {std::move(s), std::nullopt}; }
Cell none() { return {"-", std::nullopt}; }

std::string file_stem(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '_';
  return s;
}

/// Every group of one (split, model, optimizer, optimized metric), ordered by fit set.
struct Series {
  int split = 0, model = 0, optimizer = 0;
  Metric metric = Metric::of_abs;
  std::vector<const GroupRecord*> groups;
};

struct Context {
  const StoreResults& R;
  int part;
  const TableSpec& t;
  const PartSpec& spec;
  std::vector<const GroupRecord*> selected;
  bool many_models = false, many_optimizers = false, many_metrics = false, many_splits = false;

  Context(const StoreResults& results, int p, const TableSpec& request)
      : R(results), part(p), t(request), spec(results.parts.at(static_cast<std::size_t>(p))) {
    std::optional<Metric> metric;
    if (!t.metric.empty()) {
      const Metric m = parse_metric(t.metric);
      if (std::find(spec.metrics.begin(), spec.metrics.end(), m) != spec.metrics.end()) metric = m;
    }
    std::set<int> models, optimizers, splits;
    std::set<Metric> metrics;
    for (const auto& g : R.groups) {
      if (g.part != part || g.failed || g.run_results.empty()) continue;
      if (!t.splits.empty() && std::find(t.splits.begin(), t.splits.end(), split_name(g.split)) == t.splits.end()) continue;
      if (!t.models.empty() && std::find(t.models.begin(), t.models.end(), model_name(g.model)) == t.models.end()) continue;
      if (!t.optimizers.empty() &&
          std::find(t.optimizers.begin(), t.optimizers.end(), optimizer_label(g.optimizer)) == t.optimizers.end())
        continue;
      if (metric && g.metric != *metric) continue;
      // `where` picks conditions: the fit sets of a series, but the rows (fitted or predicted) of errors.
      if (!t.where.everything() && t.kind != "errors") {
        const auto& fs = fitset(g);
        if (std::none_of(fs.fit.begin(), fs.fit.end(), [&](int d) { return matches(t.where, d); })) continue;
      }
      selected.push_back(&g);
      models.insert(g.model);
      optimizers.insert(g.optimizer);
      splits.insert(g.split);
      metrics.insert(g.metric);
    }
    many_models = models.size() > 1;
    many_optimizers = optimizers.size() > 1;
    many_metrics = metrics.size() > 1;
    many_splits = splits.size() > 1;
  }

  [[nodiscard]] std::string model_name(int m) const { return R.header.models.at(static_cast<std::size_t>(R.header.model(part, m))).name; }
  [[nodiscard]] std::string optimizer_label(int o) const {
    return R.header.optimizers.at(static_cast<std::size_t>(R.header.optimizer(part, o))).label;
  }
  [[nodiscard]] std::string split_name(int s) const { return R.header.split_name(part, s); }
  [[nodiscard]] const StoreFitSet& fitset(const GroupRecord& g) const {
    return R.header.fitsets.at(static_cast<std::size_t>(R.header.fitset(part, g.split, g.fitset)));
  }
  [[nodiscard]] const StoreDataset& dataset(int d) const {
    return R.header.datasets.at(static_cast<std::size_t>(R.header.dataset(part, d)));
  }
  [[nodiscard]] bool matches(const Selection& s, int d) const { return s.matches(dataset(d).name, dataset(d).variables); }
  [[nodiscard]] const Model& model(int m) const { return R.model(part, m); }

  [[nodiscard]] std::vector<Series> series() const {
    std::map<std::tuple<int, int, int, int>, Series> by;
    for (const GroupRecord* g : selected) {
      Series& s = by[{g->split, g->model, g->optimizer, static_cast<int>(g->metric)}];
      s.split = g->split;
      s.model = g->model;
      s.optimizer = g->optimizer;
      s.metric = g->metric;
      s.groups.push_back(g);
    }
    std::vector<Series> out;
    for (auto& [k, s] : by) {
      std::sort(s.groups.begin(), s.groups.end(), [](auto* a, auto* b) { return a->fitset < b->fitset; });
      out.push_back(std::move(s));
    }
    return out;
  }

  /// "_model[_optimizer][_metric][_split]": the parts that tell this series from the others.
  [[nodiscard]] std::string suffix(const Series& s, bool with_model = true) const {
    std::string out = with_model ? "_" + model_name(s.model) : "";
    if (many_optimizers) out += "_" + optimizer_label(s.optimizer);
    if (many_metrics) out += "_" + std::string(metric_name(s.metric));
    if (many_splits) out += "_" + split_name(s.split);
    return file_stem(out);
  }
  [[nodiscard]] std::string describe(const Series& s, bool with_model = true) const {
    std::string out = with_model ? model_name(s.model) : "";
    auto add = [&](const std::string& x) { out += (out.empty() ? "" : ", ") + x; };
    if (many_optimizers || !with_model) add(optimizer_label(s.optimizer));
    if (many_metrics) add(std::string(metric_name(s.metric)));
    if (many_splits && !split_name(s.split).empty()) add("split " + split_name(s.split));
    return out;
  }
  [[nodiscard]] std::string label(const GroupRecord& g) const { return fitset(g).label; }
  [[nodiscard]] std::string title(std::string fallback) const { return t.title.empty() ? fallback : t.title; }

  /// A report; `id` starts with the kind, which the request's `name` replaces.
  [[nodiscard]] Report report(std::string id, std::string title_text, std::vector<std::string> columns) const {
    Report r;
    if (!t.name.empty() && id.starts_with(t.kind)) id = file_stem(t.name) + id.substr(t.kind.size());
    r.id = std::move(id);
    r.title = title(std::move(title_text));
    r.paper = t.paper;
    r.columns = std::move(columns);
    return r;
  }

  /// Parameter values in paper units of every run of a group.
  [[nodiscard]] std::vector<std::vector<double>> paper_params(const GroupRecord& g) const {
    std::vector<std::vector<double>> out;
    for (const auto& r : g.run_results) out.push_back(model(g.model).to_paper_units(r.params));
    return out;
  }
};

std::vector<double> best_values(const GroupRecord& g) {
  std::vector<double> v;
  for (const auto& r : g.run_results) v.push_back(r.best_value);
  return v;
}

/// Whether a group's runs converged (engine/identification/convergence.hpp), from its stored runs and traces.
Convergence group_convergence(const GroupRecord& g) {
  std::vector<RunHistory> runs;
  for (const auto& r : g.run_results) runs.push_back({r.best_value, r.trace, r.at_local_optimum});
  return assess_convergence(runs);
}

constexpr const char* kUnconvergedMark = "†";
constexpr const char* kUnconvergedNote =
    "† not converged: the runs disagree (median run > 2 % above the best), a single run cannot show agreement, or "
    "the best still improved by > 1 % in the last fifth of its budget (a hybrid whose local stage stopped at a local "
    "optimum is not asked to stall); raise runs, population or iterations "
    "before trusting it.";

Report runs_table(const Context& c, const Series& s, std::string id, std::string title) {
  Report r = c.report(std::move(id), std::move(title), {"Condition", "Mean", "Max", "Min", "Std", "Runs", "Converged"});
  for (const GroupRecord* g : s.groups) {
    const Summary x = summarize(best_values(*g));
    const Convergence conv = group_convergence(*g);
    r.rows.push_back({txt(c.label(*g)), num(x.mean), num(x.max), num(x.min), num(x.std), num(x.count),
                      txt(conv.converged ? "yes" : std::string(kUnconvergedMark) + " " + conv.verdict())});
    if (!conv.converged) r.note = kUnconvergedNote;
  }
  return r;
}

Report param_stats_table(const Context& c, const Series& s, std::string id, std::string title) {
  std::vector<std::string> cols{"Parameter"};
  for (const GroupRecord* g : s.groups) cols.push_back(c.label(*g));
  Report r = c.report(std::move(id), std::move(title), cols);
  const Model& model = c.model(s.model);
  const auto params = model.parameters();
  std::vector<std::vector<std::vector<double>>> values;  // group → run → parameter
  for (const GroupRecord* g : s.groups) values.push_back(c.paper_params(*g));
  for (int j = 0; j < model.dim(); ++j) {
    std::vector<Summary> per;
    for (const auto& runs : values) {
      std::vector<double> v;
      for (const auto& p : runs) v.push_back(p[static_cast<std::size_t>(j)]);
      per.push_back(summarize(v));
    }
    const std::pair<const char*, double Summary::*> stats[] = {
        {"mean", &Summary::mean}, {"max", &Summary::max}, {"min", &Summary::min}, {"std", &Summary::std}};
    for (const auto& [name, field] : stats) {
      std::vector<Cell> row{txt(fmt::format("{}({}) [{}]", params[j].name, name, params[j].paper_unit))};
      for (const Summary& x : per) row.push_back(num(x.*field));
      r.rows.push_back(std::move(row));
    }
  }
  return r;
}

Report variability_table(const Context& c, const Series& s, std::string id, std::string title) {
  Report r = c.report(std::move(id), std::move(title), {"Parameter", "p_mean", "delta_p", "delta_p/p_mean"});
  const Model& model = c.model(s.model);
  const auto params = model.parameters();
  std::vector<std::vector<std::vector<double>>> values;
  for (const GroupRecord* g : s.groups) values.push_back(c.paper_params(*g));
  for (int j = 0; j < model.dim(); ++j) {
    std::vector<double> means;
    for (const auto& runs : values) {
      std::vector<double> v;
      for (const auto& p : runs) v.push_back(p[static_cast<std::size_t>(j)]);
      means.push_back(summarize(v).mean);
    }
    const Summary x = summarize(means);
    const double delta = x.max - x.min;
    r.rows.push_back({txt(fmt::format("{} [{}]", params[j].name, params[j].paper_unit)), num(x.mean), num(delta),
                      x.mean != 0 ? num(delta / x.mean) : none()});
  }
  return r;
}

/// Series grouped by (split, metric) for tables with one column or row per model.
std::map<std::pair<int, int>, std::vector<Series>> by_split_metric(const std::vector<Series>& all) {
  std::map<std::pair<int, int>, std::vector<Series>> out;
  for (const auto& s : all) out[{s.split, static_cast<int>(s.metric)}].push_back(s);
  return out;
}

std::string split_metric_suffix(const Context& c, int split, Metric metric) {
  std::string out;
  if (c.many_metrics) out += "_" + std::string(metric_name(metric));
  if (c.many_splits) out += "_" + c.split_name(split);
  return file_stem(out);
}

std::string series_column(const Context& c, const Series& s) {
  return c.many_optimizers ? fmt::format("{} ({})", c.model_name(s.model), c.optimizer_label(s.optimizer))
                           : c.model_name(s.model);
}

void ranking_tables(const Context& c, std::vector<Report>& out) {
  for (const auto& [key, list] : by_split_metric(c.series())) {
    // Columns: every fit set of the split, in order.
    std::map<int, std::string> fitsets;
    for (const auto& s : list)
      for (const GroupRecord* g : s.groups) fitsets[g->fitset] = c.label(*g);
    std::vector<std::string> cols{"Model"};
    for (const auto& [f, label] : fitsets) cols.push_back(label);
    cols.push_back("mean of best");
    const Metric metric = static_cast<Metric>(key.second);
    Report r = c.report("ranking" + split_metric_suffix(c, key.first, metric),
                        fmt::format("Best {} per model and condition (lower is better)", metric_name(metric)), cols);
    for (const auto& s : list) {
      std::vector<Cell> row{txt(series_column(c, s))};
      double sum = 0;
      int n = 0;
      for (const auto& entry : fitsets) {
        const int f = entry.first;  // (a structured binding cannot be captured by clang 14, the fuzz build's compiler)
        const auto it = std::find_if(s.groups.begin(), s.groups.end(), [&](auto* g) { return g->fitset == f; });
        if (it == s.groups.end()) {
          row.push_back(none());
          continue;
        }
        const double best = (*it)->run_results[static_cast<std::size_t>((*it)->best_run())].best_value;
        sum += best;
        ++n;
        row.push_back(num(best));
      }
      row.push_back(n ? num(sum / n) : none());
      r.rows.push_back(std::move(row));
    }
    out.push_back(std::move(r));
  }
}

void fvd_tables(const Context& c, std::vector<Report>& out) {
  const auto all = c.series();
  const int n = static_cast<int>(all.size());
  auto paper = [&](int number) { return n == 4 && c.t.paper.empty() ? fmt::format("fvd Table {}", number) : c.t.paper; };
  for (int i = 0; i < n; ++i) {
    const Series& s = all[static_cast<std::size_t>(i)];
    const int runs = s.groups.empty() ? 0 : s.groups[0]->runs;
    Report r = runs_table(c, s, fmt::format("table{:02}_{}{}", 3 + i, metric_name(s.metric), c.suffix(s)),
                          fmt::format("Table {}. {} over {} runs — {}", 3 + i, metric_name(s.metric), runs, c.describe(s)));
    r.columns[0] = "Test";
    r.paper = paper(3 + i);
    out.push_back(std::move(r));
  }
  for (int i = 0; i < n; ++i) {
    const Series& s = all[static_cast<std::size_t>(i)];
    const int runs = s.groups.empty() ? 0 : s.groups[0]->runs;
    Report r = param_stats_table(c, s, fmt::format("table{:02}_params{}", 3 + n + i, c.suffix(s)),
                                 fmt::format("Table {}. Identified parameters over {} runs (paper units) — {}", 3 + n + i,
                                             runs, c.describe(s)));
    r.paper = paper(3 + n + i);
    out.push_back(std::move(r));
  }
  for (int i = 0; i < n; ++i) {
    const Series& s = all[static_cast<std::size_t>(i)];
    Report r = variability_table(c, s, fmt::format("table{:02}_variability{}", 3 + 2 * n + i, c.suffix(s)),
                                 fmt::format("Table {}. Parameter variability across tests — {}", 3 + 2 * n + i, c.describe(s)));
    r.paper = paper(3 + 2 * n + i);
    out.push_back(std::move(r));
  }
  std::vector<Report> ranking;
  ranking_tables(c, ranking);
  for (auto& r : ranking) {
    r.paper = "";
    out.push_back(std::move(r));
  }
}

constexpr const char* kUndeterminedMark = "‡";
constexpr const char* kAtBoundMark = "⊥";
constexpr const char* kIdentifiabilityNote =
    "‡ not identifiable from this record: relative standard error > 100 % or |correlation| > 0.99 with another "
    "parameter (sigma^2 (J^T J)^-1 at the best run; the fit fixes a combination, not this value). ⊥ at a bound of "
    "the box (the optimum may lie outside it).";

/// The identifiability marks of parameter j at a group's best run: ‡, ⊥, both or none.
std::string identifiability_mark(const GroupRecord& g, int j) {
  if (!g.identifiability) return "";
  return std::string(g.identifiability->determined(j) ? "" : kUndeterminedMark) + (g.identifiability->at_bound(j) ? kAtBoundMark : "");
}

void params_tables(const Context& c, std::vector<Report>& out) {
  for (const Series& s : c.series()) {
    const Model& model = c.model(s.model);
    std::vector<std::string> cols{"Parameter", "unit"};
    for (const GroupRecord* g : s.groups) cols.push_back(c.label(*g));
    Report r = c.report("params" + c.suffix(s), fmt::format("Identified parameters of the best run per condition — {}", c.describe(s)),
                        cols);
    std::vector<std::string> rel_cols{"Parameter"};
    for (const GroupRecord* g : s.groups) rel_cols.push_back(c.label(*g));
    Report rel = c.report("params" + c.suffix(s) + "_se",
                          fmt::format("Relative standard error (%) of the identified parameters, best run per condition — {}",
                                      c.describe(s)),
                          rel_cols);
    rel.paper = "";
    std::vector<std::vector<double>> best;
    for (const GroupRecord* g : s.groups)
      best.push_back(model.to_paper_units(g->run_results[static_cast<std::size_t>(g->best_run())].params));
    const auto params = model.parameters();
    bool marked = false;
    for (int j = 0; j < model.dim(); ++j) {
      std::vector<Cell> row{txt(params[j].name), txt(params[j].paper_unit)}, rel_row{txt(params[j].name)};
      for (std::size_t k = 0; k < best.size(); ++k) {
        const GroupRecord& g = *s.groups[k];
        const double v = best[k][static_cast<std::size_t>(j)];
        const std::string mark = identifiability_mark(g, j);
        marked |= !mark.empty();
        row.push_back({format_number(v) + mark, v});
        if (!g.identifiability) {
          rel_row.push_back(none());
          continue;
        }
        const double e = 100 * g.identifiability->relative_error[static_cast<std::size_t>(j)];
        std::string flags;
        for (const auto& f : g.identifiability->flags[static_cast<std::size_t>(j)]) flags += (flags.empty() ? " (" : "; ") + f;
        rel_row.push_back({format_number(e) + flags + (flags.empty() ? "" : ")"), e});
      }
      r.rows.push_back(std::move(row));
      rel.rows.push_back(std::move(rel_row));
    }
    std::vector<Cell> row{txt(std::string(metric_name(s.metric))), txt("")};
    for (const GroupRecord* g : s.groups) row.push_back(num(g->run_results[static_cast<std::size_t>(g->best_run())].best_value));
    r.rows.push_back(std::move(row));
    if (marked) r.note = kIdentifiabilityNote;
    rel.note = "Standard errors from sigma^2 (J^T J)^-1 at the best run's parameters over the fit records "
               "(engine/identification/identifiability.hpp); > 100 % means the record does not determine the parameter.";
    out.push_back(std::move(r));
    out.push_back(std::move(rel));
  }
}

std::optional<double> dataset_value(const Context& c, const GroupRecord& g, int d, bool predicted, int metric) {
  const auto& fs = c.fitset(g);
  const int best = g.run_results[static_cast<std::size_t>(g.best_run())].run;
  if (!predicted && fs.fit.size() == 1 && fs.fit[0] == d)
    return g.run_results[static_cast<std::size_t>(g.best_run())].metrics[static_cast<std::size_t>(metric)];
  for (const auto& x : g.dataset_metrics)
    if (x.run == best && x.dataset == d && x.predicted == predicted) return x.metrics[static_cast<std::size_t>(metric)];
  return std::nullopt;
}

void errors_tables(const Context& c, std::vector<Report>& out) {
  // One table per optimized metric; a column per series (model, and optimizer or split when they vary).
  std::map<int, std::vector<Series>> by_metric;
  for (const auto& s : c.series()) by_metric[static_cast<int>(s.metric)].push_back(s);
  for (const auto& [key, list] : by_metric) {
    const Metric optimized = static_cast<Metric>(key);
    const Metric shown = c.t.metric.empty() ? optimized : parse_metric(c.t.metric);
    const int m = static_cast<int>(shown);
    std::vector<std::string> cols{"Dataset"};
    for (const auto& s : list) {
      std::string col = series_column(c, s);
      if (c.many_splits && !c.split_name(s.split).empty()) col += " [" + c.split_name(s.split) + "]";
      cols.push_back(std::move(col));
    }
    Report r = c.report("errors" + (c.many_metrics ? file_stem("_" + std::string(metric_name(optimized))) : std::string()),
                        fmt::format("{} of each model's best run per dataset{}", metric_name(shown),
                                    shown != optimized ? fmt::format(" (runs optimized {})", metric_name(optimized)) : ""),
                        cols);
    const bool fits = c.t.role != "predict", predictions = c.t.role != "fit";
    std::set<int> datasets;
    for (const auto& s : list)
      for (const GroupRecord* g : s.groups) {
        const auto& fs = c.fitset(*g);
        if (fits) datasets.insert(fs.fit.begin(), fs.fit.end());
        if (predictions) datasets.insert(fs.predict.begin(), fs.predict.end());
      }
    std::vector<double> sums(list.size(), 0);
    std::vector<int> counts(list.size(), 0);
    bool averaged = false, predicted_any = false, unconverged_any = false;
    for (int d : datasets) {
      if (!c.t.where.everything() && !c.matches(c.t.where, d)) continue;
      std::vector<Cell> row{txt(c.dataset(d).name)};
      bool any = false;
      for (std::size_t i = 0; i < list.size(); ++i) {
        // The fit value when the series fits this dataset, else the (mean) prediction of it.
        std::optional<double> value;
        bool predicted = false, unconverged = false;
        for (const bool role : {false, true}) {
          if (value || (role ? !predictions : !fits)) continue;
          double sum = 0;
          int n = 0;
          bool all_converged = true;
          for (const GroupRecord* g : list[i].groups)
            if (auto v = dataset_value(c, *g, d, role, m)) {
              sum += *v;
              ++n;
              all_converged &= group_convergence(*g).converged;
            }
          if (n > 0) {
            value = sum / n;
            predicted = role;
            averaged |= n > 1;
            unconverged = !all_converged;
          }
        }
        if (!value) {
          row.push_back(none());
          continue;
        }
        any = true;
        predicted_any |= predicted;
        row.push_back({format_number(*value) + (predicted ? "*" : "") + (unconverged ? kUnconvergedMark : ""), *value});
        unconverged_any |= unconverged;
        sums[i] += *value;
        ++counts[i];
      }
      if (any) r.rows.push_back(std::move(row));
    }
    if (r.rows.size() > 1) {
      std::vector<Cell> row{txt("mean")};
      for (std::size_t i = 0; i < list.size(); ++i) row.push_back(counts[i] ? num(sums[i] / counts[i]) : none());
      r.rows.push_back(std::move(row));
    }
    std::string note;
    if (predicted_any) note = "* predicted: the dataset was not fitted, the fit of other conditions was evaluated on it.";
    if (averaged) note += std::string(note.empty() ? "" : " ") + "A dataset predicted by several fits shows the mean over them.";
    if (unconverged_any) note += std::string(note.empty() ? "" : " ") + kUnconvergedNote;
    r.note = note;
    out.push_back(std::move(r));
  }
}

RegressionResult law_regression(const Context& c, const RegressionSpec& reg) {
  RegressionResult out;
  out.spec = &reg;
  const int model_index = c.spec.model_index(reg.model);
  const int split = reg.split.empty() ? -1 : c.spec.split_index(reg.split);
  const int optimizer = reg.optimizer.empty() ? -1 : c.spec.optimizer_index(reg.optimizer);
  // The lowest metric per condition among the per-condition fits of the model.
  std::map<int, const GroupRecord*> per_dataset;
  for (const auto& g : c.R.groups) {
    if (g.part != c.part || g.failed || g.run_results.empty() || g.model != model_index) continue;
    if ((split >= 0 && g.split != split) || (optimizer >= 0 && g.optimizer != optimizer)) continue;
    const auto& fs = c.fitset(g);
    if (fs.fit.size() != 1 || !c.matches(reg.where, fs.fit[0])) continue;
    const GroupRecord*& slot = per_dataset[fs.fit[0]];
    auto best = [](const GroupRecord* x) { return x->run_results[static_cast<std::size_t>(x->best_run())].best_value; };
    if (!slot || best(&g) < best(slot)) slot = &g;
  }
  std::vector<std::vector<double>> params;
  std::vector<const GroupRecord*> groups;
  for (const auto& [d, g] : per_dataset) {
    out.variables.push_back(c.dataset(d).variables);
    params.push_back(g->run_results[static_cast<std::size_t>(g->best_run())].params);
    out.conditions.push_back(c.dataset(d).name);
    groups.push_back(g);
  }
  try {
    const Model& model = c.model(model_index);
    for (const auto& [name, law] : parse_laws(reg.laws, "laws")) {
      const int j = model.parameter_index(name);
      std::vector<double> y;
      for (const auto& p : params) y.push_back(p[static_cast<std::size_t>(j)]);
      LawRegression l{name, law, fit_law(law, name, out.variables, y), {}};
      // Conditions where parameter j was not determined by its record (‡ in the params table).
      for (const GroupRecord* g : groups) l.undetermined.push_back(g->identifiability && !g->identifiability->determined(j));
      out.laws.push_back(std::move(l));
    }
  } catch (const InputError& e) {
    out.laws.clear();
    out.error = e.what();
  }
  return out;
}

void regression_tables(const Context& c, std::vector<Report>& out) {
  for (const RegressionSpec& reg : c.spec.regressions) {
    if (!c.t.models.empty() && std::find(c.t.models.begin(), c.t.models.end(), reg.model) == c.t.models.end()) continue;
    const RegressionResult result = law_regression(c, reg);
    const std::string id = file_stem("regression_" + reg.name);
    Report coef = c.report(id, fmt::format("Regression of {}'s identified parameters on operating variables ({} conditions)",
                                           reg.model, result.conditions.size()),
                           {"Parameter", "Law", "Coefficient", "Value", "R2", "RMS residual", "Not identifiable at"});
    coef.paper = reg.paper.empty() ? c.t.paper : reg.paper;
    std::vector<std::string> res_cols{"Condition"};
    bool any_undetermined = false;
    for (const LawRegression& l : result.laws) {
      const RegressionFit& f = l.fit;
      const auto count = std::count(l.undetermined.begin(), l.undetermined.end(), true);
      any_undetermined |= count > 0;
      const std::string where = count == 0 ? "none" : fmt::format("{} {} of {}", kUndeterminedMark, count, l.undetermined.size());
      for (std::size_t k = 0; k < f.names.size(); ++k)
        coef.rows.push_back({txt(k == 0 ? l.parameter : ""), txt(k == 0 ? l.law.text() : ""), txt(f.names[k]), num(f.coefficients[k]),
                             k == 0 ? num(f.r2) : txt(""), k == 0 ? num(f.rms_residual) : txt(""), txt(k == 0 ? where : "")});
      for (const char* s : {"observed", "fitted", "residual"}) res_cols.push_back(fmt::format("{} {}", l.parameter, s));
    }
    coef.note = !result.error.empty() ? result.error
                                      : fmt::format("Least squares on the best run per condition{}{} (SI units).{}",
                                                    reg.split.empty() ? "" : ", split " + reg.split,
                                                    reg.optimizer.empty() ? "" : ", optimizer " + reg.optimizer,
                                                    any_undetermined ? fmt::format(
                                                        " Not identifiable at: conditions whose record does not determine the "
                                                        "parameter ({} in the residuals; relative standard error > 100 % or "
                                                        "|correlation| > 0.99): the regression fits their noise too.",
                                                        kUndeterminedMark)
                                                                     : "");
    out.push_back(std::move(coef));
    if (result.laws.empty()) continue;
    Report res = c.report(id + "_residuals", fmt::format("Residuals of the regression of {} per condition", reg.model), res_cols);
    res.paper = "";
    for (std::size_t i = 0; i < result.conditions.size(); ++i) {
      std::vector<Cell> row{txt(result.conditions[i])};
      for (const LawRegression& l : result.laws) {
        const RegressionFit& f = l.fit;
        const double observed = f.fitted[i] + f.residuals[i];
        row.push_back({format_number(observed) + (l.undetermined[i] ? kUndeterminedMark : ""), observed});
        row.push_back(num(f.fitted[i]));
        row.push_back(num(f.residuals[i]));
      }
      res.rows.push_back(std::move(row));
    }
    out.push_back(std::move(res));
  }
}

void sensitivity_tables(const Context& c, std::vector<Report>& out) {
  for (const Series& s : c.series()) {
    std::vector<const GroupRecord*> groups;
    for (const GroupRecord* g : s.groups)
      if (g->sensitivity) groups.push_back(g);
    if (groups.empty()) continue;
    std::vector<std::string> cols{"Parameter"};
    for (const GroupRecord* g : groups) cols.push_back(fmt::format("SP % ({})", c.label(*g)));
    cols.push_back("SP % (mean)");
    Report r = c.report("sensitivity" + c.suffix(s),
                        fmt::format("Differential sensitivity SP_z of the identified parameters (crfd eqs. 4.1-4.3) — {}",
                                    c.describe(s)),
                        cols);
    const auto params = c.model(s.model).parameters();
    for (std::size_t j = 0; j < params.size(); ++j) {
      std::vector<Cell> row{txt(params[j].name)};
      double mean = 0;
      for (const GroupRecord* g : groups) {
        const double v = g->sensitivity->SP.at(j);
        row.push_back({fmt::format("{:.2f}", v), v});
        mean += v / static_cast<double>(groups.size());
      }
      row.push_back({fmt::format("{:.2f}", mean), mean});
      r.rows.push_back(std::move(row));
    }
    out.push_back(std::move(r));
  }
}

void ranksum_tables(const Context& c, std::vector<Report>& out) {
  // (split, metric, fitset) → (model, optimizer) → group
  std::map<std::tuple<int, int, int>, std::map<std::pair<int, int>, const GroupRecord*>> problems;
  for (const GroupRecord* g : c.selected) problems[{g->split, static_cast<int>(g->metric), g->fitset}][{g->model, g->optimizer}] = g;
  Report opt = c.report("ranksum_optimizers", "Mann-Whitney rank-sum tests between optimizers (best metric of each run)",
                        {"Condition", "Model", "A", "B", "median A", "median B", "U", "p (two-sided)"});
  Report mod = c.report("ranksum_models", "Mann-Whitney rank-sum tests between models (best metric of each run)",
                        {"Condition", "Optimizer", "A", "B", "median A", "median B", "U", "p (two-sided)"});
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  };
  for (const auto& [key, cell] : problems) {
    const auto& [split, metric, fitset] = key;
    std::string cond = c.label(*cell.begin()->second);
    if (c.many_metrics) cond += " (" + std::string(metric_name(static_cast<Metric>(metric))) + ")";
    if (c.many_splits) cond += " [" + c.split_name(split) + "]";
    for (auto a = cell.begin(); a != cell.end(); ++a)
      for (auto b = std::next(a); b != cell.end(); ++b) {
        const bool same_model = a->first.first == b->first.first, same_optimizer = a->first.second == b->first.second;
        if (!same_model && !same_optimizer) continue;
        const auto va = best_values(*a->second), vb = best_values(*b->second);
        const RankSum t = mann_whitney(va, vb);
        std::vector<Cell> row{txt(cond),
                              txt(same_model ? c.model_name(a->first.first) : c.optimizer_label(a->first.second)),
                              txt(same_model ? c.optimizer_label(a->first.second) : c.model_name(a->first.first)),
                              txt(same_model ? c.optimizer_label(b->first.second) : c.model_name(b->first.first)),
                              num(median(va)), num(median(vb)), num(t.U), num(t.p)};
        (same_model ? opt : mod).rows.push_back(std::move(row));
      }
  }
  opt.note = mod.note = "Exact p-values without ties and up to 25 runs a side, else the normal approximation.";
  if (!opt.rows.empty()) out.push_back(std::move(opt));
  if (!mod.rows.empty()) out.push_back(std::move(mod));
}

void bootstrap_tables(const Context& c, std::vector<Report>& out) {
  for (const Series& s : c.series()) {
    Report r = c.report("bootstrap" + c.suffix(s),
                        fmt::format("Mean {} with its bootstrap 95 % interval (2000 resamples) — {}", metric_name(s.metric),
                                    c.describe(s)),
                        {"Condition", "Mean", "lower 95 %", "upper 95 %", "Runs"});
    for (const GroupRecord* g : s.groups) {
      const auto v = best_values(*g);
      const Interval ci = bootstrap_mean(v, hash_key({g->task_key, hash_name("bootstrap")}));
      r.rows.push_back({txt(c.label(*g)), num(ci.mean), num(ci.lower), num(ci.upper), num(static_cast<double>(v.size()))});
    }
    out.push_back(std::move(r));
  }
}

void runtime_tables(const Context& c, std::vector<Report>& out) {
  for (const auto& [key, list] : by_split_metric(c.series())) {
    const auto suffix = split_metric_suffix(c, key.first, static_cast<Metric>(key.second));
    std::set<int> optimizers;
    std::map<std::pair<int, int>, std::map<int, const GroupRecord*>> problems;  // (fitset, model) → optimizer → group
    for (const auto& s : list)
      for (const GroupRecord* g : s.groups) {
        problems[{g->fitset, g->model}][g->optimizer] = g;
        optimizers.insert(g->optimizer);
      }
    std::vector<std::string> cols{"Condition", "Model", "target"};
    for (int o : optimizers) {
      cols.push_back(fmt::format("{} success", c.optimizer_label(o)));
      cols.push_back(fmt::format("{} ERT", c.optimizer_label(o)));
    }
    Report r = c.report("runtime" + suffix,
                        fmt::format("Fixed-target runtime: evaluations to reach best known + {:g} × |best known| "
                                    "(ERT = evaluations spent / successes)",
                                    c.t.target_rel),
                        cols);
    std::map<int, std::vector<long long>> runtimes;  // optimizer → every (problem, run) runtime
    long long max_evals = 1, min_evals = std::numeric_limits<long long>::max();
    for (const auto& [pk, by_opt] : problems) {
      double best = std::numeric_limits<double>::infinity();
      for (const auto& [o, g] : by_opt)
        for (const auto& run : g->run_results) best = std::min(best, run.best_value);
      const double target = best + std::max(c.t.target_rel * std::fabs(best), 1e-12);
      std::vector<Cell> row{txt(c.label(*by_opt.begin()->second)), txt(c.model_name(pk.second)), num(target)};
      for (int o : optimizers) {
        const auto it = by_opt.find(o);
        if (it == by_opt.end()) {
          row.push_back(none());
          row.push_back(none());
          continue;
        }
        std::vector<long long> hits, spent;
        for (const auto& run : it->second->run_results) {
          hits.push_back(std::isfinite(target) ? first_hit(run.trace, target) : -1);
          spent.push_back(run.evaluations);
          max_evals = std::max(max_evals, run.evaluations);
          if (!run.trace.empty()) min_evals = std::min(min_evals, run.trace.front().evaluations);
          runtimes[o].push_back(hits.back());
        }
        const TargetRuntime t = expected_runtime(hits, spent);
        row.push_back(txt(fmt::format("{}/{}", t.successes, t.runs)));
        row.back().value = static_cast<double>(t.successes) / std::max(1, t.runs);
        row.push_back(num(t.ert));
      }
      r.rows.push_back(std::move(row));
    }
    out.push_back(std::move(r));
    // ECDF over conditions and runs, at budgets spaced evenly in log scale.
    if (min_evals == std::numeric_limits<long long>::max()) min_evals = 1;
    std::vector<double> budgets;
    const int points = 12;
    for (int i = 0; i < points; ++i)
      budgets.push_back(std::round(static_cast<double>(min_evals) *
                                   std::pow(static_cast<double>(max_evals) / static_cast<double>(min_evals),
                                            static_cast<double>(i) / (points - 1))));
    std::vector<std::string> ecols{"evaluations"};
    for (int o : optimizers) ecols.push_back(c.optimizer_label(o));
    Report e = c.report("runtime_ecdf" + suffix, "ECDF of fixed-target runtimes over conditions and runs", ecols);
    e.paper = "";
    std::map<int, std::vector<double>> fractions;
    for (int o : optimizers) fractions[o] = ecdf(runtimes[o], budgets);
    for (std::size_t i = 0; i < budgets.size(); ++i) {
      std::vector<Cell> row{num(budgets[i])};
      for (int o : optimizers) row.push_back(num(fractions[o][i]));
      e.rows.push_back(std::move(row));
    }
    out.push_back(std::move(e));
  }
}

void failures_table(const Context& c, std::vector<Report>& out) {
  Report r = c.report("failures", "Failed task groups and datasets that did not load", {"What", "Message"});
  for (const auto& g : c.R.groups) {
    if (g.part != c.part || !g.failed) continue;
    r.rows.push_back({txt(fmt::format("{} on {}, {}, {}", c.model_name(g.model), c.fitset(g).label,
                                      c.optimizer_label(g.optimizer), metric_name(g.metric))),
                      txt(g.message)});
  }
  for (int d = 0;; ++d) {
    const int k = c.R.header.dataset(c.part, d);
    if (k < 0) break;
    const auto& ds = c.R.header.datasets[static_cast<std::size_t>(k)];
    if (!ds.error.empty()) r.rows.push_back({txt("dataset " + ds.name), txt(ds.error)});
  }
  if (r.rows.empty()) r.note = "No failures.";
  out.push_back(std::move(r));
}

void overview_table(const Context& c, std::vector<Report>& out) {
  long long groups = 0, failed = 0, tasks = 0, evaluations = 0, expected = 0, expected_tasks = 0;
  double wall = 0, cs = 0;
  for (const auto& g : c.R.groups) {
    if (g.part != c.part) continue;
    ++groups;
    failed += g.failed;
    tasks += g.runs;
    evaluations += g.evaluations;
    wall += g.wall_time_s;
    cs += g.candidate_samples;
  }
  expected = c.R.header.groups;
  expected_tasks = c.R.header.tasks;
  Report r = c.report("overview", "Sweep overview — " + c.spec.name, {"Quantity", "Value"});
  r.rows = {{txt("task groups stored"), num(static_cast<double>(groups))},
            {txt("tasks (runs) stored"), num(static_cast<double>(tasks))},
            {txt("failed task groups"), num(static_cast<double>(failed))},
            {txt("evaluations"), num(static_cast<double>(evaluations))},
            {txt("candidate-samples"), num(cs)},
            {txt("group wall time, summed [s]"), num(wall)},
            {txt("candidate-samples/s (per group)"), wall > 0 ? num(cs / wall) : none()}};
  r.note = fmt::format("The whole sweep has {} task groups and {} tasks over {} part(s).", expected, expected_tasks,
                       c.R.part_count());
  out.push_back(std::move(r));
}

}  // namespace

std::vector<Report> make_tables(const StoreResults& results, int part, const TableSpec& t) {
  const Context c(results, part, t);
  std::vector<Report> out;
  const std::string& k = t.kind;
  if (k == "fvd") {
    fvd_tables(c, out);
  } else if (k == "runs" || k == "param-stats" || k == "variability") {
    for (const Series& s : c.series()) {
      const int runs = s.groups.empty() ? 0 : s.groups[0]->runs;
      if (k == "runs")
        out.push_back(runs_table(c, s, "runs" + c.suffix(s),
                                 fmt::format("{} over {} runs per condition — {}", metric_name(s.metric), runs, c.describe(s))));
      else if (k == "param-stats")
        out.push_back(param_stats_table(c, s, "param-stats" + c.suffix(s),
                                        fmt::format("Identified parameters over {} runs (paper units) — {}", runs, c.describe(s))));
      else
        out.push_back(variability_table(c, s, "variability" + c.suffix(s),
                                        fmt::format("Parameter variability across conditions — {}", c.describe(s))));
    }
  } else if (k == "ranking") {
    ranking_tables(c, out);
  } else if (k == "params") {
    params_tables(c, out);
  } else if (k == "errors") {
    errors_tables(c, out);
  } else if (k == "regression") {
    regression_tables(c, out);
  } else if (k == "sensitivity") {
    sensitivity_tables(c, out);
  } else if (k == "ranksum") {
    ranksum_tables(c, out);
  } else if (k == "bootstrap") {
    bootstrap_tables(c, out);
  } else if (k == "runtime") {
    runtime_tables(c, out);
  } else if (k == "failures") {
    failures_table(c, out);
  } else if (k == "overview") {
    overview_table(c, out);
  } else {
    const auto kinds = table_kinds();
    std::string known;
    for (const auto& x : kinds) known += (known.empty() ? "" : ", ") + x;
    throw InputError(fmt::format("--kind: unknown table kind '{}' (known: {}, sweep)", k, known));
  }
  // Ids must be unique within a part: several [[tables]] of one kind get a running number.
  return out;
}

std::vector<RegressionResult> law_regressions(const StoreResults& results, int part) {
  const TableSpec everything;
  const Context c(results, part, everything);
  std::vector<RegressionResult> out;
  for (const RegressionSpec& reg : c.spec.regressions) out.push_back(law_regression(c, reg));
  return out;
}

std::vector<Report> sweep_tables(const StoreResults& results, int part) {
  const PartSpec& spec = results.parts.at(static_cast<std::size_t>(part));
  std::vector<Report> out;
  bool regression = false;
  std::map<std::string, int> seen;
  for (const TableSpec& t : spec.tables) {
    regression |= t.kind == "regression";
    for (Report& r : make_tables(results, part, t)) {
      if (const int n = seen[r.id]++; n > 0) r.id += fmt::format("_{}", n + 1);
      out.push_back(std::move(r));
    }
  }
  if (!regression && !spec.regressions.empty()) {
    TableSpec t;
    t.kind = "regression";
    for (Report& r : make_tables(results, part, t)) out.push_back(std::move(r));
  }
  const bool failures = std::any_of(results.groups.begin(), results.groups.end(),
                                    [&](const GroupRecord& g) { return g.part == part && g.failed; }) ||
                        std::any_of(results.header.datasets.begin(), results.header.datasets.end(),
                                    [&](const StoreDataset& d) { return d.part == part && !d.error.empty(); });
  if (failures && std::none_of(spec.tables.begin(), spec.tables.end(), [](const TableSpec& t) { return t.kind == "failures"; })) {
    TableSpec t;
    t.kind = "failures";
    for (Report& r : make_tables(results, part, t)) out.push_back(std::move(r));
  }
  return out;
}

namespace {

Table plain(const Report& r) {
  Table t{r.id, r.title, r.columns, {}};
  for (const auto& row : r.rows) {
    std::vector<std::string> cells;
    for (const auto& c : row) cells.push_back(c.text);
    t.rows.push_back(std::move(cells));
  }
  return t;
}

std::string latex_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': case '%': case '$': case '#': case '_': case '{': case '}': out += '\\'; out += c; break;
      case '~': out += "\\textasciitilde{}"; break;
      case '^': out += "\\textasciicircum{}"; break;
      case '\\': out += "\\textbackslash{}"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace

std::string to_markdown(const Report& r) {
  std::string out = plain(r).to_markdown();
  if (!r.note.empty()) out += "\n" + r.note + "\n";
  return out;
}

std::string to_csv(const Report& r) { return plain(r).to_csv(); }

std::string to_latex(const Report& r) {
  std::string out = "\\begin{table}[htbp]\n\\centering\n";
  out += "\\caption{" + latex_escape(r.title) + "}\n\\label{tab:" + latex_escape(r.id) + "}\n";
  out += "\\begin{tabular}{l" + std::string(r.columns.empty() ? 0 : r.columns.size() - 1, 'r') + "}\n\\hline\n";
  auto line = [&](const std::vector<std::string>& cells) {
    std::string s;
    for (std::size_t i = 0; i < cells.size(); ++i) s += (i ? " & " : "") + latex_escape(cells[i]);
    return s + " \\\\\n";
  };
  out += line(r.columns) + "\\hline\n";
  for (const auto& row : r.rows) {
    std::vector<std::string> cells;
    for (const auto& c : row) cells.push_back(c.text);
    out += line(cells);
  }
  out += "\\hline\n\\end{tabular}\n";
  if (!r.note.empty()) out += "\\par\\footnotesize " + latex_escape(r.note) + "\n";
  out += "\\end{table}\n";
  return out;
}

std::string to_json(const std::vector<Report>& reports) {
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  for (const auto& r : reports) {
    nlohmann::ordered_json t;
    t["id"] = r.id;
    t["title"] = r.title;
    t["paper"] = r.paper;
    t["note"] = r.note;
    t["columns"] = r.columns;
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const auto& row : r.rows) {
      nlohmann::ordered_json cells = nlohmann::ordered_json::array();
      for (const auto& c : row) {
        if (c.value && std::isfinite(*c.value)) cells.push_back(*c.value);
        else if (c.value) cells.push_back(std::isnan(*c.value) ? "nan" : (*c.value > 0 ? "inf" : "-inf"));
        else cells.push_back(c.text);
      }
      rows.push_back(std::move(cells));
    }
    t["rows"] = std::move(rows);
    all.push_back(std::move(t));
  }
  return nlohmann::ordered_json{{"tables", all}}.dump(2) + "\n";
}

std::string format_reports(const std::vector<Report>& reports, const std::string& format) {
  if (format == "json") return to_json(reports);
  std::string out;
  for (const auto& r : reports) {
    if (format == "md") out += to_markdown(r) + "\n";
    else if (format == "csv") out += (reports.size() > 1 ? "# " + r.id + ": " + r.title + "\n" : "") + to_csv(r) + (reports.size() > 1 ? "\n" : "");
    else if (format == "latex") out += to_latex(r) + "\n";
    else throw InputError(fmt::format("--format: expected md, csv, latex or json, got '{}'", format));
  }
  if (reports.empty() && format != "md" && format != "csv" && format != "latex")
    throw InputError(fmt::format("--format: expected md, csv, latex or json, got '{}'", format));
  return out;
}

}  // namespace dampbench::sweep
