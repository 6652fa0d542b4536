#pragma once
// Parameter laws: a base-model parameter written as a function of the dataset's operating variables
// (I [A], V [V], phi [deg], amp [m], freq [Hz]) whose coefficients are the unknowns (step 4 of the procedure
// the five papers share, docs/models.md):
//
//   free                    p                                          1 coefficient, named p
//   a number, e.g. 0.9929   fixed                                      no coefficient
//   poly(I,2)               p_I0 + p_I1·I + p_I2·I²                    crfd eqs. 5.1, 7.2, 7.5; mfm eqs. 5–9
//   power(freq)             p_k·freq^p_p + p_c                         fdsp eq. 13
//   gauss2(freq)            p_a1·exp(−((freq − p_b1)/p_c1)²) + p_a2·exp(−((freq − p_b2)/p_c2)²)   fdsp eq. 14
//   sat(I)                  p_Ia + p_Ib·(1 − exp(−I/p_Ix0))            saturating (concave)
//   hill(I), hill(I,P)      p_Ia + p_Ib·I^p/(p_Ih^p + I^p)             sigmoid for p > 1; p = p_Ip or the fixed P
//   tanh(I)                 p_Ia + p_Ib·(tanh((I − p_Ix1)/p_Iw) + tanh(p_Ix1/p_Iw))   equals p_Ia at I = 0
//   mono(I,K1,...,Kn)       monotone piecewise cubic (PCHIP slopes) through the knots with values p_Ia,
//                           p_Ia + p_Id1, p_Ia + p_Id1 + p_Id2, ...; linear beyond the end knots
//   prod(F1,F2,...)         F1·F2·...: any of the single-variable laws above, each in its own variable
//                           (mfm eqs. 10–11: prod(poly(I,2),poly(amp,1),poly(freq,1)))
//
// sat, hill, tanh and mono are non-decreasing in their variable whenever their rises (b, d) are ≥ 0, which
// their default bounds ensure (engine/model/law_model.cpp): MR-damper parameters that grow with the
// current stay monotone and above their level a by construction.
//
// Variables come from the dataset's operating variables; "amp" and "freq" fall back to the record's
// own estimates (half the peak-to-peak displacement; fdsp eq. 15) when the dataset does not state them,
// and "w" is always the record's eq. 15 estimate ω = ΔŻ/(π·ΔZ) (the fdsp model's variable). "vamp" is the sine's
// velocity amplitude 2π·amp·freq [m/s] from those two: an MR damper's post-yield force barely grows with velocity,
// so its apparent viscous coefficient falls roughly as 1/vamp across tests (power(vamp)).
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "engine/model/model.hpp"
#include "engine/record/signals.hpp"

namespace dampbench {

/// One single-variable law: a factor of a product, or the whole law.
struct LawFactor {
  enum class Family { poly, power, gauss2, sat, hill, tanh, mono };
  Family family = Family::poly;
  std::string variable;
  int degree = 0;             ///< poly: the degree
  double exponent = 0;        ///< hill: the user's fixed exponent P; 0 when the exponent is a coefficient
  std::vector<double> knots;  ///< mono: K1 < ... < Kn

  /// Number of coefficients.
  [[nodiscard]] int size() const;
  /// Names of the coefficients after "{param}_": "I0" (poly), "Ia", "Ix0" (sat, hill, tanh, mono), "k" (power).
  [[nodiscard]] std::vector<std::string> coefficient_suffixes(bool with_variable) const;
  /// Value at x from the factor's coefficients c[0 .. size()).
  [[nodiscard]] double evaluate(const double* c, double x) const;
  [[nodiscard]] std::string text() const;
};

struct ParameterLaw {
  enum class Kind { free, fixed, product };
  Kind kind = Kind::free;
  double fixed_value = 0;
  /// product: its factors (one for a law that is not a prod), each in its own variable.
  std::vector<LawFactor> factors;

  /// True for a product whose factors are all polynomials (poly and prod(poly, ...) laws).
  [[nodiscard]] bool polynomial() const;
  /// True for a single factor of this family.
  [[nodiscard]] bool single(LawFactor::Family family) const;
  /// The variables the law reads, in factor order.
  [[nodiscard]] std::vector<std::string> variables() const;
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
