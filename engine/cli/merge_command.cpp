#include "engine/cli/merge_command.hpp"

#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "engine/distributed/merge.hpp"

namespace dampbench::cli {

void add_merge_options(CLI::App* cmd, MergeOptions& o) {
  cmd->add_option("out", o.out, "the merged store (created, or resumed when it exists)")->required();
  cmd->add_option("parts", o.parts, "the shards' stores (dampbench run --shard i/n)")->required();
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

}  // namespace dampbench::cli
