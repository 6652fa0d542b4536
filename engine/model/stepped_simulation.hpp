#pragma once
// A model's force over a record, stepped sample by sample (engine/model/stepper.hpp): `simulate --fixed-step`,
// and the forward check of a command (engine/control).
#include <span>
#include <vector>

#include "engine/model/model.hpp"

namespace dampbench {

/// The force of `model` at `params` over a rig record, stepped sample by sample with `substeps` RK4 sub-steps per
/// interval (`simulate --fixed-step`); NaN from the first sample whose states are not finite. A variable with a
/// column in the record (Dataset::operating_signals) takes its value at sample k over the interval from k to k + 1
/// (zero-order hold) and at sample 0 for the first force; the others keep their constant values. InputError for a
/// model that cannot be stepped (a structure model, a model without a stepper) or substeps < 1.
std::vector<double> simulate_stepped(const Model& model, std::span<const double> params, const Signals& data,
                                     int substeps);

}  // namespace dampbench
