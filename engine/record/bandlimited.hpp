#pragma once
// Band-limited reconstruction of a sampled input at a finer rate, for models that integrate between the record's
// samples: FFT interpolation for one period of a periodic record (exact for a multisine below Nyquist), a
// not-a-knot cubic spline otherwise.
#include <span>
#include <vector>

namespace dampbench {

/// One period of a periodic, band-limited signal sampled at N points, at factor·N points (MATLAB interpft):
/// exact when the signal has no content at or above N/2 cycles per period. For even N the Nyquist bin is split
/// evenly between +N/2 and −N/2 as interpft splits it. Via Eigen's FFT (unsupported/Eigen/FFT, kissfft: any N).
/// out[k·factor] reproduces x[k] up to rounding; factor 1 returns x unchanged.
std::vector<double> upsample_periodic(std::span<const double> x, int factor);

/// Cubic spline (not-a-knot end conditions, as MATLAB's spline/interp1 'spline') through uniformly spaced
/// samples, evaluated at factor× the rate: out[k·factor + j] = s(t_k + j·h/factor), length (N − 1)·factor + 1.
/// Two samples give the line through them and three the parabola, as MATLAB's spline does.
std::vector<double> upsample_spline(std::span<const double> x, int factor);

}  // namespace dampbench
