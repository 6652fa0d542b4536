// `dampbench run` options, `dampbench table STORE`, `dampbench verify STORE` (engine/sweep) and
// `dampbench datasets generate` (datasets/synthetic/grids.hpp).
#include "engine/cli/sweep_commands.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include "datasets/synthetic/grids.hpp"
#include "engine/cli/preset.hpp"
#include "engine/common/error.hpp"
#include "engine/distributed/merge.hpp"
#include "engine/kernels/isa.hpp"
#include "engine/sweep/fingerprint.hpp"
#include "engine/sweep/plan.hpp"
#include "engine/sweep/runner.hpp"
#include "engine/sweep/spec.hpp"
#include "engine/sweep/store.hpp"
#include "engine/sweep/tables.hpp"

namespace dampbench::cli {

void add_run_options(CLI::App* cmd, RunOptions& o) {
  cmd->add_option("preset", o.preset, "sweep file (presets: datasets/presets/*.toml)")->required();
  cmd->add_option("-o,--output", o.output_dir, "output folder (default results/<sweep name>)");
  cmd->add_option("--store", o.store, "SQLite store (default <output>/store.sqlite); an existing one is resumed");
  cmd->add_flag("--quiet", o.quiet, "no progress bar");
  cmd->add_flag("--fresh", o.fresh, "delete an existing store first instead of resuming it");
  cmd->add_flag("--no-report", o.no_report, "do not write <output>/report.html (dampbench report STORE writes it later)");
  cmd->add_option("--shard", o.shard,
                  "i/n: run only shard i of n (a fixed 1/n of the task groups, for job arrays) into its own store "
                  "(default <output>/shard-i-of-n.sqlite); `dampbench merge` joins the shards' stores");
}

void add_merge_options(CLI::App* cmd, MergeOptions& o) {
  cmd->add_option("out", o.out, "the merged store (created, or resumed when it exists)")->required();
  cmd->add_option("parts", o.parts, "the shards' stores (dampbench run --shard i/n)")->required();
}

void add_datasets_options(CLI::App* cmd, DatasetsOptions& o) {
  cmd->add_option("grids", o.grids, "grids to generate: fvd, crfd, mfm, fdsp (default: all)");
  cmd->add_option("--into", o.into, "folder (default: the cache `run` reads; env DAMPBENCH_GENERATED_DIR)");
}

int datasets_command(const DatasetsOptions& o) {
  const std::string root = o.into.empty() ? sweep::generated_dir() : o.into;
  for (const std::string& grid : o.grids.empty() ? synthetic::grid_names() : o.grids) {
    const auto state = synthetic::ensure_grid(root, grid, sweep::generator_identity());
    std::cout << fmt::format("{}: {} {}\n", grid,
                             state == synthetic::GridState::kPresent       ? "already in"
                             : state == synthetic::GridState::kGenerated   ? "generated into"
                                                                            : "regenerated (made by another build) in",
                             (std::filesystem::path(root) / grid).string());
  }
  return 0;
}

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
  cmd->add_option("--role", o.role, "errors: fit or predict");
  cmd->add_option("--target-rel", o.target_rel, "runtime: target = best known + this x |best known| (default 0.01)");
}

void add_verify_options(CLI::App* cmd, VerifyOptions& o) {
  cmd->add_option("store", o.store, "the sweep's SQLite store")->required();
  cmd->add_option("--sample", o.sample, "re-run this many stored task groups, spread over the store (default: all)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--spec", o.spec, "the sweep file (default: the path recorded in the store)");
}

int merge_command(const MergeOptions& o) {
  const distributed::MergeSummary m = distributed::merge_stores(o.out, o.parts);
  std::string shards;
  for (const auto& s : m.shards) shards += (shards.empty() ? "" : ", ") + s;
  std::cout << fmt::format("merge: {} task groups merged into {} from {} stores (shards {}), {} found twice and "
                           "identical; {} of {} groups in the merged store\n",
                           m.merged, o.out, o.parts.size(), shards, m.duplicates, m.groups - m.missing, m.groups);
  if (m.missing > 0)
    std::cerr << fmt::format("warning: {} task groups of the sweep are in no part (a shard not finished, or not given): "
                             "tables from {} are partial; merge again when they are done\n",
                             m.missing, o.out);
  return 0;
}

