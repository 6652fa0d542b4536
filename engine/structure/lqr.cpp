#include "engine/structure/lqr.hpp"

#include <cmath>

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench::structure {

StateSpace state_space(const Building& b, const Modes& modes) {
  const int n = b.storeys();
  const Eigen::VectorXd inv_m = b.mass_kg.cwiseInverse();
  StateSpace ss;
  ss.A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  ss.A.topRightCorner(n, n).setIdentity();
  ss.A.bottomLeftCorner(n, n) = -(inv_m.asDiagonal() * b.stiffness_N_m);
  ss.A.bottomRightCorner(n, n) = -(inv_m.asDiagonal() * modes.damping_N_s_m);
  ss.B = Eigen::VectorXd::Zero(2 * n);
  ss.B[n + b.damper_storey - 1] = -inv_m[b.damper_storey - 1];
  return ss;
}

Eigen::MatrixXd energy_weight(const Building& b) {
  const int n = b.storeys();
  Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  Q.topLeftCorner(n, n) = b.stiffness_N_m;
  Q.bottomRightCorner(n, n) = b.mass_kg.asDiagonal();
  return Q;
}

namespace {

/// P of AᵀP + PA = −W (A stable), by the Kronecker form (I ⊗ Aᵀ + Aᵀ ⊗ I)·vec(P) = −vec(W).
Eigen::MatrixXd lyapunov(const Eigen::MatrixXd& A, const Eigen::MatrixXd& W) {
  const auto m = A.rows();
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(m, m);
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(m * m, m * m);
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::Index j = 0; j < m; ++j) {
      L.block(i * m, j * m, m, m) += I(i, j) * A.transpose();
      L.block(i * m, j * m, m, m) += A(j, i) * I;
    }
  const Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(W.data(), m * m);
  const Eigen::VectorXd p = L.fullPivLu().solve(-w);
  const Eigen::MatrixXd P = Eigen::Map<const Eigen::MatrixXd>(p.data(), m, m);
  return 0.5 * (P + P.transpose());
}

}  // namespace

LqrGain lqr_gain(const StateSpace& ss, const Eigen::MatrixXd& Q, double R) {
  const auto m = ss.A.rows();
  if (!(R > 0) || !std::isfinite(R)) throw InputError(fmt::format("--lqr-r: expected a force weight > 0, got {}", R));
  if (Q.rows() != m || Q.cols() != m || !Q.allFinite() || (Q - Q.transpose()).cwiseAbs().maxCoeff() > 1e-9 * Q.cwiseAbs().maxCoeff())
    throw InputError(fmt::format("LQR: Q: expected a symmetric {}x{} matrix of finite numbers", m, m));
  LqrGain out;
  out.G = Eigen::RowVectorXd::Zero(m);
  constexpr int kMaxIterations = 100;
  for (out.iterations = 1; out.iterations <= kMaxIterations; ++out.iterations) {
    const Eigen::MatrixXd Ak = ss.A - ss.B * out.G;
    out.P = lyapunov(Ak, Q + out.G.transpose() * R * out.G);
    const Eigen::RowVectorXd next = ss.B.transpose() * out.P / R;
    const double change = (next - out.G).norm();
    out.G = next;
    if (change <= 1e-13 * out.G.norm()) break;
  }
  const Eigen::MatrixXd residual =
      ss.A.transpose() * out.P + out.P * ss.A - out.P * ss.B * ss.B.transpose() * out.P / R + Q;
  out.riccati_residual = residual.norm() / Q.norm();
  return out;
}

}  // namespace dampbench::structure
