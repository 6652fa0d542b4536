#pragma once
// Which task groups a run takes on, and in what order.
//
// Order never changes results (a group's result depends only on its number and the plan); it only shapes the
// tail of a sweep. Groups are handed out largest first (by estimated_cost), so that the last groups to finish
// are small ones and cores, or MPI ranks, run out of work at nearly the same time.
//
// A shard (`dampbench run SWEEP --shard i/n`, for job arrays) is a fixed 1/n of the groups, chosen by
// longest-processing-time assignment of the estimated costs: groups in decreasing cost, each to the shard with
// the least work so far (ties: lowest number). It depends on the plan only, so every job of an array computes
// the same split, and the union of the n shards is the sweep, each group in exactly one shard.
#include <string>
#include <string_view>
#include <vector>

#include "engine/sweep/plan.hpp"

namespace dampbench::sweep {

/// Shard `index` (0-based) of `count`; {0, 1} is the whole sweep. Written "index+1/count".
struct Shard {
  int index = 0, count = 1;
  [[nodiscard]] bool whole() const { return count == 1; }
  [[nodiscard]] std::string text() const;  ///< "2/3"; "" for the whole sweep
  friend bool operator==(const Shard&, const Shard&) = default;
};

inline constexpr int kMaxShards = 1'000'000;

/// "i/n" with 1 ≤ i ≤ n ≤ kMaxShards (as Slurm's --array=1-n numbers jobs); InputError naming `what` otherwise.
Shard parse_shard(std::string_view text, std::string_view what = "--shard");

/// Relative cost of a group: runs × evaluations per run × samples of its fit datasets × parameters.
/// Only an estimate for ordering; ODE models cost more per sample than it says.
double estimated_cost(const Plan& plan, const GroupRef& group);

/// in_shard[i] != 0 for the groups of `shard` (all of them for the whole sweep); size plan.groups().
std::vector<char> shard_groups(const Plan& plan, const Shard& shard);

/// The groups of `shard` not marked in `done`, largest estimated cost first (ties: lower number first).
std::vector<long long> schedule(const Plan& plan, const std::vector<char>& done, const Shard& shard = {});

}  // namespace dampbench::sweep
