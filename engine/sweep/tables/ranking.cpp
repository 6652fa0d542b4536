// ranking: the best metric per model and condition, and its mean over the conditions.
#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep::tables {

void ranking_tables(const Context& c, std::vector<Table>& out) {
  for (const auto& [key, list] : by_split_metric(c.series())) {
    // Columns: every fit set of the split, in order.
    std::map<int, std::string> fitsets;
    for (const auto& s : list)
      for (const GroupRecord* g : s.groups) fitsets[g->fitset] = c.label(*g);
    std::vector<std::string> cols{"Model"};
    for (const auto& [f, label] : fitsets) cols.push_back(label);
    cols.push_back("mean of best");
    const Metric metric = static_cast<Metric>(key.second);
    Table r = c.table("ranking" + split_metric_suffix(c, key.first, metric),
                        fmt::format("Best {} per model and condition (lower is better)", metric_name(metric)), cols);
    for (const auto& s : list) {
      std::vector<Cell> row{txt(series_column(c, s))};
      double sum = 0;
      int n = 0;
      for (const auto& entry : fitsets) {
        const int f = entry.first;  // (a structured binding cannot be captured by clang 14, the sanitizer build's compiler)
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

}  // namespace dampbench::sweep::tables
