#pragma once
// A model stepped one sample at a time, for what runs a model without knowing the whole record in advance: a
// structure whose motion depends on the damper's force (engine/structure), an inverse model (engine/control),
// `simulate --fixed-step`. The scheme is the batch kernels' with no adaptivity: classical
// Runge–Kutta (RK4) in a fixed number of sub-steps per sample interval, the inputs (x, v) linear between the
// samples, states at zero at rest. The batch kernels choose their sub-steps from the whole record (its stroke,
// peak velocity and each candidate's stiffness), which a step-by-step caller cannot know.
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>


namespace dampbench {

class ModelStepper {
 public:
  virtual ~ModelStepper() = default;

  /// The model's parameters (its own, in its order) and the operating variables by name, from now on; the
  /// internal states stay. InputError when a variable the model needs is missing.
  virtual void set_parameters(std::span<const double> params, const std::map<std::string, double>& variables) = 0;
  /// Internal states at rest (zero).
  virtual void reset() = 0;
  /// The force [N] at the current states and the inputs x [m], v [m/s], a [m/s²].
  [[nodiscard]] virtual double force(double x, double v, double a) const = 0;
  /// Advances the states by dt [s] with the inputs linear from (x0, v0) to (x1, v1), in `substeps` RK4 sub-steps
  /// (nothing for an algebraic model).
  virtual void advance(double x0, double v0, double x1, double v1, double dt, int substeps) = 0;
  /// The internal states (empty for an algebraic model), to save a step and try it again (a structure's
  /// iteration on the damper force).
  [[nodiscard]] virtual std::vector<double> states() const = 0;
  virtual void set_states(std::span<const double> states) = 0;
};

}  // namespace dampbench
