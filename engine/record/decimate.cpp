#include "engine/record/decimate.hpp"

#include <cmath>
#include <cstddef>
#include <numbers>
#include <string>

#include "engine/common/error.hpp"

namespace dampbench {
namespace {

/// sin(πu)/(πu), exactly 0 at the non-zero integers: a half-band filter's even taps are then exact zeros, as the
/// ideal response has them, rather than rounding noise of sin(kπ).
double sinc(double u) {
  if (u == 0) return 1;
  if (u == std::round(u)) return 0;
  return std::sin(std::numbers::pi * u) / (std::numbers::pi * u);
}

/// One output of the causal filter b over ext at position p (needs p ≥ b.size() − 1).
double filter_at(const std::vector<double>& b, const std::vector<double>& ext, std::size_t p) {
  double sum = 0;
  for (std::size_t i = 0; i < b.size(); ++i) sum += b[i] * ext[p - i];
  return sum;
}

}  // namespace

std::vector<double> fir1_lowpass(int order, double cutoff_nyquist) {
  if (order < 1) throw InputError("fir1_lowpass: order " + std::to_string(order) + ", expected at least 1");
  if (!(cutoff_nyquist > 0 && cutoff_nyquist < 1))
    throw InputError("fir1_lowpass: cutoff " + std::to_string(cutoff_nyquist) +
                     " of the Nyquist frequency, expected a value in (0, 1)");
  const auto taps = static_cast<std::size_t>(order) + 1;
  std::vector<double> b(taps);
  // MATLAB's hamming(n) computes the first half and mirrors it; doing the same keeps b symmetric bit for bit.
  for (std::size_t i = 0; i <= static_cast<std::size_t>(order) / 2; ++i) {
    const double window = 0.54 - 0.46 * std::cos(2 * std::numbers::pi * static_cast<double>(i) / order);
    const double offset = static_cast<double>(i) - 0.5 * order;
    b[i] = b[taps - 1 - i] = window * cutoff_nyquist * sinc(cutoff_nyquist * offset);
  }
  double sum = 0;
  for (double tap : b) sum += tap;
  for (double& tap : b) tap /= sum;
  return b;
}

std::vector<double> decimate_fir(std::span<const double> x, int factor, int order) {
  if (factor < 1) throw InputError("decimate: factor " + std::to_string(factor) + ", expected at least 1");
  if (factor == 1) return {x.begin(), x.end()};
  if (order < 1) throw InputError("decimate: filter order " + std::to_string(order) + ", expected at least 1");
  const std::size_t nd = x.size();
  const auto nfilt = static_cast<std::size_t>(order) + 1;
  if (nd < 2 * nfilt + 1)
    throw InputError("decimate: " + std::to_string(nd) + " samples, expected at least " +
                     std::to_string(2 * nfilt + 1) + " for the end padding of a filter of order " +
                     std::to_string(order));
  const std::vector<double> b = fir1_lowpass(order, 1.0 / factor);
  // ext = [2·x(1) − x(nfilt+1:−1:2), x, 2·x(nd) − x(nd−1:−1:nd−2·nfilt)] in 0-based indices.
  std::vector<double> ext;
  ext.reserve(3 * nfilt + nd);
  for (std::size_t k = 0; k < nfilt; ++k) ext.push_back(2 * x[0] - x[nfilt - k]);
  ext.insert(ext.end(), x.begin(), x.end());
  for (std::size_t k = 0; k < 2 * nfilt; ++k) ext.push_back(2 * x[nd - 1] - x[nd - 2 - k]);
  // list's first index, round(gd + 1.25) with gd = order/2: order/2 + 1 for even order, (order + 1)/2 + 1 for odd.
  const std::size_t first = static_cast<std::size_t>(order) / 2 + 1 + static_cast<std::size_t>(order % 2);
  const auto r = static_cast<std::size_t>(factor);
  const std::size_t nout = (nd + r - 1) / r;
  std::vector<double> out(nout);
  for (std::size_t j = 0; j < nout; ++j) out[j] = filter_at(b, ext, nfilt + first - 1 + j * r);
  return out;
}

std::vector<double> decimate_fir_cascade(std::span<const double> x, std::span<const int> factors) {
  std::vector<double> signal(x.begin(), x.end());
  for (std::size_t step = 0; step < factors.size(); ++step) {
    try {
      signal = decimate_fir(signal, factors[step]);
    } catch (const InputError& e) {
      throw InputError("decimation step " + std::to_string(step + 1) + " of " + std::to_string(factors.size()) +
                       " (factor " + std::to_string(factors[step]) + "): " + e.what());
    }
  }
  return signal;
}

}  // namespace dampbench
