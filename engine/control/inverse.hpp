#pragma once
// The inverse of an identified damper model (lssvm names "inverse model control" as its next
// step): the command (I, V or phi) that makes the model give a desired force, sample by sample. The model's states
// are carried forward with the command found for each interval; the command holds over the interval that starts at
// its sample (a controller's zero-order hold), chosen so that the force at the interval's end is the desired one.
// Laws monotone in the command make that a bracketed one-dimensional solve; a desired force outside the forces at
// the range's two ends is out of reach, and the nearer end is taken. The on/off rule instead takes the high
// command while the desired force exceeds the model's last force in magnitude with the same sign, else the low one.
#include <string>
#include <vector>

#include "engine/model/model.hpp"

namespace dampbench::control {

enum class InverseLaw { inverse, on_off };

struct InverseSettings {
  std::string variable;  ///< the commanded operating variable (I, V, phi)
  double low = 0, high = 0;
  InverseLaw law = InverseLaw::inverse;
  int substeps = 4;  ///< RK4 sub-steps per sample interval (engine/model/stepper.hpp)
};

struct InverseResult {
  std::vector<double> command;    ///< at each sample, held until the next one (the first also at rest: u(0) = c(0))
  std::vector<double> force_N;    ///< the model's force with that command (the forward simulation)
  std::vector<bool> reachable;    ///< whether the desired force lay between the forces at the range's ends
  double tracking_error = 0;      ///< sqrt(Σ(F − F_d)² / Σ F_d²) over the reachable samples after the first
  double share_at_low = 0, share_at_high = 0;  ///< of the samples whose command is at that end of the range
  double share_reachable = 0;     ///< of the samples after the first
};

/// InputError unless `model` has a law in `variable`, so that a command in it changes the force; `command` names the
/// command in the message.
void check_commanded_variable(const Model& model, const std::string& variable, const std::string& command);

/// The command for the desired force data.F_N over the motion data.x, v, a. InputError for a record without a
/// force column or with a non-finite desired force (naming the sample), a range without low < high, a model that
/// cannot be stepped or has no law in the variable.
InverseResult inverse_command(const Model& model, std::span<const double> params, const Signals& data,
                              const InverseSettings& settings);

}  // namespace dampbench::control
