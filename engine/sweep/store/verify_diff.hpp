#pragma once
// What `dampbench verify` reports: the bit-level differences between a stored and a recomputed group.
#include <string>
#include <vector>

#include "engine/sweep/store/records.hpp"

namespace dampbench::sweep {

/// Orders per-dataset metrics by (run, dataset), the order the store reads them back in.
void sort_dataset_metrics(std::vector<DatasetMetricRecord>& metrics);

/// Bit-exact comparison of two records of the same group (everything but wall time and fingerprint);
/// each difference as a line "run 3 params[1]: stored 0x… (1.25) vs 0x… (1.2500000000000002)".
std::vector<std::string> compare_records(const GroupRecord& stored, const GroupRecord& recomputed,
                                         const std::vector<std::string>& param_names = {});

}  // namespace dampbench::sweep
