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

/// The default bounds for fitting these records: the fixed ones, with the model's record rules
/// (Model::record_bounds_rules) applied with the records' scales. Records without force keep the fixed bounds.
Bounds default_bounds(const Model& model, std::span<const Signals* const> records);

/// Overrides bounds from "name=lo:hi,name=lo:hi" (SI). Throws InputError naming `option` for an unknown
/// parameter, a malformed range, or lower > upper ("--bounds C: lower bound 5 is greater than upper bound 1").
void override_bounds(Bounds& bounds, const Model& model, std::string_view text, std::string_view option = "--bounds");

/// Checks finite values and lower ≤ upper for every parameter (messages name the parameter).
void validate_bounds(const Bounds& bounds, const Model& model, std::string_view option = "--bounds");

}  // namespace dampbench
