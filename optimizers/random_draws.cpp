#include "optimizers/random_draws.hpp"

#include "engine/common/random.hpp"
#include "engine/common/vector_math.hpp"
#include "engine/kernels/isa.hpp"

namespace dampbench {
namespace {

/// The loops, compiled per vector level (IsaClones); integer operations, so every level gives the same bits.
struct MixLoop {
  static void run(std::uint64_t* x, std::size_t n) {
#pragma omp simd
    for (std::size_t i = 0; i < n; ++i) x[i] = mix64(x[i]);
  }
};
struct UniformLoop {
  static void run(const std::uint64_t* x, double* out, std::size_t n) {
#pragma omp simd
    for (std::size_t i = 0; i < n; ++i) out[i] = to_uniform(mix64(x[i]));
  }
};
/// Box–Muller over pairs of uniforms; its log and cos are libmvec's vector functions of the level.
struct NormalLoop {
  static void run(const double* uniform_pairs, double* out, std::size_t n) {
#pragma omp simd
    for (std::size_t i = 0; i < n; ++i) out[i] = box_muller(uniform_pairs[2 * i], uniform_pairs[2 * i + 1]);
  }
};

}  // namespace

void mix_each(std::span<std::uint64_t> x) { IsaClones<MixLoop>::call(x.data(), x.size()); }

void extend_keys(std::span<std::uint64_t> keys, std::uint64_t part) {
  const std::uint64_t mixed_part = mix64(part);
  for (std::uint64_t& k : keys) k ^= mixed_part;
  mix_each(keys);
}

void member_keys(std::uint64_t base, std::span<std::uint64_t> keys) {
  for (std::size_t i = 0; i < keys.size(); ++i) keys[i] = i;
  mix_each(keys);
  for (std::uint64_t& k : keys) k ^= base;
  mix_each(keys);
}

void first_uniforms(std::span<const std::uint64_t> keys, int draws, std::vector<double>& out,
                    std::vector<std::uint64_t>& scratch) {
  // Draw d of stream s is mix64(key_s ^ mixed_counter(d)) (RandomStream::u64_at).
  const auto d_count = static_cast<std::size_t>(draws);
  scratch.resize(keys.size() * d_count);
  out.resize(scratch.size());
  for (std::size_t s = 0; s < keys.size(); ++s)
    for (std::size_t d = 0; d < d_count; ++d) scratch[s * d_count + d] = keys[s] ^ mixed_counter(d);
  IsaClones<UniformLoop>::call(static_cast<const std::uint64_t*>(scratch.data()), out.data(), scratch.size());
}

void first_normals(std::span<const std::uint64_t> keys, int count, std::vector<double>& out,
                   std::vector<double>& uniforms, std::vector<std::uint64_t>& scratch) {
  first_uniforms(keys, 2 * count, uniforms, scratch);  // normal() draws two uniforms per normal, in order
  out.resize(keys.size() * static_cast<std::size_t>(count));
  IsaClones<NormalLoop>::call(static_cast<const double*>(uniforms.data()), out.data(), out.size());
}

}  // namespace dampbench
