#include "engine/distributed/merge.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/sweep/fingerprint.hpp"
#include "engine/sweep/store.hpp"

namespace dampbench::distributed {
namespace {

/// Empty when `b` describes the same sweep, build and datasets as `a`; otherwise what differs.
std::string header_difference(const sweep::StoreHeader& a, const sweep::StoreHeader& b) {
  if (a.spec_hash != b.spec_hash)
    return fmt::format("another sweep spec ('{}', spec hash {}, vs '{}', {})", b.name, b.spec_hash, a.name, a.spec_hash);
  if (a.dampbench_version != b.dampbench_version || a.build_flags != b.build_flags)
    return fmt::format("another build (dampbench {} ({}) vs {} ({})){}", b.dampbench_version, b.build_flags,
                       a.dampbench_version, a.build_flags,
                       a.dampbench_version == b.dampbench_version && sweep::differ_only_in_isa(a.build_flags, b.build_flags)
                           ? "; the shards ran at different vector levels: run every shard with the same --isa "
                             "(or DAMPBENCH_ISA) on machines that have it"
                           : "");
  if (a.groups != b.groups || a.datasets.size() != b.datasets.size())
    return fmt::format("another plan ({} task groups and {} datasets vs {} and {})", b.groups, b.datasets.size(),
                       a.groups, a.datasets.size());
  for (std::size_t i = 0; i < a.datasets.size(); ++i)
    if (a.datasets[i].name != b.datasets[i].name || a.datasets[i].hash != b.datasets[i].hash)
      return fmt::format("other data (dataset '{}' hash {} vs '{}' hash {})", b.datasets[i].name, b.datasets[i].hash,
                         a.datasets[i].name, a.datasets[i].hash);
  return "";
}

}  // namespace

MergeSummary merge_stores(const std::string& out_path, const std::vector<std::string>& part_paths) {
  if (part_paths.empty()) throw InputError("merge: no part stores given");
  std::error_code ec;
  for (const auto& p : part_paths)
    if (std::filesystem::equivalent(p, out_path, ec))
      throw InputError(fmt::format("merge: the output store {} is also given as a part", out_path));

  // Every header first (one part open at a time: a job array may have thousands), then the groups.
  MergeSummary sum;
  sweep::StoreHeader first;
  for (const auto& p : part_paths) {
    const sweep::StoreHeader h = sweep::Store::open(p).header();
    if (&p == &part_paths.front()) first = h;
    if (const std::string diff = header_difference(first, h); !diff.empty())
      throw InputError(fmt::format("merge: {} comes from {} than {}: not merged", p, diff, part_paths.front()));
    sum.shards.push_back(h.shard.empty() ? "whole" : h.shard);
  }
  sweep::StoreHeader whole = first;
  whole.shard.clear();
  const sweep::StoreLock lock(out_path);  // no `run` or other merge writes OUT meanwhile
  sweep::Store out = sweep::Store::create_or_resume(out_path, whole);
  sum.groups = whole.groups;

  std::vector<char> have = out.finished();
  for (const auto& p : part_paths) {
    const sweep::Store part = sweep::Store::open(p);
    const std::vector<char> in_part = part.finished();
    for (long long i = 0; i < sum.groups; ++i) {
      const auto u = static_cast<std::size_t>(i);
      if (!in_part[u]) continue;
      const auto record = part.group(i, true);
      if (!have[u]) {
        out.write(*record);
        have[u] = 1;
        ++sum.merged;
        continue;
      }
      const auto diff = sweep::compare_records(*out.group(i, true), *record);
      if (!diff.empty())
        throw InputError(fmt::format("merge: task group {} of {} differs from the one already merged ({}{}): the "
                                     "parts are not results of the same computation; {} holds the groups merged so far",
                                     i, p, diff.front(), diff.size() > 1 ? ", ..." : "", out_path));
      ++sum.duplicates;
    }
  }
  for (char h : have) sum.missing += h ? 0 : 1;
  return sum;
}

}  // namespace dampbench::distributed
