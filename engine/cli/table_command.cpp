#include "engine/cli/table_command.hpp"

#include <algorithm>
#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "engine/cli/run_command.hpp"
#include "engine/common/error.hpp"
#include "engine/model/metrics.hpp"
#include "engine/sweep/store.hpp"
#include "engine/sweep/tables.hpp"

namespace dampbench::cli {

void add_table_options(CLI::App* cmd, TableOptions& o) {
  std::string kinds;
  for (const auto& k : sweep::table_kinds()) kinds += (kinds.empty() ? "" : ", ") + k;
  cmd->add_option("store", o.store, "the sweep's SQLite store")->required();
  cmd->add_option("--kind", o.kind, "table kind: " + kinds + ", or sweep (the sweep file's tables)")->required();
  cmd->add_option("--format", o.format, "md (default), csv, latex or json");
  cmd->add_option("--split", o.split, "only this split");
  cmd->add_option("--model", o.models, "only this model (repeat for several)");
  cmd->add_option("--optimizer", o.optimizers, "only this optimizer label (repeat for several)");
  cmd->add_option("--metric", o.metric, "metric shown by errors (and the optimized metric chosen)");
  cmd->add_option("--role", o.role, "errors and held-out: fit or predict");
  cmd->add_option("--target-rel", o.target_rel, "runtime: target = best known + this x |best known| (default 0.01)");
}

void check_table_request(const TableOptions& o) {
  const auto kinds = sweep::table_kinds();
  if (o.kind != "sweep" && std::find(kinds.begin(), kinds.end(), o.kind) == kinds.end()) {
    std::string known;
    for (const auto& k : kinds) known += (known.empty() ? "" : ", ") + k;
    throw InputError(fmt::format("--kind: unknown table kind '{}' (known: {}, sweep)", o.kind, known));
  }
  if (!o.role.empty() && o.role != "fit" && o.role != "predict")
    throw InputError(fmt::format("--role: expected fit or predict, got '{}'", o.role));
  if (!o.metric.empty()) (void)parse_metric(o.metric);
}

std::vector<Table> store_tables(const TableOptions& o, const sweep::StoreResults& results) {
  std::vector<Table> reports;
  for (int p = 0; p < results.part_count(); ++p) {
    std::vector<Table> part;
    if (o.kind == "sweep") {
      part = sweep::sweep_tables(results, p);
    } else {
      sweep::TableSpec t;
      t.kind = o.kind;
      if (!o.split.empty()) t.splits = {o.split};
      t.models = o.models;
      t.optimizers = o.optimizers;
      t.metric = o.metric;
      t.role = o.role;
      t.target_rel = o.target_rel;
      part = sweep::make_tables(results, p, t);
    }
    for (auto& r : part) {
      if (results.part_count() > 1) r.id = results.header.parts[static_cast<std::size_t>(p)].name + "/" + r.id;
      reports.push_back(std::move(r));
    }
  }
  return reports;
}

int table_command(const TableOptions& o) {
  if (o.format != "md" && o.format != "csv" && o.format != "latex" && o.format != "json")
    throw InputError(fmt::format("--format: expected md, csv, latex or json, got '{}'", o.format));
  check_table_request(o);
  const sweep::Store store = sweep::Store::open(o.store);
  if (const std::string shard = store.meta("shard"); !shard.empty())
    std::cerr << fmt::format("note: {} holds shard {} of the sweep only: its tables are partial (dampbench merge joins "
                             "the shards' stores)\n", o.store, shard);
  const std::vector<Table> reports = store_tables(o, sweep::StoreResults(store, sweep_loader()));
  if (reports.empty()) {
    std::cerr << fmt::format("dampbench: no '{}' table in {} (no stored task group matches)\n", o.kind, o.store);
    return kExitDifferent;
  }
  std::cout << sweep::format_tables(reports, o.format);
  return 0;
}

}  // namespace dampbench::cli
