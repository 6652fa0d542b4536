// fvd: the fvd paper's Tables 3–14 (runs, param-stats and variability per series, numbered as the paper does), then
// the ranking.
#include <fmt/format.h>

#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep::tables {

void fvd_tables(const Context& c, std::vector<Table>& out) {
  const auto all = c.series();
  const int n = static_cast<int>(all.size());
  auto paper = [&](int number) { return n == 4 && c.t.paper.empty() ? fmt::format("fvd Table {}", number) : c.t.paper; };
  for (int i = 0; i < n; ++i) {
    const Series& s = all[static_cast<std::size_t>(i)];
    const int runs = s.groups.empty() ? 0 : s.groups[0]->runs;
    Table r = runs_table(c, s, fmt::format("table{:02}_{}{}", 3 + i, metric_name(s.metric), c.suffix(s)),
                          fmt::format("Table {}. {} over {} runs — {}", 3 + i, metric_name(s.metric), runs, c.describe(s)));
    r.columns[0] = "Test";
    r.paper = paper(3 + i);
    out.push_back(std::move(r));
  }
  for (int i = 0; i < n; ++i) {
    const Series& s = all[static_cast<std::size_t>(i)];
    if (Context::chose_laws(s)) continue;  // each group has its own parameters (the params table shows them)
    const int runs = s.groups.empty() ? 0 : s.groups[0]->runs;
    Table r = param_stats_table(c, s, fmt::format("table{:02}_params{}", 3 + n + i, c.suffix(s)),
                                 fmt::format("Table {}. Identified parameters over {} runs (paper units) — {}", 3 + n + i,
                                             runs, c.describe(s)));
    r.paper = paper(3 + n + i);
    out.push_back(std::move(r));
  }
  for (int i = 0; i < n; ++i) {
    const Series& s = all[static_cast<std::size_t>(i)];
    if (Context::chose_laws(s)) continue;
    Table r = variability_table(c, s, fmt::format("table{:02}_variability{}", 3 + 2 * n + i, c.suffix(s)),
                                 fmt::format("Table {}. Parameter variability across tests — {}", 3 + 2 * n + i, c.describe(s)));
    r.paper = paper(3 + 2 * n + i);
    out.push_back(std::move(r));
  }
  std::vector<Table> ranking;
  ranking_tables(c, ranking);
  for (auto& r : ranking) {
    r.paper = "";
    out.push_back(std::move(r));
  }
}

}  // namespace dampbench::sweep::tables
