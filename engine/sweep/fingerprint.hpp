#pragma once
// What a stored result was computed with (DESIGN.md, "Reproducibility"): the dampbench version, the build
// flags, the sweep spec's hash and the hash of every dataset it used. A store only takes results from the
// same version and flags, so resumed results are bit-identical to an uninterrupted run.
#include <cstdint>
#include <span>
#include <string>

#include "engine/record/signals.hpp"

namespace dampbench::sweep {

/// DAMPBENCH_VERSION of this build ("0.2.0").
std::string dampbench_version();
/// DAMPBENCH_BUILD_FLAGS of this build ("Release,native=OFF,GNU-12.2.0").
std::string build_flags();

/// 64-bit hash (16 hex digits) of a prepared dataset: name, every signal's bits and the operating variables.
std::string dataset_hash(const Signals& data);

/// Combines hex hashes in order into one.
std::string combine_hashes(std::span<const std::string> hashes);

}  // namespace dampbench::sweep
