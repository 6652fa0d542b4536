// variability: per parameter, the mean over conditions of the per-condition mean, its range and relative range.
#include <fmt/format.h>

#include "engine/common/statistics.hpp"
#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep::tables {

Table variability_table(const Context& c, const Series& s, std::string id, std::string title) {
  Table r = c.table(std::move(id), std::move(title), {"Parameter", "p_mean", "delta_p", "delta_p/p_mean"});
  const Model& model = c.model(s.model);
  const auto params = model.parameters();
  const auto summaries = c.parameter_summaries(s);
  for (int j = 0; j < model.dim(); ++j) {
    std::vector<double> means;
    for (const Summary& x : summaries[static_cast<std::size_t>(j)]) means.push_back(x.mean);
    const Summary x = summarize(means);
    const double delta = x.max - x.min;
    r.rows.push_back({txt(fmt::format("{} [{}]", params[j].name, params[j].paper_unit)), num(x.mean), num(delta),
                      x.mean != 0 ? num(delta / x.mean) : none()});
  }
  return r;
}

void variability_tables(const Context& c, std::vector<Table>& out) {
  for (const Series& s : c.series())
    if (!Context::chose_laws(s))  // a statistic per parameter needs the same parameters in every group
      out.push_back(variability_table(c, s, "variability" + c.suffix(s),
                                      fmt::format("Parameter variability across conditions — {}", c.describe(s))));
}

}  // namespace dampbench::sweep::tables
