// `dampbench verify STORE`: re-runs stored task groups of a sweep (engine/sweep run_group) and compares them with
// the store bit for bit.
#include "engine/cli/verify_command.hpp"

#include <algorithm>
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include "engine/cli/run_command.hpp"
#include "engine/common/error.hpp"
#include "engine/kernels/isa.hpp"
#include "engine/sweep/fingerprint.hpp"
#include "engine/sweep/plan.hpp"
#include "engine/sweep/runner.hpp"
#include "engine/sweep/spec.hpp"
#include "engine/sweep/store.hpp"
#include "engine/sweep/tables.hpp"

namespace dampbench::cli {

void add_verify_options(CLI::App* cmd, VerifyOptions& o) {
  cmd->add_option("store", o.store, "the sweep's SQLite store")->required();
  cmd->add_option("--sample", o.sample, "re-run this many stored task groups, spread over the store (default: all)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--spec", o.spec, "the sweep file (default: the path recorded in the store)");
}

namespace {

/// Vector levels differ in the last bits (engine/kernels/isa.hpp): re-runs at the store's level if this CPU has
/// it, unless --isa or DAMPBENCH_ISA asked for another, and says so.
void select_store_isa(const sweep::StoreHeader& header) {
  const std::string stored = sweep::isa_of_build_flags(header.build_flags);
  if (stored.empty() || stored == isa_name(active_isa())) return;
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

/// The plan of the store's sweep file, after checking that the file is the one the store was written from.
sweep::Plan stored_plan(const sweep::StoreHeader& header, const std::string& spec_path) {
  if (header.dampbench_version != sweep::dampbench_version() || header.build_flags != sweep::build_flags())
    std::cout << fmt::format("note: the store was written by dampbench {} ({}), this is {} ({}); differences may come "
                             "from the build\n",
                             header.dampbench_version, header.build_flags, sweep::dampbench_version(), sweep::build_flags());
  sweep::SweepSpec spec = sweep::load_sweep(spec_path);
  if (spec.hash != header.spec_hash)
    throw InputError(fmt::format("{}: the sweep file changed since the store was written (spec hash {}, store {}); give "
                                 "the original with --spec",
                                 spec_path, spec.hash, header.spec_hash));
  return sweep::Plan(std::move(spec), sweep_loader());
}

/// Prints every dataset whose hash differs from the store's; false when any does.
bool same_datasets(const sweep::Plan& plan, const sweep::StoreHeader& header, const std::string& spec_path) {
  const sweep::StoreHeader now = sweep::make_store_header(plan, spec_path);
  if (now.datasets.size() != header.datasets.size()) {
    std::cout << fmt::format("DIFFERENT: the sweep now has {} datasets, the store {}\n", now.datasets.size(),
                             header.datasets.size());
    return false;
  }
  bool same = true;
  for (std::size_t i = 0; i < now.datasets.size(); ++i)
    if (now.datasets[i].hash != header.datasets[i].hash || now.datasets[i].name != header.datasets[i].name) {
      std::cout << fmt::format("DIFFERENT: dataset '{}' ({}): hash {} in the store, {} now\n", header.datasets[i].name,
                               header.datasets[i].path, header.datasets[i].hash, now.datasets[i].hash);
      same = false;
    }
  return same;
}

/// `sample` stored groups spread evenly over the stored ones (every stored group for 0).
std::vector<long long> chosen_groups(const std::vector<long long>& stored, int sample) {
  std::vector<long long> chosen;
  const std::size_t k = sample > 0 ? std::min<std::size_t>(static_cast<std::size_t>(sample), stored.size()) : stored.size();
  for (std::size_t i = 0; i < k; ++i) chosen.push_back(stored[i * stored.size() / k]);
  return chosen;
}

struct VerifyCount {
  long long differing = 0, runs = 0;
};

/// Re-runs the chosen groups several at a time (as `run` does) and compares each with the store, in order.
VerifyCount rerun_and_compare(const sweep::Plan& plan, const sweep::Store& store, const std::vector<long long>& chosen) {
  VerifyCount count;
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
            const Model& part_model = *plan.parts()[g.part].models[g.model].model;
            // A group's own laws (chosen, or held) act on the entry's registered model, not on the plan's model of it
            const std::string& base_id = plan.spec().parts[g.part].models[g.model].model;
            const ResolvedModel law_model = old->laws.empty() ? ResolvedModel{} : sweep::chosen_law_model(base_id, old->laws);
            std::vector<std::string> names;
            for (const auto& p : (law_model.model ? *law_model.model : part_model).parameters()) names.push_back(p.name);
            const auto diff = sweep::compare_records(*old, *again, names);
            count.runs += static_cast<long long>(old->run_results.size());
            if (diff.empty()) return;
            ++count.differing;
            std::cout << fmt::format("DIFFERENT: task group {} ({}):\n", again->index, plan.describe(g));
            for (std::size_t j = 0; j < diff.size() && j < 20; ++j) std::cout << "  " << diff[j] << "\n";
            if (diff.size() > 20) std::cout << fmt::format("  ... and {} more\n", diff.size() - 20);
          }));
  return count;
}

}  // namespace

int verify_command(const VerifyOptions& o) {
  const sweep::Store store = sweep::Store::open(o.store);
  const sweep::StoreHeader header = store.header();
  const std::string spec_path = o.spec.empty() ? header.spec_path : o.spec;
  select_store_isa(header);
  const sweep::Plan plan = stored_plan(header, spec_path);
  if (!same_datasets(plan, header, spec_path)) return kExitDifferent;

  std::vector<long long> stored;
  const auto finished = store.finished();
  for (std::size_t i = 0; i < finished.size(); ++i)
    if (finished[i]) stored.push_back(static_cast<long long>(i));
  const std::vector<long long> chosen = chosen_groups(stored, o.sample);
  const VerifyCount count = rerun_and_compare(plan, store, chosen);
  if (count.differing) {
    std::cout << fmt::format("verify: {} of {} re-run task groups differ from the store {}\n", count.differing,
                             chosen.size(), o.store);
    return kExitDifferent;
  }
  std::cout << fmt::format("verify: {} task groups ({} runs) re-run, every stored number identical bit for bit ({} of {} "
                           "stored groups checked)\n",
                           chosen.size(), count.runs, chosen.size(), stored.size());
  return 0;
}

}  // namespace dampbench::cli
