#pragma once
// Reconstructions of a uniformly sampled input between its samples, for models that integrate faster than the
// record's rate (the force-driven structures of models/structure.cpp).
#include <span>
#include <vector>

namespace dampbench {

/// One period of a periodic, band-limited signal sampled at N points, at factor·N points (MATLAB interpft): exact
/// when the signal has no content at or above N/2 cycles per period. Via Eigen's FFT (kissfft: any N).
std::vector<double> upsample_periodic(std::span<const double> x, int factor);

/// Cubic spline (not-a-knot end conditions, as MATLAB's spline) through uniformly spaced samples, evaluated at
/// factor× the rate: out[k·factor + j] = s(t_k + j·h/factor), length (N − 1)·factor + 1.
std::vector<double> upsample_spline(std::span<const double> x, int factor);

}  // namespace dampbench
