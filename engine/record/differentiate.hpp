#pragma once
// Numerical differentiation of sampled signals (velocity and acceleration from displacement).
#include <vector>

namespace dampbench {

/// d y / d t by the derivative of cubic Lagrange interpolants (a 3rd-order scheme, fvd paper eq. 7 text:
/// "numerical differentiation ... with a 3rd order algorithm"). Interior points average the two 4-point
/// stencils {i-2..i+1} and {i-1..i+2} (on a uniform grid this is the 4th-order central difference);
/// the first two and last two points use one-sided 4-point stencils. Works on non-uniform t.
/// Requires t.size() == y.size() >= 4 (throws std::invalid_argument otherwise — a programming error,
/// the loader checks sizes).
std::vector<double> differentiate_3rd_order(const std::vector<double>& t, const std::vector<double>& y);

}  // namespace dampbench
