#pragma once
// The law families `fit --laws auto` chooses from, fitted to values of one parameter identified record by record
// (engine/fit/law_selection.hpp). A candidate is a shape in current times an optional factor in one setting
// variable:
//   F(I) · G,  F ∈ {a, a + b·I, a + b·I²/(h² + I²), a + b·(1 − e^(−I/h))},
//              G ∈ {1, q0 + q1·amp, q0 + q1·freq, k·vamp^p + c, k·amp^p + c, k·freq^p + c}
// written in the law grammar (engine/model/parameter_law.hpp) as free, mono(I,0,1), hill(I,2), sat(I),
// poly(amp,1), prod(hill(I,2),poly(freq,1)), prod(sat(I),power(vamp)), ... b ≥ 0 keeps F non-decreasing in I.
// The linear shape is mono(I,0,1) (a + d·I over 0–1 A) rather than poly(I,1): its rise is bounded by twice the
// parameter's range, poly's slope by 2/3 of it, which a viscous coefficient rising fivefold over 1 A exceeds.
// A law in a setting variable has at most three coefficients (six settings would otherwise become a lookup
// table); the power law in the velocity amplitude follows an MR damper's viscous coefficients, which fall
// roughly as 1/vamp across tests whose post-yield force hardly changes (parameter_law.hpp), and the power law in
// the amplitude its hysteresis, whose per-setting yield displacement 1/A grows with the stroke.
#include <map>
#include <string>
#include <vector>

namespace dampbench {

struct ValueLaw {
  enum class Shape { constant, linear, hill2, saturating };
  enum class Factor { none, linear, power };  ///< G = 1, q0 + q1·v, or k·v^p + c
  Shape current = Shape::constant;  ///< F(I)
  Factor factor = Factor::none;     ///< G(v)
  std::string setting;              ///< v: "amp", "freq" or "vamp" ("" without a factor)

  /// The law in the grammar of parse_law ("free" for a constant without a setting factor).
  [[nodiscard]] std::string text() const;
  /// Coefficients of the law in the grammar (its coefficient_names order).
  [[nodiscard]] int coefficients() const;
};

/// Every candidate: 4 shapes × (no factor, linear in amp or freq, power of vamp, amp or freq).
std::vector<ValueLaw> value_law_candidates();

/// A candidate fitted to values: its coefficients in the grammar's order, and the residual sum of squares.
struct ValueFit {
  std::vector<double> coefficients;
  double rss = 0;
  [[nodiscard]] double predict(const ValueLaw& law, const std::map<std::string, double>& variables) const;
};

/// Least squares of `law` to values[r] at variables[r] (each with I and the setting variable): linear in (a, b)
/// for a fixed h and q1/q0, h on a grid over 0.05–2 A, the factor by alternating least squares; b < 0 falls
/// back to b = 0, so the fit is non-decreasing in I like the law's default bounds. A power factor's exponent p is
/// searched on a grid over [−2, 2] refined by golden section, the rest as for a linear factor in v^p; as a later
/// factor it is scaled to 1 at the records' geometric-mean v (its default bounds are ±1, the first factor carries
/// the size), or to max(|k|, |c|) = 1 when that would leave the bounds.
ValueFit fit_value_law(const ValueLaw& law, const std::vector<std::map<std::string, double>>& variables,
                       const std::vector<double>& values);

}  // namespace dampbench
