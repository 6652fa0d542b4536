#pragma once
// `dampbench table STORE --kind K`: a table of a sweep's store (engine/sweep/tables.hpp), or every table the
// sweep file asks for (--kind sweep).
#include <string>
#include <vector>

#include "engine/common/table.hpp"
#include "engine/sweep/tables.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

struct TableOptions {
  std::string store;
  std::string kind;           ///< a table kind (engine/sweep/tables.hpp) or "sweep": the sweep file's tables
  std::string format = "md";  ///< md, csv, latex, json
  std::string split;          ///< only this split
  std::vector<std::string> models, optimizers;  ///< only these (names / labels)
  std::string metric;         ///< metric shown (errors) / optimized metric chosen
  std::string role;           ///< errors: fit or predict
  double target_rel = 0.01;   ///< runtime: relative distance of the target to the best known value
};

void add_table_options(CLI::App* cmd, TableOptions& options);
/// InputError for an unknown kind, role or metric (checked before the store is opened).
void check_table_request(const TableOptions& options);
/// The tables `table` prints (its computing half, the Python module's too): per part of the store, the kind's
/// tables or the sweep file's; a table's id starts with its part's name when the store has several parts.
/// Empty when no stored group matches.
std::vector<Table> store_tables(const TableOptions& options, const sweep::StoreResults& results);
int table_command(const TableOptions& options);

}  // namespace dampbench::cli