int table_command(const TableOptions& o) {
  if (o.format != "md" && o.format != "csv" && o.format != "latex" && o.format != "json")
    throw InputError(fmt::format("--format: expected md, csv, latex or json, got '{}'", o.format));
  const auto kinds = sweep::table_kinds();
  if (o.kind != "sweep" && std::find(kinds.begin(), kinds.end(), o.kind) == kinds.end()) {
    std::string known;
    for (const auto& k : kinds) known += (known.empty() ? "" : ", ") + k;
    throw InputError(fmt::format("--kind: unknown table kind '{}' (known: {}, sweep)", o.kind, known));
  }
  if (!o.role.empty() && o.role != "fit" && o.role != "predict")
    throw InputError(fmt::format("--role: expected fit or predict, got '{}'", o.role));
  if (!o.metric.empty()) (void)parse_metric(o.metric);
  const sweep::Store store = sweep::Store::open(o.store);
  if (const std::string shard = store.meta("shard"); !shard.empty())
    std::cerr << fmt::format("note: {} holds shard {} of the sweep only: its tables are partial (dampbench merge joins "
                             "the shards' stores)\n", o.store, shard);
  const sweep::StoreResults results(store);
  std::vector<sweep::Report> reports;
  for (int p = 0; p < results.part_count(); ++p) {
    std::vector<sweep::Report> part;
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
  if (reports.empty()) {
    std::cerr << fmt::format("dampbench: no '{}' table in {} (no stored task group matches)\n", o.kind, o.store);
    return kExitDifferent;
  }
  std::cout << sweep::format_reports(reports, o.format);
  return 0;
}

int verify_command(const VerifyOptions& o) {
  const sweep::Store store = sweep::Store::open(o.store);
  const sweep::StoreHeader header = store.header();
  const std::string spec_path = o.spec.empty() ? header.spec_path : o.spec;
  // Vector levels differ in the last bits (engine/kernels/isa.hpp): re-run at the store's level if this CPU has it,
  // unless --isa or DAMPBENCH_ISA asked for another.
  if (const std::string stored = sweep::isa_of_build_flags(header.build_flags);
      !stored.empty() && stored != isa_name(active_isa())) {
    const auto level = parse_isa(stored);
    if (isa_chosen_by_user()) {
      std::cout << fmt::format("note: the store was computed with {} kernels; verify re-runs them with {} as --isa or "
                               "DAMPBENCH_ISA asks: results of different levels differ in the last bits of vector math, "
                               "and a fit's path can then differ (docs/performance.md, \"Vector levels\")\n",
                               stored, isa_name(active_isa()));
    } else if (level && std::ranges::find(supported_isas(), *level) != supported_isas().end()) {
      std::cout << fmt::format("note: the store was computed with {} kernels; verify re-runs them with {} (this process "
                               "would use {})\n", stored, stored, isa_name(active_isa()));
      select_isa(*level);
    } else {
      std::cout << fmt::format("note: the store was computed with {} vector kernels, which this CPU or build does not "
                               "have (it has {}): results of different levels differ in the last bits of vector math, "
                               "and a fit's path can then differ (docs/performance.md, \"Vector levels\")\n",
                               stored, isa_summary());
    }
  }
  if (header.dampbench_version != sweep::dampbench_version() || header.build_flags != sweep::build_flags())
    std::cout << fmt::format("note: the store was written by dampbench {} ({}), this is {} ({}); differences may come "
                             "from the build\n",
                             header.dampbench_version, header.build_flags, sweep::dampbench_version(), sweep::build_flags());
  sweep::SweepSpec spec = sweep::load_sweep(spec_path);
  if (spec.hash != header.spec_hash)
    throw InputError(fmt::format("{}: the sweep file changed since the store was written (spec hash {}, store {}); give "
                                 "the original with --spec",
                                 spec_path, spec.hash, header.spec_hash));
  const sweep::Plan plan(std::move(spec), sweep_loader());
  const sweep::StoreHeader now = sweep::make_store_header(plan, spec_path);
  int problems = 0;
  if (now.datasets.size() != header.datasets.size()) {
    std::cout << fmt::format("DIFFERENT: the sweep now has {} datasets, the store {}\n", now.datasets.size(),
                             header.datasets.size());
    return kExitDifferent;
  }
  for (std::size_t i = 0; i < now.datasets.size(); ++i)
    if (now.datasets[i].hash != header.datasets[i].hash || now.datasets[i].name != header.datasets[i].name) {
      std::cout << fmt::format("DIFFERENT: dataset '{}' ({}): hash {} in the store, {} now\n", header.datasets[i].name,
                               header.datasets[i].path, header.datasets[i].hash, now.datasets[i].hash);
      ++problems;
    }
  if (problems) return kExitDifferent;

  std::vector<long long> stored;
  const auto finished = store.finished();
  for (std::size_t i = 0; i < finished.size(); ++i)
    if (finished[i]) stored.push_back(static_cast<long long>(i));
  std::vector<long long> chosen;
  const std::size_t k = o.sample > 0 ? std::min<std::size_t>(static_cast<std::size_t>(o.sample), stored.size()) : stored.size();
  for (std::size_t i = 0; i < k; ++i) chosen.push_back(stored[i * stored.size() / k]);

  // Re-run the chosen groups several at a time (as `run` does), compare in order as they come.
  long long differing = 0, runs = 0;
  std::size_t next = 0;
  using Record = std::shared_ptr<sweep::GroupRecord>;
  tbb::parallel_pipeline(
      static_cast<std::size_t>(2 * std::max(1, tbb::this_task_arena::max_concurrency())),
      tbb::make_filter<void, long long>(tbb::filter_mode::serial_in_order,
                                        [&](tbb::flow_control& fc) -> long long {
                                          if (next >= chosen.size()) {
                                            fc.stop();
                                            return -1;
                                          }
                                          return chosen[next++];
                                        }) &
          tbb::make_filter<long long, Record>(
              tbb::filter_mode::parallel,
              [&](long long i) { return std::make_shared<sweep::GroupRecord>(sweep::run_group(plan, i)); }) &
          tbb::make_filter<Record, void>(tbb::filter_mode::serial_in_order, [&](const Record& again) {
            const auto old = store.group(again->index);
            const sweep::GroupRef g = plan.group(again->index);
            std::vector<std::string> names;
            for (const auto& p : plan.parts()[g.part].models[g.model].model->parameters()) names.push_back(p.name);
            const auto diff = sweep::compare_records(*old, *again, names);
            runs += static_cast<long long>(old->run_results.size());
            if (diff.empty()) return;
            ++differing;
            std::cout << fmt::format("DIFFERENT: task group {} ({}):\n", again->index, plan.describe(g));
            for (std::size_t j = 0; j < diff.size() && j < 20; ++j) std::cout << "  " << diff[j] << "\n";
            if (diff.size() > 20) std::cout << fmt::format("  ... and {} more\n", diff.size() - 20);
          }));
  if (differing) {
    std::cout << fmt::format("verify: {} of {} re-run task groups differ from the store {}\n", differing, chosen.size(), o.store);
    return kExitDifferent;
  }
  std::cout << fmt::format("verify: {} task groups ({} runs) re-run, every stored number identical bit for bit ({} of {} "
                           "stored groups checked)\n",
                           chosen.size(), runs, chosen.size(), stored.size());
  return 0;
}

}  // namespace dampbench::cli
