#pragma once
// The linear-quadratic regulator of a building with one damper force (Dyke et al. 1996's clipped-optimal
// control starts from it): states z = [u; u̇] (storey displacements relative to the ground and their rates),
// ż = A·z + B·f with f the damper's force on its storey, cost ∫ zᵀQz + R·f² dt, desired force f = −G·z.
#include <Eigen/Dense>

#include "engine/structure/building.hpp"

namespace dampbench::structure {

/// A and B of the building: A = [[0, I], [−M⁻¹K, −M⁻¹C]], B = [0; −M⁻¹·e_d] (the damper pushes its storey
/// back with its force).
struct StateSpace {
  Eigen::MatrixXd A;
  Eigen::VectorXd B;
};
StateSpace state_space(const Building& b, const Modes& modes);

/// The energy weight Q = blockdiag(K, M): zᵀQz is twice the building's strain and kinetic energy [J].
Eigen::MatrixXd energy_weight(const Building& b);

struct LqrGain {
  Eigen::RowVectorXd G;   ///< desired force f = −G·z
  Eigen::MatrixXd P;      ///< the Riccati solution
  int iterations = 0;
  double riccati_residual = 0;  ///< ‖AᵀP + PA − PBR⁻¹BᵀP + Q‖ / ‖Q‖
};

/// Solves the continuous Riccati equation by Kleinman's iteration from G = 0 (the damped building is stable),
/// each step a Lyapunov equation solved as a linear system: exact to rounding for the few storeys of a
/// reference building. InputError for R ≤ 0 or a Q that is not symmetric positive semi-definite of size 2n.
LqrGain lqr_gain(const StateSpace& ss, const Eigen::MatrixXd& Q, double R);

}  // namespace dampbench::structure
