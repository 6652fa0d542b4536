// runs: repeated-run statistics of the metric per condition, with the convergence verdict.
#include <fmt/format.h>

#include "engine/common/statistics.hpp"
#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep::tables {

Table runs_table(const Context& c, const Series& s, std::string id, std::string title) {
  Table r = c.table(std::move(id), std::move(title), {"Condition", "Mean", "Max", "Min", "Std", "Runs", "Converged"});
  for (const GroupRecord* g : s.groups) {
    const Summary x = summarize(best_values(*g));
    const Convergence conv = group_convergence(*g);
    r.rows.push_back({txt(c.label(*g)), num(x.mean), num(x.max), num(x.min), num(x.std), num(x.count),
                      txt(conv.converged ? "yes" : std::string(kUnconvergedMark) + " " + conv.verdict())});
    if (!conv.converged) r.note = kUnconvergedNote;
  }
  return r;
}

void runs_tables(const Context& c, std::vector<Table>& out) {
  for (const Series& s : c.series()) {
    const int runs = s.groups.empty() ? 0 : s.groups[0]->runs;
    out.push_back(runs_table(c, s, "runs" + c.suffix(s),
                             fmt::format("{} over {} runs per condition — {}", metric_name(s.metric), runs, c.describe(s))));
  }
}

}  // namespace dampbench::sweep::tables
