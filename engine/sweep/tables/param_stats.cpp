// param-stats: each parameter's mean, max, min and std over the runs per condition, in paper units.
#include <fmt/format.h>

#include "engine/common/statistics.hpp"
#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep::tables {

Table param_stats_table(const Context& c, const Series& s, std::string id, std::string title) {
  std::vector<std::string> cols{"Parameter"};
  for (const GroupRecord* g : s.groups) cols.push_back(c.label(*g));
  Table r = c.table(std::move(id), std::move(title), cols);
  const Model& model = c.model(s.model);
  const auto params = model.parameters();
  const auto summaries = c.parameter_summaries(s);
  for (int j = 0; j < model.dim(); ++j) {
    const std::vector<Summary>& per = summaries[static_cast<std::size_t>(j)];
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

void param_stats_tables(const Context& c, std::vector<Table>& out) {
  for (const Series& s : c.series()) {
    if (Context::chose_laws(s)) continue;  // the groups' parameters differ: the params table shows each group's
    const int runs = s.groups.empty() ? 0 : s.groups[0]->runs;
    out.push_back(param_stats_table(c, s, "param-stats" + c.suffix(s),
                                    fmt::format("Identified parameters over {} runs (paper units) — {}", runs, c.describe(s))));
  }
}

}  // namespace dampbench::sweep::tables
