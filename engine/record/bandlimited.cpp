#include "engine/record/bandlimited.hpp"

#include <complex>

#include <fmt/format.h>
#include <unsupported/Eigen/FFT>

#include "engine/common/error.hpp"

namespace dampbench {

std::vector<double> upsample_periodic(std::span<const double> x, int factor) {
  const std::size_t n = x.size(), m = n * static_cast<std::size_t>(factor);
  if (factor < 1 || n < 2) throw InputError(fmt::format("upsample_periodic: {} samples by {}; expected at least 2 samples and a factor of at least 1", n, factor));
  if (factor == 1) return {x.begin(), x.end()};
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> spectrum, wide(m);
  fft.fwd(spectrum, std::vector<double>(x.begin(), x.end()));
  // Non-negative frequencies to the front, negative ones to the back; an even N's Nyquist bin is split between
  // +N/2 and −N/2 (as interpft), which keeps the result real.
  const std::size_t half = n / 2;
  for (std::size_t k = 0; k < (n + 1) / 2; ++k) wide[k] = spectrum[k];
  for (std::size_t k = 1; k < (n + 1) / 2; ++k) wide[m - k] = spectrum[n - k];
  if (n % 2 == 0) {
    wide[half] = 0.5 * spectrum[half];
    wide[m - half] = 0.5 * spectrum[half];
  }
  std::vector<std::complex<double>> fine;
  fft.inv(fine, wide);
  std::vector<double> out(m);
  for (std::size_t i = 0; i < m; ++i) out[i] = fine[i].real() * static_cast<double>(factor);
  return out;
}

std::vector<double> upsample_spline(std::span<const double> x, int factor) {
  const std::size_t n = x.size();
  if (factor < 1 || n < 4) throw InputError(fmt::format("upsample_spline: {} samples by {}; expected at least 4 samples and a factor of at least 1", n, factor));
  // Second derivatives M_k (unit spacing) of the not-a-knot spline: M_{k−1} + 4M_k + M_{k+1} = 6Δ²x_k inside, and
  // M_0 − 2M_1 + M_2 = 0, M_{n−3} − 2M_{n−2} + M_{n−1} = 0 (a continuous third derivative at the second and the
  // second-to-last knots), eliminated into the first and last interior rows to keep the system tridiagonal.
  const std::size_t inner = n - 2;
  std::vector<double> lower(inner, 1.0), diag(inner, 4.0), upper(inner, 1.0), rhs(inner);
  for (std::size_t k = 0; k < inner; ++k) rhs[k] = 6 * (x[k] - 2 * x[k + 1] + x[k + 2]);
  // M_0 = 2M_1 − M_2: row 0 becomes 6M_1 + 0·M_2; M_{n−1} = 2M_{n−2} − M_{n−3}: last row becomes 0·M_{n−3} + 6M_{n−2}.
  diag[0] = 6;
  upper[0] = 0;
  diag[inner - 1] = 6;
  lower[inner - 1] = 0;
  for (std::size_t k = 1; k < inner; ++k) {  // Thomas algorithm
    const double w = lower[k] / diag[k - 1];
    diag[k] -= w * upper[k - 1];
    rhs[k] -= w * rhs[k - 1];
  }
  std::vector<double> M(n);
  M[inner] = rhs[inner - 1] / diag[inner - 1];
  for (std::size_t k = inner - 1; k-- > 0;) M[k + 1] = (rhs[k] - upper[k] * M[k + 2]) / diag[k];
  M[0] = 2 * M[1] - M[2];
  M[n - 1] = 2 * M[n - 2] - M[n - 3];
  std::vector<double> out((n - 1) * static_cast<std::size_t>(factor) + 1);
  for (std::size_t k = 0; k + 1 < n; ++k)
    for (int j = 0; j < factor; ++j) {
      const double s = static_cast<double>(j) / factor, r = 1 - s;
      out[k * static_cast<std::size_t>(factor) + static_cast<std::size_t>(j)] =
          r * x[k] + s * x[k + 1] + ((r * r * r - r) * M[k] + (s * s * s - s) * M[k + 1]) / 6;
    }
  out.back() = x[n - 1];
  return out;
}

}  // namespace dampbench
