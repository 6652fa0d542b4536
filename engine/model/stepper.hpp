#pragma once
// A model stepped one sample at a time, for what runs a model without knowing the whole record in advance: a
// structure whose motion depends on the damper's force (engine/structure), an inverse model (engine/control),
// `simulate --fixed-step`. The scheme is the batch kernels' with no adaptivity: classical
// Runge–Kutta (RK4) in a fixed number of sub-steps per sample interval, the inputs (x, v) linear between the
// samples, states at zero at rest. The batch kernels choose their sub-steps from the whole record (its stroke,
// peak velocity and each candidate's stiffness), which a step-by-step caller cannot know.
#include <cstddef>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>


namespace dampbench {

struct Signals;

class ModelStepper {
 public:
  virtual ~ModelStepper() = default;

  /// The model's parameters (its own, in its order) and the operating variables by name, from now on; the
  /// internal states stay. InputError when a variable the model needs is missing.
  virtual void set_parameters(std::span<const double> params, const std::map<std::string, double>& variables) = 0;
  /// New parameters with the variables of the last set_parameters (a lagged law model's laws move its base's
  /// parameters at every sub-step).
  virtual void set_parameter_values(std::span<const double> params) = 0;
  /// Whether the model reads the variables of set_parameters itself (beyond its parameters): a lagged law model
  /// then gives it the lagged values at every sub-step.
  [[nodiscard]] virtual bool reads_variables() const { return true; }
  /// Internal states at rest (zero).
  virtual void reset() = 0;
  /// The force [N] at the current states and the inputs x [m], v [m/s], a [m/s²].
  [[nodiscard]] virtual double force(double x, double v, double a) const = 0;
  /// Advances the states by dt [s] with the inputs linear from (x0, v0) to (x1, v1), in `substeps` RK4 sub-steps
  /// (nothing for an algebraic model).
  virtual void advance(double x0, double v0, double x1, double v1, double dt, int substeps) = 0;
  /// The batch kernels' stiffness estimate λ [1/s] at the current parameters on a record of this peak |v| and
  /// stroke (engine/kernels/substep_rule.hpp); 0 for a model without one (+inf where it is not finite).
  [[nodiscard]] virtual double stiffness(double /*velocity_max_abs_m_s*/, double /*displacement_ptp_m*/) const { return 0; }
  /// The sub-steps the batch kernels take on interval k of `data` for a lane of stiffness `lambda` [1/s]: the
  /// record's count, or more for a stiff lane; 0 where they mask the lane as too stiff. 1 for an algebraic model.
  [[nodiscard]] virtual int kernel_substeps(const Signals& /*data*/, std::size_t /*k*/, double /*lambda*/) const { return 1; }
  /// The internal states (empty for an algebraic model), to save a step and try it again (a structure's
  /// iteration on the damper force).
  [[nodiscard]] virtual std::vector<double> states() const = 0;
  virtual void set_states(std::span<const double> states) = 0;
};

}  // namespace dampbench
