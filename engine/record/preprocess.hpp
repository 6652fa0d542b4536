#pragma once
// The preprocessing a raw rig record needs before a fit (record options --smooth, --remove-mean, --whole-cycles,
// and the keys smooth, remove_mean, whole_cycles of a sweep file's [[datasets]]): applied to the record's columns
// after they are in SI units and before velocity and acceleration are differentiated from x.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace dampbench {

/// Centred moving average over `window` samples: sample k is the mean of samples k − ⌊window/2⌋ … k − ⌊window/2⌋ +
/// window − 1 that exist (the window is cut at the record's ends). The UTFSM thesis smooths with 1/(10·Ts·f) samples
/// (a causal filter there; centred here, so the force does not lag the displacement).
std::vector<double> centred_moving_average(const std::vector<double>& values, int window);

/// values − their mean.
void remove_mean(std::vector<double>& values);

/// The samples [first, last) from the first upward crossing of x through its mean to the last: whole cycles of a
/// periodic test, its ramps in and out left off. Throws InputError(`source`...) when x crosses upward fewer than twice.
std::pair<std::size_t, std::size_t> whole_cycles_span(const std::vector<double>& x, const std::string& source);

}  // namespace dampbench
