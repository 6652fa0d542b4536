// RBF kernel, the bordered LS-SVM system by Cholesky, and the spectral factor that reuses one
// eigendecomposition of K for many c (engine/lssvm/lssvm.hpp).
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Jacobi>
#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/vector_math.hpp"
#include "engine/lssvm/lssvm.hpp"

namespace dampbench::lssvm {
namespace {

void check_sigma(double sigma) {
  if (!(sigma > 0) || !std::isfinite(sigma)) throw InputError(fmt::format("lssvm: sigma must be positive, got {}", sigma));
}

void check_c(double c) {
  if (!(c > 0) || !std::isfinite(c)) throw InputError(fmt::format("lssvm: c must be positive, got {}", c));
}

void check_system(const Eigen::MatrixXd& K, const Eigen::VectorXd& y) {
  if (K.rows() == 0) throw InputError("lssvm: empty training set (no samples to solve for)");
  if (K.rows() != K.cols() || K.rows() != y.size())
    throw InputError(fmt::format("lssvm: kernel matrix is {}x{} but there are {} targets", K.rows(), K.cols(), y.size()));
}


/// One implicit symmetric QR step with the Wilkinson shift on the unreduced block [start, end] of the
/// tridiagonal (diag, sub), applying every rotation G_k on the right of W (W ← W·G_k). Same arithmetic as
/// Eigen 3.4's internal tridiagonal_qr_step (Golub & Van Loan, Alg. 8.3.2), with W in place of Q.
void qr_step(double* diag, double* sub, Eigen::Index start, Eigen::Index end, Eigen::MatrixXd& W) {
  const double td = (diag[end - 1] - diag[end]) * 0.5;
  const double e = sub[end - 1];
  double mu = diag[end];
  if (td == 0) {
    mu -= std::abs(e);
  } else if (e != 0) {
    const double e2 = e * e;
    const double h = std::hypot(td, e);
    if (e2 == 0)
      mu -= e / ((td + (td > 0 ? h : -h)) / e);
    else
      mu -= e2 / (td + (td > 0 ? h : -h));
  }
  double x = diag[start] - mu;
  double z = sub[start];
  for (Eigen::Index k = start; k < end && z != 0; ++k) {
    Eigen::JacobiRotation<double> rot;
    rot.makeGivens(x, z);
    const double c = rot.c(), s = rot.s();
    const double sdk = s * diag[k] + c * sub[k];
    const double dkp1 = s * sub[k] + c * diag[k + 1];
    diag[k] = c * (c * diag[k] - s * sub[k]) - s * (c * sub[k] - s * diag[k + 1]);
    diag[k + 1] = s * sdk + c * dkp1;
    sub[k] = c * sdk - s * dkp1;
    if (k > start) sub[k - 1] = c * sub[k - 1] - s * z;
    x = sub[k];
    if (k < end - 1) {
      z = -s * sub[k + 1];
      sub[k + 1] = c * sub[k + 1];
    }
    W.applyOnTheRight(k, k + 1, rot);
  }
}

/// Eigenvalues of the symmetric tridiagonal (diag, sub) into diag; rotations applied to W. Deflation and
/// iteration limit as Eigen's SelfAdjointEigenSolver (the kernel matrix needs no scaling: |K_ij| ≤ 1).
bool symmetric_tridiagonal_qr(Eigen::VectorXd& diag, Eigen::VectorXd& sub, Eigen::MatrixXd& W) {
  const Eigen::Index n = diag.size();
  Eigen::Index end = n - 1, start = 0, iterations = 0;
  const double as_zero = std::numeric_limits<double>::min();
  const double precision_inv = 1.0 / std::numeric_limits<double>::epsilon();
  while (end > 0) {
    for (Eigen::Index i = start; i < end; ++i) {
      if (std::abs(sub[i]) < as_zero) {
        sub[i] = 0;
      } else {
        const double scaled = precision_inv * sub[i];
        if (scaled * scaled <= std::abs(diag[i]) + std::abs(diag[i + 1])) sub[i] = 0;
      }
    }
    while (end > 0 && sub[end - 1] == 0) --end;
    if (end <= 0) break;
    if (++iterations > 30 * n) return false;
    start = end - 1;
    while (start > 0 && sub[start - 1] != 0) --start;
    qr_step(diag.data(), sub.data(), start, end, W);
  }
  return true;
}

}  // namespace

void rbf_kernel_column(const Eigen::MatrixXd& A, const double* b, double inv_sigma2, double* out, Eigen::Index count) {
  const Eigen::Index dim = A.rows();
  for (Eigen::Index i = 0; i < count; ++i) {
    const double* a = A.col(i).data();
    double s = 0;
    for (Eigen::Index k = 0; k < dim; ++k) {
      const double d = a[k] - b[k];
      s += d * d;
    }
    out[i] = -s * inv_sigma2;
  }
#pragma omp simd
  for (Eigen::Index i = 0; i < count; ++i) out[i] = std::exp(out[i]);
}

Eigen::MatrixXd rbf_kernel(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double sigma) {
  check_sigma(sigma);
  if (A.rows() != B.rows())
    throw InputError(fmt::format("lssvm: regressors of length {} and {} in one kernel", A.rows(), B.rows()));
  const double inv_sigma2 = 1.0 / (sigma * sigma);
  Eigen::MatrixXd K(A.cols(), B.cols());
  for (Eigen::Index j = 0; j < B.cols(); ++j) rbf_kernel_column(A, B.col(j).data(), inv_sigma2, K.col(j).data(), A.cols());
  return K;
}

Eigen::MatrixXd rbf_kernel(const Eigen::MatrixXd& X, double sigma) {
  check_sigma(sigma);
  const double inv_sigma2 = 1.0 / (sigma * sigma);
  const Eigen::Index n = X.cols();
  Eigen::MatrixXd K(n, n);
  // Upper triangle column by column (rows 0 .. j), mirrored: K is exactly symmetric with K_jj = 1.
  for (Eigen::Index j = 0; j < n; ++j) {
    rbf_kernel_column(X, X.col(j).data(), inv_sigma2, K.col(j).data(), j);
    K(j, j) = 1.0;
  }
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = j + 1; i < n; ++i) K(i, j) = K(j, i);
  return K;
}

