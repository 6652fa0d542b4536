#pragma once
// Vector math for candidate-lane loops. Declaring these functions with the `simd` attribute tells GCC
// that glibc's libmvec has vector variants (_ZGVbN2v_exp, _ZGVdN4v_exp, ...), so a `#pragma omp simd`
// loop that calls std::exp vectorizes instead of calling the scalar function lane by lane. glibc's own
// math.h only does this under -ffast-math, which we refuse (it would hide NaN and Inf, and a blown-up
// candidate must be detected). Needs -fno-math-errno (set on dampbench_flags) and -lmvec.
// Clang has no `simd` attribute: its builds (the sanitizer build) call the scalar functions in every lane,
// so a lane's bits there never depend on which lanes share its vector either.
#include <algorithm>
#include <cmath>

#if defined(__GNUC__) && !defined(__clang__)
extern "C" {
__attribute__((simd("notinbranch"))) double exp(double) noexcept;
__attribute__((simd("notinbranch"))) double log(double) noexcept;
__attribute__((simd("notinbranch"))) double pow(double, double) noexcept;
__attribute__((simd("notinbranch"))) double sin(double) noexcept;
__attribute__((simd("notinbranch"))) double cos(double) noexcept;
__attribute__((simd("notinbranch"))) double tanh(double) noexcept;
__attribute__((simd("notinbranch"))) double atan(double) noexcept;
__attribute__((simd("notinbranch"))) float expf(float) noexcept;
__attribute__((simd("notinbranch"))) float logf(float) noexcept;
}
#endif

namespace dampbench {

/// sgn(v) with sgn(0) = 0 (the papers' notation). Written with bool→double conversions: the int
/// difference (v > 0) − (v < 0) stops GCC from vectorizing a lane loop ("no vectype").
inline double sign(double v) { return static_cast<double>(v > 0.0) - static_cast<double>(v < 0.0); }

/// log|v| clamped so that |v|^α = exp(α·log|v|) stays finite for v = 0 and any α ≥ 0; the caller
/// multiplies by sgn(v) = 0 there, so the clamp never shows in a result.
inline double log_abs_clamped(double v) { return std::log(std::fabs(v) + 1e-300); }

/// log(|z| + 1e−100), the logarithm the state powers below use.
inline double log_abs_for_pow(double z) { return std::log(std::fabs(z) + 1e-100); }

/// |z|^n for 0 ≤ n ≤ 7, written exp(n·log(|z| + 1e−100)): one vector log and exp per lane.
/// Why 1e−100 and not 1e−300: libmvec's vector exp leaves its fast path for the whole vector when one
/// lane underflows (argument below −708) and calls scalar exp lane by lane; a state at exactly zero
/// (the start of every ODE lane, a reset lane) would give n·log(1e−300) < −708 for n > 1.03, 10 % of
/// mrd.spencer's time in `dampbench bench`. The offset changes |z|^n only where |z| < 1e−90, a zero
/// for any force. (Clamping the argument instead does not work: GCC folds exp(−708) and selects after
/// the call, so the vector exp still sees the raw argument.)
inline double abs_pow(double z, double n) { return std::exp(n * log_abs_for_pow(z)); }

/// exp of a lane: plain in double; in float with the argument floored at −80, above float's underflow (−87),
/// where libmvec would leave its fast path for the whole vector, as abs_pow(double) explains. e^−80 is a zero for
/// any force.
inline double lane_exp(double x) { return std::exp(x); }
inline float lane_exp(float x) { return std::exp(std::max(x, -80.0f)); }

/// The single-precision lanes' overloads (engine/kernels/lane_kernel.hpp, Float32).
inline float sign(float v) { return static_cast<float>(v > 0.0f) - static_cast<float>(v < 0.0f); }
/// |z|^n in float: lane_exp(n·log(|z| + 1e−30)), which differs from |z|^n only where that is below 2e−35.
inline float abs_pow(float z, float n) { return lane_exp(n * std::log(std::fabs(z) + 1e-30f)); }

}  // namespace dampbench
