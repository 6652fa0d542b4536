// sensitivity: SP_z per parameter and condition, and their mean.
#include <fmt/format.h>

#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep::tables {

void sensitivity_tables(const Context& c, std::vector<Table>& out) {
  for (const Series& s : c.series()) {
    std::vector<const GroupRecord*> groups;
    for (const GroupRecord* g : s.groups)
      if (g->sensitivity) groups.push_back(g);
    if (groups.empty()) continue;
    std::vector<std::string> cols{"Parameter"};
    for (const GroupRecord* g : groups) cols.push_back(fmt::format("SP % ({})", c.label(*g)));
    cols.push_back("SP % (mean)");
    Table r = c.table("sensitivity" + c.suffix(s),
                        fmt::format("Differential sensitivity SP_z of the identified parameters (crfd eqs. 4.1-4.3) — {}",
                                    c.describe(s)),
                        cols);
    const auto params = c.model(s.model).parameters();
    for (std::size_t j = 0; j < params.size(); ++j) {
      std::vector<Cell> row{txt(params[j].name)};
      double mean = 0;
      for (const GroupRecord* g : groups) {
        const double v = g->sensitivity->SP.at(j);
        row.push_back({fmt::format("{:.2f}", v), v});
        mean += v / static_cast<double>(groups.size());
      }
      row.push_back({fmt::format("{:.2f}", mean), mean});
      r.rows.push_back(std::move(row));
    }
    out.push_back(std::move(r));
  }
}

}  // namespace dampbench::sweep::tables
