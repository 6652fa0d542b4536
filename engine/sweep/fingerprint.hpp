#pragma once
// What a stored result was computed with (docs/design.md, reproducibility): the dampbench version, the build
// flags, the sweep spec's hash and the hash of every dataset it used. A store only takes results from the
// same version and flags, so resumed results are bit-identical to an uninterrupted run.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "engine/record/signals.hpp"

namespace dampbench::sweep {

/// DAMPBENCH_VERSION of this build ("0.2.0").
std::string dampbench_version();
/// DAMPBENCH_BUILD_FLAGS of this build and the vector level the kernels run with
/// ("Release,native=OFF,libmvec,GNU-12.2.0,isa=avx512"; engine/kernels/isa.hpp): the levels differ in the
/// last bits of vector math, so results of one level only are mixed in a store.
std::string build_flags();
/// The "isa=" part of build flags ("avx512"), "" if absent (stores of dampbench before 0.3).
std::string isa_of_build_flags(std::string_view flags);
/// Whether build flags a and b differ in their vector level alone.
bool differ_only_in_isa(std::string_view a, std::string_view b);

/// 64-bit hash (16 hex digits) of a prepared dataset: name, every signal's bits and the operating variables.
std::string dataset_hash(const Signals& data);

/// Combines hex hashes in order into one.
std::string combine_hashes(std::span<const std::string> hashes);

}  // namespace dampbench::sweep
