// ranksum: Mann–Whitney p-values between optimizers (same model and condition) and between models.
#include <algorithm>
#include <map>
#include <tuple>

#include <fmt/format.h>

#include "engine/sweep/analysis.hpp"
#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep::tables {

void ranksum_tables(const Context& c, std::vector<Table>& out) {
  // (split, metric, fitset) → (model, optimizer) → group
  std::map<std::tuple<int, int, int>, std::map<std::pair<int, int>, const GroupRecord*>> problems;
  for (const GroupRecord* g : c.selected) problems[{g->split, static_cast<int>(g->metric), g->fitset}][{g->model, g->optimizer}] = g;
  Table opt = c.table("ranksum_optimizers", "Mann-Whitney rank-sum tests between optimizers (best metric of each run)",
                        {"Condition", "Model", "A", "B", "median A", "median B", "U", "p (two-sided)"});
  Table mod = c.table("ranksum_models", "Mann-Whitney rank-sum tests between models (best metric of each run)",
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

}  // namespace dampbench::sweep::tables
