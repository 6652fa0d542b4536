#pragma once
// `dampbench table STORE --kind K`: a table of a sweep's store (engine/sweep/tables.hpp), or every table the
// sweep file asks for (--kind sweep).
#include <string>
#include <vector>

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
int table_command(const TableOptions& options);

}  // namespace dampbench::cli
