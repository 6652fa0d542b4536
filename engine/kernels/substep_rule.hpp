#pragma once
// How many RK4 sub-steps an ODE law takes on a sample interval: the record's rule (the stroke a sub-step may
// move) and a stiff lane's count (its stiffness estimate times the interval). The batch kernel
// (engine/kernels/ode_kernel.hpp) and a law stepped sample by sample (engine/kernels/law_stepper.hpp) share them.
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "engine/record/signals.hpp"

namespace dampbench {

/// What a law's stiffness estimate may use of the record.
struct RecordScales {
  double velocity_max_abs = 0;  ///< max |v| [m/s]
  double displacement_ptp = 0;  ///< max x − min x [m]
};

/// h·λ a stiff lane's sub-step may reach, unless the law sets its own `kStiffStep`: lane l takes
/// max(n, ceil(dt·λ_l / kStiffStep)) sub-steps on an interval, inside RK4's stability interval (|h·λ| < 2.78 on
/// the negative real axis) with room for accuracy. λ_l comes from the record's peak |v| (RecordScales) for every
/// interval, also for stroke-driven laws: a count that followed the parameters interval by interval would make
/// the objective jump by the discretization error wherever it changed, and local optimizers stall on such
/// steps. 1.0 keeps Bouc–Wen's worst relative L2 to CVODE over random candidates of its default box under the
/// 1e-4 bound of tests/unit/kernels/test_ode_stiff_lanes.cpp with margin. Spencer and the fdsp laws set larger ones that
/// stay within Bouc–Wen's worst error, because stiff lanes are most of a real-data fit's time
/// (docs/performance.md, "The ODE kernel's rules", has the errors of each choice).
inline constexpr double kStiffStep = 1.0;
/// Sub-steps per sample interval beyond which a lane is masked as too stiff.
inline constexpr int kMaxSubsteps = 512;

/// A law's `kStrokeDriven` (default false; see ode_substeps).
template <class Law>
constexpr bool law_stroke_driven() {
  if constexpr (requires { Law::kStrokeDriven; }) return Law::kStrokeDriven;
  else return false;
}

/// A law's `kStiffStep` (default ::kStiffStep).
template <class Law>
constexpr double law_stiff_step() {
  if constexpr (requires { Law::kStiffStep; }) return Law::kStiffStep;
  else return kStiffStep;
}

/// RK4 sub-steps on the sample interval [k−1, k], the same for every lane: ceil(dt·V / (ΔZ / kSubstepsPerStroke)),
/// at least 1, so a sub-step never moves the piston more than 1/kSubstepsPerStroke of the peak-to-peak stroke ΔZ.
/// V is the record's peak |v|, or with `local` (a stroke-driven law, whose states move with the relative
/// velocity) the larger |v| at the interval's two ends: the same bound on the stroke with fewer sub-steps where
/// the piston moves slowly. A law that relaxes on the clock (generalized Maxwell) keeps the peak.
inline int ode_substeps(const Signals& data, std::size_t k, double substeps_per_stroke, bool local) {
  const double dt = data.t_s[k] - data.t_s[k - 1];
  if (data.displacement_ptp <= 0) return 1;
  const double v_max = local ? std::max(std::fabs(data.v_m_s[k - 1]), std::fabs(data.v_m_s[k])) : data.velocity_max_abs;
  const double n = std::ceil(dt * v_max * substeps_per_stroke / data.displacement_ptp);
  return std::max(1, static_cast<int>(std::min(n, 1e6)));
}

}  // namespace dampbench
