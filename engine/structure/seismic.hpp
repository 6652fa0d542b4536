#pragma once
// A building under a ground-acceleration record with an identified damper between the ground and one storey
//. The building steps by Newmark's average-acceleration rule (γ = 1/2, β = 1/4: unconditionally
// stable, no numerical damping) in storey displacements relative to the ground,
//   M·ü + C·u̇ + K·u = −M·1·ag − e_d·F,
// and the damper's states step with it (engine/model/stepper.hpp, fixed RK4 sub-steps on the step's motion). Its
// force F at the step's end depends on the storey's motion there, which depends on F: each step solves
// F = damper(x(F), v(F)) by secant iterations from the last force, restoring the damper's states before each try.
// The energies are summed by the trapezoid rule the scheme satisfies exactly (input = structural damping + damper
// work + kinetic + strain), so their balance checks the assembly, not the scheme.
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "engine/model/model.hpp"
#include "engine/structure/building.hpp"
#include "engine/structure/ground_motion.hpp"

namespace dampbench::structure {

/// The identified damper: a model with its parameters and the operating variables it runs at (passive).
struct Damper {
  const Model* model = nullptr;
  std::vector<double> params;
  std::map<std::string, double> variables;
  int substeps = 4;  ///< the damper's RK4 sub-steps per building step
};

/// Semi-active on/off control (Dyke et al. 1996, clipped optimal): the command is `high` while the desired force
/// f = −G·z and the damper's force have the same sign and |f| > |F|, else `low`, decided from the state at each
/// step's start and held over the step.
struct OnOffControl {
  std::string variable;  ///< the commanded operating variable (I)
  double low = 0, high = 0;
  Eigen::RowVectorXd gain;  ///< G on z = [u; u̇]
};

struct SeismicRun {
  Building building;
  GroundMotion ground;
  double step_s = 1.0 / 4096.0;        ///< the building's time step (the UTFSM study's control rate by default)
  std::optional<Damper> damper;        ///< none: the bare building
  std::optional<OnOffControl> control; ///< none: passive at the damper's variables
  int output_every = 8;                ///< steps between rows of the time histories
};

struct Energies {
  double input_J = 0, structural_J = 0, damper_J = 0, kinetic_J = 0, strain_J = 0;
  /// |input − (structural + damper + kinetic + strain)| / the largest |input| of the run
  double balance_error = 0;
};

struct SeismicResponse {
  std::vector<double> t_s, ag_m_s2;        ///< at the output rows
  Eigen::MatrixXd u_m, drift_m, abs_acc_m_s2;  ///< rows: output rows, columns: storeys
  std::vector<double> force_N, command;    ///< the damper's force and command at the output rows
  Eigen::VectorXd peak_u_m, peak_drift_m, peak_abs_acc_m_s2;  ///< over every step, per storey
  double peak_force_N = 0;
  double high_share = 0;                   ///< share of steps at the high command (on/off control)
  Energies energy;
  int steps = 0;
  int unconverged_steps = 0;               ///< steps whose force iteration did not converge
};

/// InputError for a step that is not positive, a damper model that cannot be stepped or whose variables miss one
/// its laws need, a control variable outside the damper's laws, low > high.
SeismicResponse simulate_seismic(const SeismicRun& run);

}  // namespace dampbench::structure
