#pragma once
// Differential sensitivity analysis (crfd §4.1, eqs. 4.1–4.3). Each parameter z is swept over
// [z·(1 − range), z·(1 + range)] on N equally spaced points with the others held; the point sensitivity
// is the one-sided difference at the two ends and the central difference inside (eq. 4.1),
// S_z = sqrt(mean S_zi²) (eq. 4.2) and SP_z = S_z / Σ S × 100 % (eq. 4.3).
//
// The paper does not define f(z); by default f is the RMS of the model force (torque) over the record
// (docs/models.md (crfd)), or any metric against the record's measured force. As printed, S_z has the units of
// f per unit of z, so parameters with small values (J) look insensitive and large ones sensitive only
// through their units; `normalized` multiplies S_z by |z| (an elasticity, f per relative change),
// which compares parameters on one scale.
#include <optional>
#include <span>
#include <vector>

#include "engine/model/metrics.hpp"
#include "engine/model/model.hpp"
#include "engine/record/signals.hpp"

namespace dampbench {

struct SensitivitySettings {
  int points = 21;                 ///< N grid points per parameter (≥ 3)
  double range = 0.5;              ///< ±50 % (crfd Table 4)
  std::optional<Metric> metric;    ///< f = this metric against the record's force; default: RMS of the model force
  bool normalized = false;         ///< S_z·|z| instead of S_z as printed
};

struct Sensitivity {
  std::vector<double> S;   ///< eq. 4.2, per parameter
  std::vector<double> SP;  ///< eq. 4.3, percent
};

/// Throws InputError for points < 3, range outside (0, 1), or a metric objective on a record without force.
Sensitivity differential_sensitivity(const Model& model, std::span<const double> params, const Signals& data,
                                     const SensitivitySettings& settings = {});

}  // namespace dampbench
