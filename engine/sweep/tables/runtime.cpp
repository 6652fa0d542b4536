// runtime: fixed-target runtime (success rate and expected running time per optimizer and problem, in evaluations
// and in seconds), and the ECDF of runtimes over conditions and runs.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include <fmt/format.h>

#include "engine/sweep/analysis.hpp"
#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep::tables {
namespace {

using ByOptimizer = std::map<int, const GroupRecord*>;

/// Wall seconds per evaluation of a group: the wall time of its lockstep runs over the evaluations they spent.
/// NaN when the group spent none or its time is not known, so that no seconds are made up.
double seconds_per_evaluation(const GroupRecord& g) {
  if (g.evaluations <= 0 || !(g.wall_time_s > 0)) return std::numeric_limits<double>::quiet_NaN();
  return g.wall_time_s / static_cast<double>(g.evaluations);
}

/// Every (problem, run) runtime per optimizer (−1: the run missed the target), and the range of evaluations the
/// ECDF spans: from the earliest first trace point to the largest run.
struct Runtimes {
  std::map<int, std::vector<long long>> of;
  long long max_evals = 1, min_evals = std::numeric_limits<long long>::max();
};

/// The success, ERT and ERT-seconds cells of one optimizer's group on one problem; records its runtimes.
void ert_cells(const GroupRecord& g, int optimizer, double target, Runtimes& rt, std::vector<Cell>& row) {
  std::vector<long long> hits, spent;
  for (const auto& run : g.run_results) {
    hits.push_back(std::isfinite(target) ? first_hit(run.trace, target) : -1);
    spent.push_back(run.evaluations);
    rt.max_evals = std::max(rt.max_evals, run.evaluations);
    if (!run.trace.empty()) rt.min_evals = std::min(rt.min_evals, run.trace.front().evaluations);
    rt.of[optimizer].push_back(hits.back());
  }
  const TargetRuntime t = expected_runtime(hits, spent);
  row.push_back(txt(fmt::format("{}/{}", t.successes, t.runs)));
  row.back().value = static_cast<double>(t.successes) / std::max(1, t.runs);
  row.push_back(num(t.ert));
  const double per_evaluation = seconds_per_evaluation(g);
  row.push_back(std::isnan(per_evaluation) ? none() : num(t.ert * per_evaluation));
}

/// One row per problem (fit set, model): its target from the best known, then each optimizer's cells.
Table ert_table(const Context& c, const std::string& suffix, const std::string& head, const std::set<int>& optimizers,
                const std::map<std::pair<int, int>, ByOptimizer>& problems, Runtimes& rt) {
  std::vector<std::string> cols{"Condition", "Model", "target"};
  for (int o : optimizers) {
    cols.push_back(fmt::format("{} success", c.optimizer_label(o)));
    cols.push_back(fmt::format("{} ERT", c.optimizer_label(o)));
    cols.push_back(fmt::format("{} ERT s", c.optimizer_label(o)));
  }
  Table r = c.table("runtime" + suffix,
                    fmt::format("{}Fixed-target runtime: evaluations to reach best known + {:g} × |best known| (best known: "
                                "the lowest value of any run of the optimizers in this table; ERT = evaluations spent by "
                                "all runs, restarts included, until the target or their end / successes). ERT s = ERT × "
                                "the group's wall seconds per evaluation as measured in this sweep: they depend on the "
                                "machine, its threads and the groups run beside it, so compare them within one store only",
                                head, c.t.target_rel),
                    cols);
  for (const auto& [pk, by_opt] : problems) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& [o, g] : by_opt)
      for (const auto& run : g->run_results) best = std::min(best, run.best_value);
    const double target = best + std::max(c.t.target_rel * std::fabs(best), 1e-12);
    std::vector<Cell> row{txt(c.label(*by_opt.begin()->second)), txt(c.model_name(pk.second)), num(target)};
    for (int o : optimizers) {
      const auto it = by_opt.find(o);
      if (it == by_opt.end())
        row.insert(row.end(), {none(), none(), none()});
      else
        ert_cells(*it->second, o, target, rt, row);
    }
    r.rows.push_back(std::move(row));
  }
  return r;
}

/// The ECDF over conditions and runs, at budgets spaced evenly in log scale.
Table ecdf_table(const Context& c, const std::string& suffix, const std::string& head, const std::set<int>& optimizers,
                 Runtimes& rt) {
  if (rt.min_evals == std::numeric_limits<long long>::max()) rt.min_evals = 1;
  std::vector<double> budgets;
  const int points = 12;
  const auto lo = static_cast<double>(rt.min_evals), hi = static_cast<double>(rt.max_evals);
  for (int i = 0; i < points; ++i)
    budgets.push_back(std::round(lo * std::pow(hi / lo, static_cast<double>(i) / (points - 1))));
  std::vector<std::string> ecols{"evaluations"};
  for (int o : optimizers) ecols.push_back(c.optimizer_label(o));
  Table e = c.table("runtime_ecdf" + suffix,
                    fmt::format("{}ECDF of fixed-target runtimes over conditions and runs (target: best known + {:g} × "
                                "|best known|)",
                                head, c.t.target_rel),
                    ecols);
  e.paper = "";
  std::map<int, std::vector<double>> fractions;
  for (int o : optimizers) fractions[o] = ecdf(rt.of[o], budgets);
  for (std::size_t i = 0; i < budgets.size(); ++i) {
    std::vector<Cell> row{num(budgets[i])};
    for (int o : optimizers) row.push_back(num(fractions[o][i]));
    e.rows.push_back(std::move(row));
  }
  return e;
}

}  // namespace

void runtime_tables(const Context& c, std::vector<Table>& out) {
  for (const auto& [key, list] : by_split_metric(c.series())) {
    const auto metric = static_cast<Metric>(key.second);
    const auto suffix = split_metric_suffix(c, key.first, metric);
    const auto head = split_metric_head(c, key.first, metric);
    std::set<int> optimizers;
    std::map<std::pair<int, int>, ByOptimizer> problems;  // (fitset, model) → optimizer → group
    for (const auto& s : list)
      for (const GroupRecord* g : s.groups) {
        problems[{g->fitset, g->model}][g->optimizer] = g;
        optimizers.insert(g->optimizer);
      }
    Runtimes rt;
    out.push_back(ert_table(c, suffix, head, optimizers, problems, rt));
    out.push_back(ecdf_table(c, suffix, head, optimizers, rt));
  }
}

}  // namespace dampbench::sweep::tables
