#pragma once
// The table kinds (engine/sweep/tables.hpp lists what each holds), one file each, and the registry that names
// them: a kind is added by writing its file and its line in registry.cpp.
#include <string_view>
#include <vector>

#include "engine/sweep/tables/context.hpp"

namespace dampbench::sweep::tables {

/// Appends the tables of one kind for the request in `c`.
using KindTables = void (*)(const Context& c, std::vector<Table>& out);

struct Kind {
  std::string_view name;
  KindTables make;
  /// A request's `where` picks the kind's rows (the records fitted or predicted) instead of the series' fits.
  bool where_picks_rows = false;
};
/// Every kind a sweep file may ask for, in the order the help lists them.
const std::vector<Kind>& registry();

void runs_tables(const Context& c, std::vector<Table>& out);
void param_stats_tables(const Context& c, std::vector<Table>& out);
void variability_tables(const Context& c, std::vector<Table>& out);
void ranking_tables(const Context& c, std::vector<Table>& out);
void fvd_tables(const Context& c, std::vector<Table>& out);
void params_tables(const Context& c, std::vector<Table>& out);
void errors_tables(const Context& c, std::vector<Table>& out);
void energy_tables(const Context& c, std::vector<Table>& out);
void landscape_tables(const Context& c, std::vector<Table>& out);
void held_out_tables(const Context& c, std::vector<Table>& out);
void regression_tables(const Context& c, std::vector<Table>& out);
void sensitivity_tables(const Context& c, std::vector<Table>& out);
void ranksum_tables(const Context& c, std::vector<Table>& out);
void bootstrap_tables(const Context& c, std::vector<Table>& out);
void runtime_tables(const Context& c, std::vector<Table>& out);
void failures_table(const Context& c, std::vector<Table>& out);
void overview_table(const Context& c, std::vector<Table>& out);

/// One series' table of each repeated-run kind (the fvd set numbers and titles them its own way).
Table runs_table(const Context& c, const Series& s, std::string id, std::string title);
Table param_stats_table(const Context& c, const Series& s, std::string id, std::string title);
Table variability_table(const Context& c, const Series& s, std::string id, std::string title);

/// One [[regressions]] entry fitted on the lowest-metric single-dataset fit per condition.
RegressionResult law_regression(const Context& c, const RegressionSpec& reg);

}  // namespace dampbench::sweep::tables