Coefficients solve_bordered(const Eigen::MatrixXd& K, const Eigen::VectorXd& y, double c) {
  return solve_bordered(Eigen::MatrixXd(K), y, c);
}

Coefficients solve_bordered(Eigen::MatrixXd&& K, const Eigen::VectorXd& y, double c) {
  check_c(c);
  check_system(K, y);
  Eigen::MatrixXd H = std::move(K);  // H = K + I/c in K's storage: no second N × N matrix
  H.diagonal().array() += 1.0 / c;
  const Eigen::VectorXd diagonal = H.diagonal();
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(y.size());
  Eigen::VectorXd eta, nu;
  Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(H);  // in place: overwrites the lower triangle only
  if (llt.info() == Eigen::Success) {
    eta = llt.solve(ones);
    nu = llt.solve(y);
  } else {  // K + I/c is SPD in exact arithmetic; rounding with a huge c may defeat Cholesky
    Eigen::MatrixXd restored = H.selfadjointView<Eigen::Upper>();  // from the untouched upper triangle
    restored.diagonal() = diagonal;
    Eigen::LDLT<Eigen::MatrixXd> ldlt(restored);
    eta = ldlt.solve(ones);
    nu = ldlt.solve(y);
  }
  Coefficients out;
  out.b = nu.sum() / eta.sum();
  out.alpha = nu - out.b * eta;
  return out;
}

// ---- SpectralFactor ---------------------------------------------------------------------------------------------

SpectralFactor::SpectralFactor(const Eigen::MatrixXd& K, const Eigen::VectorXd& y, const Eigen::MatrixXd& cross,
                               bool keep_vectors)
    : cross_rows_(static_cast<int>(cross.rows())), keep_vectors_(keep_vectors) {
  check_system(K, y);
  const Eigen::Index n = K.rows();
  if (cross.rows() > 0 && cross.cols() != n)
    throw InputError(fmt::format("lssvm: cross kernel has {} columns for {} training points", cross.cols(), n));
  Eigen::Tridiagonalization<Eigen::MatrixXd> tri(K);
  Eigen::VectorXd diag = tri.diagonal();
  Eigen::VectorXd sub = tri.subDiagonal();

  // Probes z (columns): y, 1, the cross rows, the unit vectors. Rows of rotated_ become (Qᵀz)ᵀ = zᵀ·V·S,
  // where K = V T Vᵀ (Householder) and T = S Λ Sᵀ (the rotations of the QR iteration).
  const Eigen::Index m = cross.rows();
  const Eigen::Index probes = 2 + m + (keep_vectors ? n : 0);
  Eigen::MatrixXd Z(n, probes);
  Z.col(0) = y;
  Z.col(1).setOnes();
  if (m > 0) Z.middleCols(2, m) = cross.transpose();
  if (keep_vectors) Z.rightCols(n).setIdentity();
  const Eigen::MatrixXd VtZ = tri.matrixQ().transpose() * Z;
  rotated_ = VtZ.transpose();
  ok_ = symmetric_tridiagonal_qr(diag, sub, rotated_);
  lambda_ = std::move(diag);
}

double SpectralFactor::coefficients_in_eigenbasis(double c, Eigen::VectorXd& g) const {
  check_c(c);
  const Eigen::Index n = lambda_.size();
  const double inv_c = 1.0 / c;
  g.resize(n);
  double num = 0, den = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double d = 1.0 / (lambda_[k] + inv_c);
    const double u = rotated_(0, k), w = rotated_(1, k);
    g[k] = d;
    num += d * w * u;
    den += d * w * w;
  }
  const double b = num / den;
  for (Eigen::Index k = 0; k < n; ++k) g[k] *= rotated_(0, k) - b * rotated_(1, k);
  return b;
}

double SpectralFactor::bias(double c) const {
  Eigen::VectorXd g;
  return coefficients_in_eigenbasis(c, g);
}

double SpectralFactor::training_sse(double c) const {
  Eigen::VectorXd g;
  coefficients_in_eigenbasis(c, g);
  return g.squaredNorm() / (c * c);
}

Eigen::VectorXd SpectralFactor::cross_predictions(double c) const {
  Eigen::VectorXd g;
  const double b = coefficients_in_eigenbasis(c, g);
  Eigen::VectorXd f = rotated_.middleRows(2, cross_rows_) * g;
  f.array() += b;
  return f;
}

double SpectralFactor::cross_sse(double c, const Eigen::VectorXd& y_cross) const {
  if (y_cross.size() != cross_rows_)
    throw InputError(fmt::format("lssvm: {} cross targets for {} cross points", y_cross.size(), cross_rows_));
  return (y_cross - cross_predictions(c)).squaredNorm();
}

Coefficients SpectralFactor::solve(double c) const {
  if (!keep_vectors_) throw InputError("lssvm: SpectralFactor::solve needs the eigenvectors (keep_vectors)");
  Eigen::VectorXd g;
  Coefficients out;
  out.b = coefficients_in_eigenbasis(c, g);
  out.alpha = rotated_.bottomRows(lambda_.size()) * g;
  return out;
}

}  // namespace dampbench::lssvm
