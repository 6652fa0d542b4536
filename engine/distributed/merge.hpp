#pragma once
// `dampbench merge OUT.sqlite PART.sqlite ...`: joins the stores of a sweep's shards (run --shard i/n, e.g. the
// jobs of a Slurm array) into one store of the whole sweep, from which tables, reports and verify work as on
// a store written by one process.
//
// Every part must come from the same sweep spec (hash), the same dampbench version and build flags, and the
// same datasets (names and hashes): otherwise nothing is merged and the message names the part and what
// differs. A group found in several parts (or already in OUT) must be bit-identical in each (compare_records):
// it is then written once; a group that differs is an error, since the same binary on the same inputs must
// give the same bits. OUT may exist (a merge can be repeated as more shards finish): it is resumed after the
// same checks.
#include <string>
#include <vector>

namespace dampbench::distributed {

struct MergeSummary {
  long long groups = 0;           ///< task groups of the sweep
  long long merged = 0;           ///< groups written into OUT by this merge
  long long duplicates = 0;       ///< groups found again (in OUT or another part), identical
  long long missing = 0;          ///< groups of the sweep in no part (OUT is incomplete)
  std::vector<std::string> shards;  ///< each part's shard ("2/3", or "whole" for a whole-sweep store)
};

/// StoreError (a part that cannot be read) or InputError (parts of different sweeps or builds, or a group
/// whose results differ between parts), naming the part; nothing is written in OUT before every header is checked.
MergeSummary merge_stores(const std::string& out_path, const std::vector<std::string>& part_paths);

}  // namespace dampbench::distributed
