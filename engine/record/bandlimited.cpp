#include "engine/record/bandlimited.hpp"

#include <complex>
#include <cstddef>
#include <string>
#include <unsupported/Eigen/FFT>

#include "engine/common/error.hpp"

namespace dampbench {
namespace {

void check_upsample_input(const char* where, std::size_t n, std::size_t minimum, int factor) {
  if (factor < 1) throw InputError(std::string(where) + ": factor " + std::to_string(factor) + ", expected at least 1");
  if (n < minimum)
    throw InputError(std::string(where) + ": " + std::to_string(n) + " samples, expected at least " +
                     std::to_string(minimum));
}

/// Second derivatives (per sample², h = 1) of the not-a-knot spline through x, x.size() ≥ 2.
/// On a uniform grid the not-a-knot conditions M0 = 2·M1 − M2 and M(n−1) = 2·M(n−2) − M(n−3) turn the first and
/// last equations M(i−1) + 4·M(i) + M(i+1) = d(i) into 6·M1 = d1 and 6·M(n−2) = d(n−2), so only the rows in
/// between form a tridiagonal system, solved by the Thomas algorithm (diagonally dominant: stable without pivots).
std::vector<double> not_a_knot_moments(std::span<const double> x) {
  const std::size_t n = x.size();
  std::vector<double> m(n, 0.0);
  if (n == 2) return m;  // the line through two points
  std::vector<double> d(n, 0.0);
  for (std::size_t i = 1; i + 1 < n; ++i) d[i] = 6 * (x[i - 1] - 2 * x[i] + x[i + 1]);
  if (n == 3) {  // both conditions are the same equation: the parabola through the three points
    m[0] = m[1] = m[2] = d[1] / 6;
    return m;
  }
  m[1] = d[1] / 6;
  m[n - 2] = d[n - 2] / 6;
  // Rows i = 2 … n−3: M(i−1) + 4·M(i) + M(i+1) = d(i), with M1 and M(n−2) known.
  if (n > 4) {
    d[2] -= m[1];
    d[n - 3] -= m[n - 2];
    std::vector<double> c(n, 0.0);  // the eliminated super-diagonal
    double pivot = 4;
    c[2] = 1 / pivot;
    d[2] /= pivot;
    for (std::size_t i = 3; i + 2 < n; ++i) {
      pivot = 4 - c[i - 1];
      c[i] = 1 / pivot;
      d[i] = (d[i] - d[i - 1]) / pivot;
    }
    m[n - 3] = d[n - 3];
    for (std::size_t i = n - 4; i >= 2; --i) m[i] = d[i] - c[i] * m[i + 1];
  }
  m[0] = 2 * m[1] - m[2];
  m[n - 1] = 2 * m[n - 2] - m[n - 3];
  return m;
}

}  // namespace

std::vector<double> upsample_periodic(std::span<const double> x, int factor) {
  check_upsample_input("upsample_periodic", x.size(), 1, factor);
  if (factor == 1) return {x.begin(), x.end()};
  const std::size_t n = x.size();
  const std::size_t ny = n * static_cast<std::size_t>(factor);
  using Complex = std::complex<double>;
  std::vector<Complex> samples(x.begin(), x.end());
  std::vector<Complex> spectrum;
  Eigen::FFT<double> fft;
  fft.fwd(spectrum, samples);
  // interpft's spectrum: bins below N/2 keep their places at both ends, zeros fill the middle, and an even N's
  // Nyquist bin goes half to +N/2 and half to −N/2 so that it stays a real cosine.
  std::vector<Complex> padded(ny, Complex(0, 0));
  padded[0] = spectrum[0];
  for (std::size_t k = 1; 2 * k < n; ++k) {
    padded[k] = spectrum[k];
    padded[ny - k] = spectrum[n - k];
  }
  if (n % 2 == 0) padded[n / 2] = padded[ny - n / 2] = spectrum[n / 2] / 2.0;
  std::vector<Complex> fine;
  fft.inv(fine, padded);  // scaled by 1/ny; interpft's factor ny/N makes it 1/N
  std::vector<double> out(ny);
  const double scale = static_cast<double>(factor);
  for (std::size_t i = 0; i < ny; ++i) out[i] = fine[i].real() * scale;
  return out;
}

std::vector<double> upsample_spline(std::span<const double> x, int factor) {
  check_upsample_input("upsample_spline", x.size(), 2, factor);
  const std::vector<double> m = not_a_knot_moments(x);
  const auto r = static_cast<std::size_t>(factor);
  const std::size_t n = x.size();
  std::vector<double> out((n - 1) * r + 1);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    for (std::size_t j = 0; j < r; ++j) {
      const double s = static_cast<double>(j) / factor;
      const double u = 1 - s;
      out[k * r + j] = u * x[k] + s * x[k + 1] + ((u * u * u - u) * m[k] + (s * s * s - s) * m[k + 1]) / 6;
    }
  }
  out.back() = x[n - 1];
  return out;
}

}  // namespace dampbench
