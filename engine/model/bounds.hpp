#pragma once
// Search bounds of a model's parameters: defaults from the model, overridden by name (--bounds, sweep files).
#include <span>
#include <string_view>
#include <vector>

#include "engine/model/model.hpp"

namespace dampbench {

struct Bounds {
  std::vector<double> lower, upper;
  /// A known good point, or empty: population optimizers make it the first member of their initial population
  /// (optimizers/population.hpp), so a search refines what an earlier stage found (`fit --laws auto`,
  /// `fit --start per-file`). Defaulted, so that brace-initialized boxes may leave it out.
  std::vector<double> start = {};
  [[nodiscard]] int dim() const { return static_cast<int>(lower.size()); }
};

/// The model's fixed default bounds.
Bounds default_bounds(const Model& model);

/// Which box over several records: that of their joint fit (each rule's hull of the records' own ranges, a
/// stiffening rule's intersection), or the hull of the boxes of a fit of each record alone.
enum class RecordBox { joint, hull };

/// The default bounds for fitting these records: the fixed ones, with the model's record rules
/// (Model::record_bounds_rules) applied with the records' scales. Records without force keep the fixed bounds.
Bounds default_bounds(const Model& model, std::span<const Signals* const> records, RecordBox box = RecordBox::joint);

/// `point` (a start) moved into `box`: coordinate by coordinate, except the free parameters a law model's state
/// gauge sums (β and γ of Bouc–Wen, A = β + γ), which are first scaled together by the largest factor in (0, 1]
/// that brings each inside its bounds: clamped one by one, β = −1.2e5 and γ = 1.2e5 into ±8e4 would give A = 0 and
/// a state that never moves, where scaled they keep the loop's shape with a longer yield displacement.
void clamp_into_box(const Model& model, const Bounds& box, std::span<double> point);

/// Overrides bounds from "name=lo:hi,name=lo:hi" (SI). Throws InputError naming `option` for an unknown
/// parameter, a malformed range, or lower > upper ("--bounds C: lower bound 5 is greater than upper bound 1").
void override_bounds(Bounds& bounds, const Model& model, std::string_view text, std::string_view option = "--bounds");

/// Checks finite values and lower ≤ upper for every parameter (messages name the parameter).
void validate_bounds(const Bounds& bounds, const Model& model, std::string_view option = "--bounds");

}  // namespace dampbench
