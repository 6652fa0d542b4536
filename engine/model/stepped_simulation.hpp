#pragma once
// A model's force over a record, stepped sample by sample (engine/model/stepper.hpp): `simulate --fixed-step`,
// the forward check of a command (engine/control), and the evaluation of a law model on a record whose commanded
// variable varies over the test (engine/model/law_model.hpp).
#include <span>
#include <vector>

#include "engine/model/model.hpp"

namespace dampbench {

/// `substeps` of simulate_stepped: the batch kernels' rules instead of a fixed count (kernel_substeps below).
inline constexpr int kKernelSubsteps = -1;

/// The force of `model` at `params` over a rig record, stepped sample by sample with `substeps` RK4 sub-steps per
/// interval (`simulate --fixed-step`), or with kKernelSubsteps the counts kernel_substeps gives; NaN from the first
/// sample whose states are not finite (everywhere for a candidate the kernels mask as too stiff). A variable with
/// a column in the record (Dataset::operating_signals) takes its value at sample k over the interval from k to
/// k + 1 (zero-order hold) and at sample 0 for the first force; the others keep their constant values. InputError
/// for a model that cannot be stepped (a structure model, a model without a stepper) or substeps < 1 other than
/// kKernelSubsteps.
std::vector<double> simulate_stepped(const Model& model, std::span<const double> params, const Signals& data,
                                     int substeps);

/// The sub-steps of each interval of `data` (element k − 1 for the interval from sample k − 1 to k) under the
/// batch kernels' rules (ModelStepper::kernel_substeps) for the stiffest parameters the candidate takes over the
/// record: its stiffness estimate at the variables' values of 64 samples evenly spread over the record and of
/// each column's smallest and largest value, the largest of them for every interval, so the count follows the
/// candidate and the record, never the command interval by interval (a count that jumped where the command
/// changes would make the objective jump with it). Empty when the kernels would mask the candidate as too stiff.
std::vector<int> kernel_substeps(const Model& model, std::span<const double> params, const Signals& data);

}  // namespace dampbench
