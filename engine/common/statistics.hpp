#pragma once
// Summary statistics of repeated runs (fvd Tables 3–10: Mean, Max, Min, Std).
#include <span>
#include <vector>

namespace dampbench {

struct Summary {
  double mean = 0, max = 0, min = 0;
  double std = 0;  ///< sample standard deviation (n − 1); 0 for a single value
  int count = 0;
};

/// Summary of the values, summed in index order (same input ⇒ same bits). Non-finite values (+inf
/// metrics of failed runs) make every field +inf except count, so a failure is never averaged away.
Summary summarize(std::span<const double> values);

/// Quantile q ∈ [0, 1] of sorted values (R type 7: linear between order statistics, numpy's default);
/// +inf entries allowed (never NaN); NaN for no values.
double sorted_quantile(const std::vector<double>& sorted, double q);

}  // namespace dampbench
