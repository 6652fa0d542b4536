#include "engine/sweep/fingerprint.hpp"

#include <bit>
#include <cstring>

#include <fmt/format.h>

#include "engine/common/random.hpp"
#include "engine/kernels/isa.hpp"

#ifndef DAMPBENCH_VERSION
#error "dampbench_sweep needs DAMPBENCH_VERSION (engine/sweep/CMakeLists.txt)"
#endif
#ifndef DAMPBENCH_BUILD_FLAGS
#error "dampbench_sweep needs DAMPBENCH_BUILD_FLAGS (engine/sweep/CMakeLists.txt)"
#endif

namespace dampbench::sweep {
namespace {

std::uint64_t mix_doubles(std::uint64_t h, const std::vector<double>& v) {
  h = mix64(h ^ v.size());
  for (double x : v) h = mix64(h ^ std::bit_cast<std::uint64_t>(x));
  return h;
}

}  // namespace

std::string dampbench_version() { return DAMPBENCH_VERSION; }
std::string build_flags() { return fmt::format("{},isa={}", DAMPBENCH_BUILD_FLAGS, isa_name(active_isa())); }

std::string isa_of_build_flags(std::string_view flags) {
  const auto at = flags.rfind(",isa=");
  return at == std::string_view::npos ? std::string() : std::string(flags.substr(at + 5));
}

bool differ_only_in_isa(std::string_view a, std::string_view b) {
  const auto strip = [](std::string_view f) { return f.substr(0, f.rfind(",isa=")); };
  return a != b && strip(a) == strip(b) && !isa_of_build_flags(a).empty() && !isa_of_build_flags(b).empty();
}

std::string dataset_hash(const Signals& d) {
  std::uint64_t h = hash_name(d.name);
  for (const auto* v : {&d.t_s, &d.x_m, &d.v_m_s, &d.a_m_s2, &d.F_N}) h = mix_doubles(h, *v);
  for (const auto& [k, x] : d.operating) h = hash_key({h, hash_name(k), std::bit_cast<std::uint64_t>(x)});
  // A command column that varies (none for a constant record, whose hash stays what it was).
  for (const auto& [k, column] : d.operating_signals) h = mix_doubles(hash_key({h, hash_name(k)}), column);
  return fmt::format("{:016x}", h);
}

std::string combine_hashes(std::span<const std::string> hashes) {
  std::uint64_t h = hash_name("datasets");
  for (const auto& s : hashes) h = hash_key({h, hash_name(s)});
  return fmt::format("{:016x}", h);
}

}  // namespace dampbench::sweep
