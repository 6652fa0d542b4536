#pragma once
// Vector math for candidate-lane loops. Declaring these functions with the `simd` attribute tells GCC
// that glibc's libmvec has vector variants (_ZGVbN2v_exp, _ZGVdN4v_exp, ...), so a `#pragma omp simd`
// loop that calls std::exp vectorizes instead of calling the scalar function lane by lane. glibc's own
// math.h only does this under -ffast-math, which we refuse (it would hide NaN and Inf, and a blown-up
// candidate must be detected). Needs -fno-math-errno (set on dampbench_flags) and -lmvec.
#include <cmath>

extern "C" {
__attribute__((simd("notinbranch"))) double exp(double) noexcept;
__attribute__((simd("notinbranch"))) double log(double) noexcept;
__attribute__((simd("notinbranch"))) double pow(double, double) noexcept;
__attribute__((simd("notinbranch"))) double sin(double) noexcept;
__attribute__((simd("notinbranch"))) double cos(double) noexcept;
__attribute__((simd("notinbranch"))) double tanh(double) noexcept;
__attribute__((simd("notinbranch"))) double atan(double) noexcept;
}

namespace dampbench {

/// sgn(v) with sgn(0) = 0 (MODELS.md notation). Written with bool→double conversions: the int
/// difference (v > 0) − (v < 0) stops GCC from vectorizing a lane loop ("no vectype").
inline double sign(double v) { return static_cast<double>(v > 0.0) - static_cast<double>(v < 0.0); }

/// log|v| clamped so that |v|^α = exp(α·log|v|) stays finite for v = 0 and any α ≥ 0; the caller
/// multiplies by sgn(v) = 0 there, so the clamp never shows in a result.
inline double log_abs_clamped(double v) { return std::log(std::fabs(v) + 1e-300); }

}  // namespace dampbench
