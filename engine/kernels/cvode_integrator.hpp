#pragma once
// SUNDIALS CVODE (BDF, Newton iteration, dense direct solver) behind a small interface: the reference
// integrator that fixed-step ODE kernels are checked against, and the integrator of synthetic "truth"
// data with a hysteretic state (datasets/).
#include <functional>
#include <span>
#include <vector>

namespace dampbench {

struct CvodeSettings {
  double relative_tolerance = 1e-10;
  double absolute_tolerance = 1e-12;
  long max_steps_per_output = 100000;
  /// Never step past an output time (CVodeSetStopTime): needed for inputs with kinks at the output times
  /// (records, piecewise linear). The fvd generator's input is a smooth cosine and keeps its committed
  /// records by stepping freely.
  bool stop_at_each_time = true;
};

/// dy/dt = rhs(t, y); `dydt` has y's size. Must not throw.
using OdeRhs = std::function<void(double t, std::span<const double> y, std::span<double> dydt)>;

/// Integrates from (times[0], y0) and returns the state at every time in `times` (increasing);
/// element k is y(times[k]). Throws std::runtime_error with CVODE's flag if the integration fails.
std::vector<std::vector<double>> integrate_cvode(const OdeRhs& rhs, std::vector<double> y0,
                                                 std::span<const double> times, const CvodeSettings& settings = {});

}  // namespace dampbench
