#pragma once
// A finished task group as bytes, for the messages between MPI ranks (mpi_runner.hpp).
//
// Every field of GroupRecord is written, doubles as their 8 bytes, so the record rank 0 stores from a
// worker's message is bit-for-bit the one the worker computed. The layout is private to one binary: both
// ends are the same dampbench (the ranks check their fingerprints when they start).
#include <string>
#include <string_view>

#include "engine/sweep/store.hpp"

namespace dampbench::distributed {

std::string encode_group(const sweep::GroupRecord& group);

/// DataError when the bytes end early or carry trailing bytes (a truncated or mixed-up message).
sweep::GroupRecord decode_group(std::string_view bytes);

}  // namespace dampbench::distributed
