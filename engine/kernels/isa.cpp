#include "engine/kernels/isa.hpp"

#include <array>
#include <atomic>

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench {
namespace {

constexpr std::array<std::string_view, 5> kNames{"sse2", "avx2", "avx512", "native", "generic"};

std::vector<Isa> detect_levels() {
#if DAMPBENCH_ISA_DISPATCH
  // __builtin_cpu_supports also checks that the OS saves the vector registers (XCR0). GCC knows the levels
  // by name (every feature of x86-64-v3/v4, LZCNT, MOVBE and F16C included); Clang 14 (the sanitizer build) does
  // not, nor those three features, so it checks the rest.
  __builtin_cpu_init();
  std::vector<Isa> levels{Isa::sse2};
#if defined(__clang__)
  const bool v3 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi") &&
                  __builtin_cpu_supports("bmi2") && __builtin_cpu_supports("popcnt") && __builtin_cpu_supports("sse4.2");
  const bool v4 = v3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
                  __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
                  __builtin_cpu_supports("avx512vl");
#else
  const bool v3 = __builtin_cpu_supports("x86-64-v3");
  const bool v4 = v3 && __builtin_cpu_supports("x86-64-v4");
#endif
  if (v3) levels.push_back(Isa::avx2);
  if (v4) levels.push_back(Isa::avx512);
  return levels;
#elif defined(DAMPBENCH_NATIVE_BUILD)
  return {Isa::native};
#else
  return {Isa::generic};
#endif
}

std::atomic<Isa>& active_level() {
  static std::atomic<Isa> level{best_isa()};
  return level;
}

std::atomic<bool>& chosen_by_user() {
  static std::atomic<bool> chosen{false};
  return chosen;
}

std::string level_list() {
  std::string list;
  for (Isa i : supported_isas()) list += (list.empty() ? "" : ", ") + std::string(isa_name(i));
  return list;
}

}  // namespace

std::string_view isa_name(Isa isa) { return kNames[static_cast<std::size_t>(isa)]; }

std::optional<Isa> parse_isa(std::string_view name) {
  for (std::size_t i = 0; i < kNames.size(); ++i)
    if (kNames[i] == name) return static_cast<Isa>(i);
  return std::nullopt;
}

const std::vector<Isa>& supported_isas() {
  static const std::vector<Isa> levels = detect_levels();
  return levels;
}

Isa best_isa() { return supported_isas().back(); }

Isa active_isa() { return active_level().load(std::memory_order_relaxed); }

void select_isa(Isa isa) {
  for (Isa i : supported_isas())
    if (i == isa) {
      active_level().store(isa, std::memory_order_relaxed);
      return;
    }
  throw InputError(fmt::format("vector instruction set '{}' is not available with this build on this CPU (available: {})",
                               isa_name(isa), level_list()));
}

void select_isa(std::string_view name, std::string_view where) {
  const auto isa = parse_isa(name);
  if (!isa)
    throw InputError(fmt::format("{}: expected one of {} (the vector instruction sets of this build on this CPU), got '{}'",
                                 where, level_list(), name));
  try {
    select_isa(*isa);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", where, e.what()));
  }
  chosen_by_user().store(true, std::memory_order_relaxed);
}

bool isa_chosen_by_user() { return chosen_by_user().load(std::memory_order_relaxed); }

std::string isa_summary() { return fmt::format("{} (of {})", isa_name(active_isa()), level_list()); }

}  // namespace dampbench
