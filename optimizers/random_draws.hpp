#pragma once
// Many keyed random draws at once (engine/common/random.hpp): the same numbers RandomStream gives, computed as
// vector loops at the active vector level (engine/kernels/isa.hpp). A draw is one SplitMix64 mix, two 64-bit
// multiplies; an optimizer that knows in advance which streams and how many draws a generation needs gets them
// several lanes at a time instead of one mix after the other, because the draws are most of the GAs' serial
// work per generation.
#include <cstdint>
#include <span>
#include <vector>

namespace dampbench {

/// x[i] = mix64(x[i]) for every i.
void mix_each(std::span<std::uint64_t> x);

/// keys[i] = extend_key(keys[i], part) for every i.
void extend_keys(std::span<std::uint64_t> keys, std::uint64_t part);

/// keys[i] = extend_key(base, i) for every i: the keys of members 0, 1, … under `base`.
void member_keys(std::uint64_t base, std::span<std::uint64_t> keys);

/// The first `draws` uniforms of each stream: out[s·draws + d] is what the (d + 1)-th uniform() of
/// RandomStream(keys[s]) returns. `out` is resized to keys.size() × draws; `scratch` is working storage.
void first_uniforms(std::span<const std::uint64_t> keys, int draws, std::vector<double>& out,
                    std::vector<std::uint64_t>& scratch);

/// The first `count` normals of each stream: out[s·count + i] is what the (i + 1)-th normal() of
/// RandomStream(keys[s]) returns, up to the last bits of the vector log and cos (libmvec at the active level, as
/// the kernels' vector math). `out` is resized to keys.size() × count; `uniforms` and `scratch` are working storage.
void first_normals(std::span<const std::uint64_t> keys, int count, std::vector<double>& out,
                   std::vector<double>& uniforms, std::vector<std::uint64_t>& scratch);

}  // namespace dampbench
