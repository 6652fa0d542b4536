// runtime: fixed-target runtime (success rate and expected running time per optimizer and problem), and the ECDF of
// runtimes over conditions and runs.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include <fmt/format.h>

#include "engine/sweep/analysis.hpp"
#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep::tables {

void runtime_tables(const Context& c, std::vector<Table>& out) {
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
    Table r = c.table("runtime" + suffix,
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
    Table e = c.table("runtime_ecdf" + suffix, "ECDF of fixed-target runtimes over conditions and runs", ecols);
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

}  // namespace dampbench::sweep::tables
