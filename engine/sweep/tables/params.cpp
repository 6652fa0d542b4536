// params: the identified parameters of the best run per condition in paper units with their identifiability marks,
// then their relative standard errors.
#include <algorithm>

#include <fmt/format.h>

#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep::tables {
namespace {

constexpr const char* kIdentifiabilityNote =
    "‡ not identifiable from this record: relative standard error > 100 % or |correlation| > 0.99 with another "
    "parameter (sigma^2 (J^T J)^-1 at the best run; the fit fixes a combination, not this value). ⊥ at a bound of "
    "the box (the optimum may lie outside it).";

/// The identifiability marks of parameter j at a group's best run: ‡, ⊥, both or none.
std::string identifiability_mark(const GroupRecord& g, int j) {
  if (!g.identifiability) return "";
  return std::string(g.identifiability->determined(j) ? "" : kUndeterminedMark) + (g.identifiability->at_bound(j) ? kAtBoundMark : "");
}

/// The laws of a series' groups, each once, in order of first appearance: one block of rows per laws ("" for a series
/// of one model; several when its groups chose different laws, whose coefficients mean different things).
std::vector<std::string> law_blocks(const Series& s) {
  std::vector<std::string> blocks;
  for (const GroupRecord* g : s.groups)
    if (std::find(blocks.begin(), blocks.end(), g->laws) == blocks.end()) blocks.push_back(g->laws);
  return blocks;
}

}  // namespace

void params_tables(const Context& c, std::vector<Table>& out) {
  for (const Series& s : c.series()) {
    std::vector<std::string> cols{"Parameter", "unit"};
    for (const GroupRecord* g : s.groups) cols.push_back(c.label(*g));
    Table r = c.table("params" + c.suffix(s), fmt::format("Identified parameters of the best run per condition — {}", c.describe(s)),
                        cols);
    std::vector<std::string> rel_cols{"Parameter"};
    for (const GroupRecord* g : s.groups) rel_cols.push_back(c.label(*g));
    Table rel = c.table("params" + c.suffix(s) + "_se",
                          fmt::format("Relative standard error (%) of the identified parameters, best run per condition — {}",
                                      c.describe(s)),
                          rel_cols);
    rel.paper = "";
    std::vector<std::vector<double>> best;
    for (const GroupRecord* g : s.groups)
      best.push_back(c.model(*g).to_paper_units(g->run_results[static_cast<std::size_t>(g->best_run())].params));
    bool marked = false;
    for (const std::string& laws : law_blocks(s)) {
      const GroupRecord* first = *std::find_if(s.groups.begin(), s.groups.end(), [&](auto* g) { return g->laws == laws; });
      if (!laws.empty()) {
        std::vector<Cell> row{txt("laws"), txt("")};
        for (const GroupRecord* g : s.groups) row.push_back(g->laws == laws ? txt(laws) : none());
        r.rows.push_back(std::move(row));
      }
      const auto params = c.model(*first).parameters();
      for (std::size_t j = 0; j < params.size(); ++j) {
        std::vector<Cell> row{txt(params[j].name), txt(params[j].paper_unit)}, rel_row{txt(params[j].name)};
        for (std::size_t k = 0; k < best.size(); ++k) {
          const GroupRecord& g = *s.groups[k];
          if (g.laws != laws) {  // another block's group
            row.push_back(none());
            rel_row.push_back(none());
            continue;
          }
          const double v = best[k][j];
          const std::string mark = identifiability_mark(g, static_cast<int>(j));
          marked |= !mark.empty();
          row.push_back({format_number(v) + mark, v});
          if (!g.identifiability) {
            rel_row.push_back(none());
            continue;
          }
          const double e = 100 * g.identifiability->relative_error[j];
          std::string flags;
          for (const auto& f : g.identifiability->flags[j]) flags += (flags.empty() ? " (" : "; ") + f;
          rel_row.push_back({format_number(e) + flags + (flags.empty() ? "" : ")"), e});
        }
        r.rows.push_back(std::move(row));
        rel.rows.push_back(std::move(rel_row));
      }
    }
    std::vector<Cell> row{txt(std::string(metric_name(s.metric))), txt("")};
    for (const GroupRecord* g : s.groups) row.push_back(num(g->run_results[static_cast<std::size_t>(g->best_run())].best_value));
    r.rows.push_back(std::move(row));
    if (marked) r.note = kIdentifiabilityNote;
    rel.note = "Standard errors from sigma^2 (J^T J)^-1 at the best run's parameters over the fit records "
               "(engine/identification/identifiability.hpp); > 100 % means the record does not determine the parameter.";
    out.push_back(std::move(r));
    out.push_back(std::move(rel));
  }
}

}  // namespace dampbench::sweep::tables
