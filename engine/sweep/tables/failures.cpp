// failures: failed task groups and datasets that did not load, with their messages.
#include <fmt/format.h>

#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep::tables {

void failures_table(const Context& c, std::vector<Table>& out) {
  Table r = c.table("failures", "Failed task groups and datasets that did not load", {"What", "Message"});
  for (const auto& g : c.R.groups) {
    if (g.part != c.part || !g.failed) continue;
    r.rows.push_back({txt(fmt::format("{} on {}, {}, {}", c.model_name(g.model), c.fitset(g).label,
                                      c.optimizer_label(g.optimizer), metric_name(g.metric))),
                      txt(g.message)});
  }
  for (int d = 0;; ++d) {
    const int k = c.R.header.dataset(c.part, d);
    if (k < 0) break;
    const auto& ds = c.R.header.datasets[static_cast<std::size_t>(k)];
    if (!ds.error.empty()) r.rows.push_back({txt("dataset " + ds.name), txt(ds.error)});
  }
  if (r.rows.empty()) r.note = "No failures.";
  out.push_back(std::move(r));
}

}  // namespace dampbench::sweep::tables
