// Optimizers ([optimizer] or [[optimizers]]) and the metrics each task optimizes.
#include <algorithm>

#include "engine/sweep/spec/reader.hpp"

namespace dampbench::sweep::spec_file {

namespace {

std::string setting_text(const Reader& r, const toml::node& v, const std::string& key) {
  if (v.is_string()) return std::string(*v.value<std::string>());
  if (v.is_integer()) return std::to_string(*v.value<std::int64_t>());
  if (v.is_floating_point()) return fmt::format("{}", *v.value<double>());
  if (v.is_boolean()) return *v.value<bool>() ? "true" : "false";
  r.fail(&v, key, "expected a string, number or boolean");
}

/// `budget`: "auto" or "fixed"; by default auto when the entry sets none of the budget's keys (as `fit` does).
void read_budget_kind(const Reader& r, const toml::table& t, const std::string& key, int part_runs, OptimizerEntry& o) {
  const bool fixed_given = t.contains("population") || t.contains("iterations") || t.contains("max_evaluations") ||
                           t.contains("target") || t.contains("stall_iterations");
  const auto kind = r.string(t, "budget", key);
  if (kind && *kind != "auto" && *kind != "fixed")
    r.fail(t.get("budget"), Reader::join(key, "budget"), fmt::format("expected \"auto\" or \"fixed\", got '{}'", *kind));
  o.auto_budget = kind ? *kind == "auto" : !fixed_given;
  o.max_total_evaluations = r.integer(t, "max_total_evaluations", key, 0, 1);
  if (t.contains("max_total_evaluations") && !o.auto_budget)
    r.fail(t.get("max_total_evaluations"), Reader::join(key, "max_total_evaluations"),
           "caps the automatic budget, and this entry's budget is fixed (it sets population, iterations or a stopping "
           "rule, or budget = \"fixed\"): add budget = \"auto\" or drop it");
  if (o.auto_budget && (o.runs > 0 ? o.runs : part_runs) < 2)
    r.fail(&t, key, "the automatic budget (no population, iterations or stopping rule given) needs runs >= 2, "
                    "since one run cannot show that runs agree: set runs, or budget = \"fixed\"");
}

OptimizerEntry read_optimizer(const Reader& r, const toml::table& t, const std::string& key, int part_runs) {
  r.only_keys(t, key, {"label", "name", "population", "iterations", "runs", "settings", "max_evaluations", "target",
                       "stall_iterations", "budget", "max_total_evaluations", "precision"});
  OptimizerEntry o;
  o.spec.name = r.string(t, "name", key).value_or("pso");
  o.label = r.string(t, "label", key).value_or(o.spec.name);
  o.spec.population = static_cast<int>(r.integer(t, "population", key, 50, 2));
  o.spec.iterations = static_cast<int>(r.integer(t, "iterations", key, 100, 1));
  o.runs = static_cast<int>(r.integer(t, "runs", key, 0, 1));
  o.budget.max_evaluations = r.integer(t, "max_evaluations", key, 0, 0);
  o.budget.stall_iterations = static_cast<int>(r.integer(t, "stall_iterations", key, 0, 0));
  if (auto target = r.number(t, "target", key)) o.budget.target = *target;
  read_budget_kind(r, t, key, part_runs, o);
  if (const auto precision = r.string(t, "precision", key)) {
    const auto p = search_precision_of(*precision);
    if (!p)
      r.fail(t.get("precision"), Reader::join(key, "precision"),
             fmt::format("expected \"double\" or \"mixed\" (the population search in float32 lanes), got '{}'", *precision));
    o.search_precision = *p;
  }
  if (const toml::node* s = t.get("settings")) {
    if (!s->is_table()) r.fail(s, Reader::join(key, "settings"), "expected a table of settings, e.g. { pc = 0.6 }");
    for (const auto& [k, v] : *s->as_table())
      o.spec.settings[std::string(k.str())] = setting_text(r, v, Reader::join(key, "settings." + std::string(k.str())));
  }
  r.check(&t, key, [&] { return make_optimizer_factory(o.spec); });
  return o;
}

}  // namespace

void read_optimizers(const Reader& r, const toml::table& root, PartSpec& part) {
  const toml::node* one = root.get("optimizer");
  const toml::node* many = root.get("optimizers");
  if (one && many) r.fail(many, "optimizers", "give either [optimizer] or [[optimizers]], not both");
  if (one) {
    if (!one->is_table()) r.fail(one, "optimizer", "expected a table [optimizer]");
    part.optimizers.push_back(read_optimizer(r, *one->as_table(), "optimizer", part.runs));
  } else if (many) {
    if (!many->is_array_of_tables() || many->as_array()->empty())
      r.fail(many, "optimizers", "expected one or more [[optimizers]] tables");
    const auto& a = *many->as_array();
    for (std::size_t i = 0; i < a.size(); ++i) {
      const std::string key = fmt::format("optimizers[{}]", i);
      OptimizerEntry o = read_optimizer(r, *a.get(i)->as_table(), key, part.runs);
      if (part.optimizer_index(o.label) >= 0)
        r.fail(a.get(i), key, fmt::format("optimizer label '{}' is used twice (give each a 'label')", o.label));
      part.optimizers.push_back(std::move(o));
    }
  } else {
    if (part.runs < 2)
      r.fail(root.get("runs"), "runs",
             "the default optimizer (pso with the automatic budget) needs runs >= 2, since one run cannot show that "
             "runs agree: set runs, or give an [optimizer] with a population");
    part.optimizers.push_back(OptimizerEntry{"pso", OptimizerSpec{}, Budget{}, 0, true, 0});
  }
  const toml::node* models = root.get("models");
  for (std::size_t i = 0; i < part.models.size(); ++i)
    for (const auto& label : part.models[i].optimizers)
      if (part.optimizer_index(label) < 0)
        r.fail(models->as_array()->get(i), fmt::format("models[{}].optimizers", i),
               fmt::format("no optimizer labelled '{}'", label));
}

void read_metrics(const Reader& r, const toml::table& root, PartSpec& part) {
  const toml::node* one = root.get("metric");
  const toml::node* many = root.get("metrics");
  if (one && many) r.fail(many, "metrics", "give either 'metric' or 'metrics', not both");
  const toml::node* n = one ? one : many;
  if (!n) return;
  const std::string key = one ? "metric" : "metrics";
  if (one && !one->is_string()) r.fail(one, key, "expected a metric name");
  part.metrics.clear();
  for (const auto& name : r.strings(*n, key)) {
    const Metric m = r.check(n, key, [&] { return parse_metric(name); });
    if (std::find(part.metrics.begin(), part.metrics.end(), m) != part.metrics.end())
      r.fail(n, key, fmt::format("metric '{}' is listed twice", name));
    part.metrics.push_back(m);
  }
  if (part.metrics.empty()) r.fail(n, key, "expected at least one metric");
}

}  // namespace dampbench::sweep::spec_file
