// The registry of table kinds, and the tables a request or a whole sweep file asks for.
#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/sweep/tables/kinds.hpp"

namespace dampbench::sweep {

const std::vector<tables::Kind>& tables::registry() {
  static const std::vector<Kind> kinds{
      {"runs", runs_tables},           {"param-stats", param_stats_tables}, {"variability", variability_tables},
      {"ranking", ranking_tables},     {"fvd", fvd_tables},                 {"params", params_tables},
      {"errors", errors_tables, true}, {"energy", energy_tables, true},     {"held-out", held_out_tables, true},
      {"regression", regression_tables}, {"sensitivity", sensitivity_tables}, {"landscape", landscape_tables},
      {"ranksum", ranksum_tables},     {"bootstrap", bootstrap_tables},     {"runtime", runtime_tables},
      {"failures", failures_table},    {"overview", overview_table}};
  return kinds;
}

bool tables::where_picks_rows(std::string_view name) {
  const auto& kinds = registry();
  const auto it = std::find_if(kinds.begin(), kinds.end(), [&](const Kind& k) { return k.name == name; });
  return it != kinds.end() && it->where_picks_rows;
}

std::vector<std::string> table_kinds() {
  std::vector<std::string> out;
  for (const tables::Kind& k : tables::registry()) out.emplace_back(k.name);
  return out;
}

std::vector<Table> make_tables(const StoreResults& results, int part, const TableSpec& t) {
  const tables::Context c(results, part, t);
  const auto& kinds = tables::registry();
  const auto kind = std::find_if(kinds.begin(), kinds.end(), [&](const tables::Kind& k) { return k.name == t.kind; });
  if (kind == kinds.end()) {
    std::string known;
    for (const auto& x : kinds) known += (known.empty() ? "" : ", ") + std::string(x.name);
    throw InputError(fmt::format("--kind: unknown table kind '{}' (known: {}, sweep)", t.kind, known));
  }
  std::vector<Table> out;
  kind->make(c, out);
  return out;
}

std::vector<RegressionResult> law_regressions(const StoreResults& results, int part) {
  const TableSpec everything;
  const tables::Context c(results, part, everything);
  std::vector<RegressionResult> out;
  for (const RegressionSpec& reg : c.spec.regressions) out.push_back(tables::law_regression(c, reg));
  return out;
}

namespace {

/// The tables of `kind` with the request's defaults.
std::vector<Table> tables_of_kind(const StoreResults& results, int part, const char* kind) {
  TableSpec t;
  t.kind = kind;
  return make_tables(results, part, t);
}

bool has_failures(const StoreResults& results, int part) {
  return std::any_of(results.groups.begin(), results.groups.end(),
                     [&](const GroupRecord& g) { return g.part == part && g.failed; }) ||
         std::any_of(results.header.datasets.begin(), results.header.datasets.end(),
                     [&](const StoreDataset& d) { return d.part == part && !d.error.empty(); });
}

}  // namespace

std::vector<Table> sweep_tables(const StoreResults& results, int part) {
  const PartSpec& spec = results.parts.at(static_cast<std::size_t>(part));
  std::vector<Table> out;
  bool regression = false;
  // Ids must be unique within a part: several [[tables]] of one kind get a running number.
  std::map<std::string, int> seen;
  for (const TableSpec& t : spec.tables) {
    regression |= t.kind == "regression";
    for (Table& r : make_tables(results, part, t)) {
      if (const int n = seen[r.id]++; n > 0) r.id += fmt::format("_{}", n + 1);
      out.push_back(std::move(r));
    }
  }
  if (!regression && !spec.regressions.empty())
    for (Table& r : tables_of_kind(results, part, "regression")) out.push_back(std::move(r));
  const bool asked_failures =
      std::any_of(spec.tables.begin(), spec.tables.end(), [](const TableSpec& t) { return t.kind == "failures"; });
  if (has_failures(results, part) && !asked_failures)
    for (Table& r : tables_of_kind(results, part, "failures")) out.push_back(std::move(r));
  return out;
}

}  // namespace dampbench::sweep
