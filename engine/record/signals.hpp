#pragma once
// A dataset prepared for the kernels: the signals, trapezoid weights and the force statistics that
// normalize the metrics, computed once per dataset and shared by every candidate.
#include <map>
#include <string>
#include <vector>

#include "engine/record/dataset.hpp"

namespace dampbench {

/// The dataset (its signals and operating variables) plus what every candidate's evaluation shares.
struct Signals : Dataset {
  std::vector<double> w_trapz_s;  ///< trapezoid-rule weights: ∫ g dt ≈ Σ w_k g_k
  /// Per-sample invariants of the power laws, computed once here instead of once per lane block:
  /// sgn(x), sgn(v) and log|x|, log|v| (clamped, engine/common/vector_math.hpp) so that |v|^α = exp(α·log|v|)
  /// costs the lanes one vector exp. A scalar log per sample and block would be 19 % of
  /// fvd.gv_linear_elastic's time.
  std::vector<double> sgn_x, sgn_v, log_abs_x, log_abs_v;
  double duration_s = 0;          ///< t_end − t_start
  // Statistics of the measured output (Dataset::measured(): the force F [N] of a rig record, the displacement
  // y [m] of a system record) that normalise the metrics.
  double measured_std = 0;      ///< population standard deviation, σ(p_m) of fvd eq. 7
  double measured_max_abs = 0;  ///< max |F| (or |y|), normalizes nrmse
  double measured_sum_sq = 0;   ///< Σ F² [N²] (or Σ y² [m²]), normalizes mfm eq. 12
  double velocity_max_abs = 0;    ///< max |v| [m/s] (ΔŻ of fdsp eq. 15)
  double displacement_ptp = 0;    ///< max x − min x [m] (ΔZ of fdsp eq. 15)
  /// fdsp eq. 15: ω = ΔŻ/(π·ΔZ), the excitation frequency [Hz] for a sinusoid, estimated from the record.
  double excitation_freq_hz = 0;
  /// Variables parameter laws may use (engine/model/parameter_law.hpp): `operating`, plus amp (ΔZ/2) and freq
  /// (eq. 15 estimate) from the signals when the dataset does not state them.
  std::map<std::string, double> law_variables;
  /// Where each law variable comes from: `operating_source`, "record estimate (half peak-to-peak)" for amp and
  /// "record estimate (fdsp eq. 15)" for freq and w when they are estimated here, "dataset" when unrecorded.
  std::map<std::string, std::string> law_variable_source;
};

/// Whether two operating values (law_variables) are one value: the same number read from two files, or computed
/// twice, may differ in its last bits (a relative 1e-9). Folds, sweep selections and fitted ranges compare by it.
bool same_operating_value(double a, double b);

/// Builds the kernel view of a dataset (copies its signals; computes weights and force statistics).
Signals prepare_signals(const Dataset& data);

/// A system record's samples may lie this fraction of a step off the uniform grid: times written with 7 significant
/// digits (the benchmark's test file) are off by up to 0.4 % of a step, a missing or doubled sample by a whole one.
inline constexpr double kUniformSamplingTolerance = 0.05;

/// Throws InputError naming the record and the first offending sample unless every sample lies within
/// kUniformSamplingTolerance of a step of the uniform grid from the first to the last time: a system model
/// reconstructs the input between samples assuming a uniform rate.
void check_uniform_sampling(const Dataset& data);

}  // namespace dampbench
