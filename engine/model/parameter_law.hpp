#pragma once
// Parameter laws: a base-model parameter written as a function of the dataset's operating variables
// (I [A], V [V], phi [deg], amp [m], freq [Hz]) whose coefficients are the unknowns (step 4 of the procedure
// the five papers share, docs/models.md):
//
//   free                    p                                          1 coefficient, named p
//   a number, e.g. 0.9929   fixed                                      no coefficient
//   poly(I,2)               p_I0 + p_I1·I + p_I2·I²                    crfd eqs. 5.1, 7.2, 7.5; mfm eqs. 5–9
//   prod(poly(I,2),poly(amp,1),poly(freq,1))
//                           (Σ p_Ik I^k)(Σ p_ampk amp^k)(Σ p_freqk freq^k)   mfm eqs. 10–11
//   power(freq)             p_k·freq^p_p + p_c                         fdsp eq. 13
//   gauss2(freq)            p_a1·exp(−((freq − p_b1)/p_c1)²) + p_a2·exp(−((freq − p_b2)/p_c2)²)   fdsp eq. 14
//
// Variables come from the dataset's operating variables; "amp" and "freq" fall back to the record's
// own estimates (half the peak-to-peak displacement; fdsp eq. 15) when the dataset does not state them,
// and "w" is always the record's eq. 15 estimate ω = ΔŻ/(π·ΔZ) (the fdsp model's variable).
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/model/model.hpp"
#include "engine/record/signals.hpp"

namespace dampbench {

struct ParameterLaw {
  enum class Kind { free, fixed, polynomial, power, gaussian2 };
  Kind kind = Kind::free;
  double fixed_value = 0;
  /// polynomial: the factors of the product (one for poly), each (variable, degree)
  std::vector<std::pair<std::string, int>> factors;
  std::string variable;  ///< power, gaussian2

  /// Names of the coefficients for parameter `name`, in order.
  [[nodiscard]] std::vector<std::string> coefficient_names(const std::string& name) const;
  /// Value of the parameter from its coefficients and the operating variables (NaN when a variable is missing).
  [[nodiscard]] double evaluate(const double* coefficients, const std::map<std::string, double>& variables) const;
  /// The law as text (parse_law(text()) gives it back).
  [[nodiscard]] std::string text() const;
};

/// Parses one law; `where` names the source for messages ("--laws c0").
ParameterLaw parse_law(std::string_view text, std::string_view where);

/// Parses "c0=poly(I,1);alpha=poly(I,1);n=0.9929" (laws separated by ';', since laws contain commas).
std::map<std::string, ParameterLaw> parse_laws(std::string_view text, std::string_view where);

}  // namespace dampbench
