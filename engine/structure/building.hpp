#pragma once
// A building of lumped storey masses for a damper to act in: masses, a condensed lateral
// stiffness matrix and modal damping ratios, as the UTFSM damper's own study gives its three reference buildings
// (../shared/data/README.md, "earthquakes/"). The damping matrix is the classical one with those ratios,
// C = M·Φ·diag(2ζᵢωᵢ)·Φᵀ·M for mass-normalized modes Φ (Chopra, Dynamics of Structures, §11.4).
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace dampbench::structure {

struct Building {
  std::string name;
  Eigen::VectorXd mass_kg;         ///< storey masses, ground floor first
  Eigen::MatrixXd stiffness_N_m;   ///< condensed lateral stiffness (symmetric positive definite)
  Eigen::VectorXd modal_damping;   ///< ζ of each mode, lowest frequency first
  int damper_storey = 1;           ///< the damper acts between the ground and this storey (1-based)

  [[nodiscard]] int storeys() const { return static_cast<int>(mass_kg.size()); }
};

/// The building's modes: natural circular frequencies [rad/s] ascending, mass-normalized shapes in columns, and
/// the classical damping matrix of its modal damping ratios.
struct Modes {
  Eigen::VectorXd omega_rad_s;
  Eigen::MatrixXd shapes;
  Eigen::MatrixXd damping_N_s_m;
};

/// InputError naming `where` and what was expected: positive finite masses, a square symmetric positive definite
/// stiffness of the masses' size, one damping ratio in [0, 1) per storey, the damper's storey within them.
void check_building(const Building& b, const std::string& where);

Modes modes_of(const Building& b);

/// A building from a TOML file:
///   name = "..."; mass_kg = [..]; stiffness_N_m = [[..], ..]; modal_damping = [..] (or one number for every
///   mode); damper_storey = 1
/// InputError "<path>: <key>: <expected>" for a missing key, a wrong type or a building check_building refuses.
Building read_building_file(const std::string& path);

}  // namespace dampbench::structure
