#include "engine/sweep/tables/context.hpp"

#include <algorithm>
#include <cctype>
#include <optional>
#include <set>
#include <tuple>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/fit/auto_budget.hpp"

namespace dampbench::sweep::tables {

std::string file_stem(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '_';
  return s;
}

Context::Context(const StoreResults& results, int p, const TableSpec& request)
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
    // `where` picks conditions: the fit sets of a series, or the rows (fitted or predicted) of a kind that says so.
    if (!t.where.everything() && !where_picks_rows(t.kind)) {
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

std::vector<Series> Context::series() const {
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

std::string Context::suffix(const Series& s, bool with_model) const {
  std::string out = with_model ? "_" + model_name(s.model) : "";
  if (many_optimizers) out += "_" + optimizer_label(s.optimizer);
  if (many_metrics) out += "_" + std::string(metric_name(s.metric));
  if (many_splits) out += "_" + split_name(s.split);
  return file_stem(out);
}

std::string Context::describe(const Series& s, bool with_model) const {
  std::string out = with_model ? model_name(s.model) : "";
  auto add = [&](const std::string& x) { out += (out.empty() ? "" : ", ") + x; };
  if (many_optimizers || !with_model) add(optimizer_label(s.optimizer));
  if (many_metrics) add(std::string(metric_name(s.metric)));
  if (many_splits && !split_name(s.split).empty()) add("split " + split_name(s.split));
  return out;
}

Table Context::table(std::string id, std::string title_text, std::vector<std::string> columns) const {
  Table r;
  if (!t.name.empty() && id.starts_with(t.kind)) id = file_stem(t.name) + id.substr(t.kind.size());
  r.id = std::move(id);
  r.title = title(std::move(title_text));
  r.paper = t.paper;
  r.columns = std::move(columns);
  return r;
}

std::vector<std::vector<double>> Context::paper_params(const GroupRecord& g) const {
  std::vector<std::vector<double>> out;
  for (const auto& r : g.run_results) out.push_back(model(g).to_paper_units(r.params));
  return out;
}

std::vector<std::vector<Summary>> Context::parameter_summaries(const Series& s) const {
  if (chose_laws(s))  // each group's parameters are its own law model's coefficients
    throw InputError(fmt::format("{}: its groups chose their own laws (laws = \"auto\"), so their parameters differ: "
                                 "the params table shows each group's",
                                 describe(s)));
  std::vector<std::vector<std::vector<double>>> values;  // group → run → parameter
  for (const GroupRecord* g : s.groups) values.push_back(paper_params(*g));
  std::vector<std::vector<Summary>> out(static_cast<std::size_t>(model(s.model).dim()));
  for (std::size_t j = 0; j < out.size(); ++j)
    for (const auto& runs : values) {
      std::vector<double> v;
      for (const auto& p : runs) v.push_back(p[j]);
      out[j].push_back(summarize(v));
    }
  return out;
}

std::vector<double> best_values(const GroupRecord& g) {
  std::vector<double> v;
  for (const auto& r : g.run_results) v.push_back(r.best_value);
  return v;
}

std::optional<double> dataset_value(const Context& c, const GroupRecord& g, int d, bool predicted, int metric) {
  const auto& fs = c.fitset(g);
  const auto& best = g.run_results[static_cast<std::size_t>(g.best_run())];
  if (!predicted && fs.fit.size() == 1 && fs.fit[0] == d) return best.metrics[static_cast<std::size_t>(metric)];
  for (const auto& x : g.dataset_metrics)
    if (x.run == best.run && x.dataset == d && x.predicted == predicted) return x.metrics[static_cast<std::size_t>(metric)];
  return std::nullopt;
}

std::set<int> series_datasets(const Context& c, const std::vector<Series>& list, bool fits, bool predictions) {
  std::set<int> datasets;
  for (const auto& s : list)
    for (const GroupRecord* g : s.groups) {
      const auto& fs = c.fitset(*g);
      if (fits) datasets.insert(fs.fit.begin(), fs.fit.end());
      if (predictions) datasets.insert(fs.predict.begin(), fs.predict.end());
    }
  return datasets;
}

SeriesValue series_value(const Context& c, const Series& s, int d, int metric, bool fits, bool predictions) {
  SeriesValue out;
  for (const bool role : {false, true}) {
    if (out.value || (role ? !predictions : !fits)) continue;
    double sum = 0;
    int n = 0;
    bool all_converged = true;
    for (const GroupRecord* g : s.groups)
      if (auto v = dataset_value(c, *g, d, role, metric)) {
        sum += *v;
        ++n;
        all_converged &= group_convergence(*g).converged;
      }
    if (n > 0) {
      out.value = sum / n;
      out.predicted = role;
      out.averaged = n > 1;
      out.unconverged = !all_converged;
    }
  }
  return out;
}

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

std::string split_metric_head(const Context& c, int split, Metric metric) {
  std::string head;
  if (c.many_splits) head = fmt::format("Split {}", c.split_name(split));
  if (c.many_metrics) head += fmt::format("{}{}", head.empty() ? "" : ", ", metric_name(metric));
  return head.empty() ? head : head + ": ";
}

std::string series_column(const Context& c, const Series& s) {
  return c.many_optimizers ? fmt::format("{} ({})", c.model_name(s.model), c.optimizer_label(s.optimizer))
                           : c.model_name(s.model);
}

}  // namespace dampbench::sweep::tables

namespace dampbench::sweep {

Convergence group_convergence(const GroupRecord& g) {
  std::vector<RunHistory> runs;
  for (const auto& r : g.run_results) runs.push_back({r.best_value, r.trace, r.at_local_optimum});
  return assess_convergence(runs, {}, !g.failed && stopped_before_converging(g.message));
}

}  // namespace dampbench::sweep
