// bootstrap: the bootstrap 95 % interval of the mean metric per condition.
#include <fmt/format.h>

#include "engine/common/random.hpp"
#include "engine/sweep/analysis.hpp"
#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep::tables {

void bootstrap_tables(const Context& c, std::vector<Table>& out) {
  for (const Series& s : c.series()) {
    Table r = c.table("bootstrap" + c.suffix(s),
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

}  // namespace dampbench::sweep::tables
