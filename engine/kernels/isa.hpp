#pragma once
// Runtime choice of the vector instruction set the lane kernels run with. One default build runs
// on any x86-64 CPU and uses the best level of the CPU it runs on:
//   sse2    x86-64 baseline (SSE2): 2 doubles per vector, libmvec's _ZGVb variants
//   avx2    x86-64-v3 (AVX2, FMA, BMI2): 4 doubles, _ZGVd variants
//   avx512  x86-64-v4 (AVX-512 F/CD/BW/DQ/VL): 8 doubles, _ZGVe variants
// A build with -DDAMPBENCH_NATIVE=ON has one level, "native" (whatever -march=native gives); a non-x86 build
// has one level, "generic".
//
// How: IsaClones<Body> compiles Body::run three times, with GCC/Clang function attributes
// target("arch=x86-64-v3") / target("arch=x86-64-v4") and flatten (everything Body::run calls is inlined
// into the clone and vectorized for its level; what cannot be inlined stays baseline code, so no
// instruction of a higher level leaks into code that runs on any CPU; Clang's flatten inlines one level
// only, so a Clang build's clones may call baseline code: slower, still correct). call() picks the clone of the active
// level. The compiler's own multiversioning (target_clones) would pick at load time with no way to choose a
// lower level; Google Highway's dynamic dispatch does the same job for kernels written in Highway's vector
// types, while ours are `omp simd` lane loops (engine/kernels/lane_kernel.hpp) whose vector math is
// libmvec, which the compiler selects per level by itself (engine/common/vector_math.hpp).
//
// Reproducibility: at one level the kernels (and the GAs' vector pow, optimizers/ga/operators.hpp) run the same
// instructions on every CPU that has it (one
// exception: libmvec's SSE2-level functions use SSE4.1 code where the CPU has it, as every x86-64 CPU since
// 2008 does), and the same bits for any thread count or batch split. Levels differ from each other in the last bits of
// vector exp/log/sin/... (libmvec's variants are different code; tests/unit/kernels/test_isa.cpp measures by how much), so
// the level is part of build_flags() (engine/sweep/fingerprint.hpp): a store resumes, merges and runs across
// MPI ranks on one level only, and `verify` re-runs at the store's level. (glibc's scalar libm, used outside
// the kernels, picks its code by CPU features too; the MPI fingerprint compares those.)
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace dampbench {

enum class Isa { sse2, avx2, avx512, native, generic };

/// "sse2", "avx2", "avx512", "native", "generic".
std::string_view isa_name(Isa isa);
/// The level named `name` (one of isa_name's), or nullopt.
std::optional<Isa> parse_isa(std::string_view name);

/// Levels this build can run on this CPU, lowest first (one entry for native and non-x86 builds).
const std::vector<Isa>& supported_isas();
/// The highest of supported_isas(): the level kernels run with unless select_isa chose another.
Isa best_isa();
/// The level the kernels run with now.
Isa active_isa();
/// Runs the kernels with `isa` from now on (call it before any evaluation starts, e.g. at start-up).
/// Throws InputError naming the supported levels if this CPU or build does not have it.
void select_isa(Isa isa);
/// select_isa(parse_isa(name)) with `where` (an option or variable name) in the error message: the user's choice
/// (--isa, DAMPBENCH_ISA), which isa_chosen_by_user() reports from then on.
void select_isa(std::string_view name, std::string_view where);
/// True once select_isa(name, where) succeeded: `verify` then keeps the user's level instead of the store's.
bool isa_chosen_by_user();
/// "avx512 (of sse2, avx2, avx512)": the active level and the supported ones, for --version and bench.
std::string isa_summary();

// A build may set DAMPBENCH_ISA_DISPATCH=0 (CMake option DAMPBENCH_ISA_DISPATCH=OFF): the kernels are then compiled
// once, for the baseline, as the one level "generic". The sanitizer build (fuzz targets included) does so: it checks
// the kernels' code, which is the same at every level, and one copy of each kernel compiles faster than three.
#ifndef DAMPBENCH_ISA_DISPATCH
#if defined(__x86_64__) && !defined(DAMPBENCH_NATIVE_BUILD)
#define DAMPBENCH_ISA_DISPATCH 1
#else
#define DAMPBENCH_ISA_DISPATCH 0
#endif
#endif

// GCC 12's partial redundancy elimination (PRE, -ftree-pre), run over a whole flattened time loop, helps some
// bodies and hurts others, so a Body chooses: with `static constexpr bool kWithoutTreePre = true` its clones
// are compiled with gnu::optimize("no-tree-pre"). Without PRE the algebraic kernels run faster, so
// AlgebraicKernel asks for it; with PRE the ODE kernels do (docs/performance.md, "Measurements behind code
// choices", has the numbers; perf shows the same libmvec calls either way, so the cause is not known). Either
// way the same floating-point operations run, so the bits do not change. Clang has no optimize attribute and
// ignores the choice.
template <class Body>
inline constexpr bool clones_without_tree_pre = requires { requires Body::kWithoutTreePre; };

#if DAMPBENCH_ISA_DISPATCH
/// The three clones of Body::run (flattened, one per level) with the extra function attributes `...`.
#define DAMPBENCH_ISA_CLONE_SET(NAME, ...)                                                          \
  template <class Body>                                                                            \
  struct NAME {                                                                                    \
    template <class... Args>                                                                       \
    [[gnu::target("arch=x86-64-v4"), gnu::flatten __VA_OPT__(, ) __VA_ARGS__]] static void avx512( \
        Args... args) {                                                                            \
      Body::run(args...);                                                                          \
    }                                                                                              \
    template <class... Args>                                                                       \
    [[gnu::target("arch=x86-64-v3"), gnu::flatten __VA_OPT__(, ) __VA_ARGS__]] static void avx2(   \
        Args... args) {                                                                            \
      Body::run(args...);                                                                          \
    }                                                                                              \
    template <class... Args>                                                                       \
    [[gnu::flatten __VA_OPT__(, ) __VA_ARGS__]] static void sse2(Args... args) {                   \
      Body::run(args...);                                                                          \
    }                                                                                              \
  };
namespace isa_clones {
DAMPBENCH_ISA_CLONE_SET(WithTreePre)
#if defined(__clang__)
DAMPBENCH_ISA_CLONE_SET(WithoutTreePre)
#else
DAMPBENCH_ISA_CLONE_SET(WithoutTreePre, gnu::optimize("no-tree-pre"))
#endif
}  // namespace isa_clones
#undef DAMPBENCH_ISA_CLONE_SET
#endif

/// Body::run(args...) compiled once per level; call() runs the active level's copy.
template <class Body>
struct IsaClones {
  template <class... Args>
  static void call(Args... args) {
#if DAMPBENCH_ISA_DISPATCH
    using Clones = std::conditional_t<clones_without_tree_pre<Body>, isa_clones::WithoutTreePre<Body>,
                                      isa_clones::WithTreePre<Body>>;
    switch (active_isa()) {
      case Isa::avx512: return Clones::avx512(args...);
      case Isa::avx2: return Clones::avx2(args...);
      default: return Clones::sse2(args...);
    }
#else
    Body::run(args...);
#endif
  }
};

}  // namespace dampbench
