#pragma once
// Where a law model extrapolates: the range of each operating variable its laws read over the records it was
// fitted on, and the variables of another record that lie outside it. A law fitted on 0–1 A or on 5–25 mm strokes
// says nothing reliable at 3 A or 2 mm (a power law in the stroke fitted on 5–25 mm can give n = 7.5 at 2 mm), so
// a prediction there is flagged, not refused: held-out records, `evaluate --model-file` and `simulate --model-file`
// name the variable and the range.
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "engine/model/model.hpp"

namespace dampbench {

class FittedRange {
 public:
  /// The ranges of the variables `model`'s laws read (none for a model without laws) over `fitted`, the fitted
  /// records' operating variables; a variable a record lacks does not widen its range.
  FittedRange(const Model& model, const std::vector<std::map<std::string, double>>& fitted);

  /// Each variable of `record` outside its fitted range, e.g. "amp = 0.002 (fitted on 0.005 to 0.025)", joined by
  /// ", "; "" when every one lies inside (a value same_operating_value as an end is inside, as folds compare).
  [[nodiscard]] std::string outside(const std::map<std::string, double>& record) const;
  /// Each variable's smallest and largest fitted value (a variable no record gives has none).
  [[nodiscard]] const std::map<std::string, std::pair<double, double>>& ranges() const { return range_; }

 private:
  std::map<std::string, std::pair<double, double>> range_;
};

}  // namespace dampbench
