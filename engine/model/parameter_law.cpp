#include "engine/model/parameter_law.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"

namespace dampbench {
namespace {

using Family = LawFactor::Family;

const char* const kVariables[] = {"I", "V", "phi", "amp", "freq", "w", "vamp"};

/// mono's knots live on the stack while it is evaluated (no allocation per candidate and record).
constexpr std::size_t kMaxKnots = 16;
/// hill's fixed exponent: any P > 0 keeps the law monotone; the cap keeps (h/x)^P finite over the variables' ranges.
constexpr double kMaxHillExponent = 8;

struct FamilyName {
  const char* name;
  Family family;
};
constexpr FamilyName kFamilies[] = {{"poly", Family::poly}, {"power", Family::power}, {"gauss2", Family::gauss2},
                                    {"sat", Family::sat},   {"hill", Family::hill},   {"tanh", Family::tanh},
                                    {"mono", Family::mono}};

const char* family_name(Family f) {
  for (const auto& known : kFamilies)
    if (known.family == f) return known.name;
  return "";
}

void check_variable(const std::string& v, std::string_view where) {
  for (const char* known : kVariables)
    if (v == known) return;
  throw InputError(fmt::format("{}: unknown operating variable '{}' (known: I, V, phi, amp, freq, w, vamp)", where, v));
}

/// Splits "a,b(c,d),e" at top-level commas.
std::vector<std::string> split_arguments(std::string_view s) {
  std::vector<std::string> out;
  int depth = 0;
  std::string current;
  for (char c : s) {
    if (c == ',' && depth == 0) {
      out.emplace_back(trim(current));
      current.clear();
      continue;
    }
    depth += (c == '(') - (c == ')');
    current += c;
  }
  out.emplace_back(trim(current));
  return out;
}

/// "name(args)" → {name, args}; throws when the text is not a call.
std::pair<std::string, std::string> split_call(std::string_view text, std::string_view where) {
  const auto open = text.find('(');
  if (open == std::string_view::npos || text.back() != ')')
    throw InputError(fmt::format("{}: expected a number, poly(VAR,DEGREE), power(VAR), gauss2(VAR), sat(VAR), "
                                 "hill(VAR) or hill(VAR,P), tanh(VAR), mono(VAR,K1,...,Kn) or prod(LAW,LAW,...), got '{}'",
                                 where, text));
  return {std::string(trim(text.substr(0, open))), std::string(text.substr(open + 1, text.size() - open - 2))};
}

[[noreturn]] void unknown_law(std::string_view name, std::string_view where) {
  throw InputError(fmt::format(
      "{}: unknown law '{}' (known: poly, prod, power, gauss2, sat, hill, tanh, mono, free, or a number)", where, name));
}

int parse_degree(const std::string& text, std::string_view where) {
  const double degree = parse_number(text, fmt::format("{}: polynomial degree", where));
  if (degree != std::floor(degree) || degree < 0 || degree > 6)
    throw InputError(fmt::format("{}: polynomial degree must be a whole number from 0 to 6, got '{}'", where, text));
  return static_cast<int>(degree);
}

double parse_exponent(const std::string& text, std::string_view where) {
  const double p = parse_number(text, fmt::format("{}: hill exponent", where));
  if (!(p > 0 && p <= kMaxHillExponent))
    throw InputError(fmt::format("{}: hill exponent must be above 0 and at most {}, got '{}'", where, kMaxHillExponent, text));
  return p;
}

std::vector<double> parse_knots(const std::vector<std::string>& parts, std::string_view text, std::string_view where) {
  if (parts.size() < 3 || parts.size() > kMaxKnots + 1)
    throw InputError(fmt::format("{}: expected mono(VAR,K1,K2,...,Kn) with 2 to {} knots, got '{}'", where, kMaxKnots, text));
  std::vector<double> knots;
  for (std::size_t i = 1; i < parts.size(); ++i) {
    knots.push_back(parse_number(parts[i], fmt::format("{}: mono knot {}", where, i)));
    if (i > 1 && !(knots[i - 1] > knots[i - 2]))
      throw InputError(fmt::format("{}: mono knots must be strictly increasing (no repeats), got {} after {} in '{}'",
                                   where, parts[i], parts[i - 1], text));
  }
  return knots;
}

/// One single-variable law, e.g. "hill(I,2)" (a lone law has passed split_call already: a text that is not
/// a call here is a factor of a prod).
LawFactor parse_factor(std::string_view text, std::string_view where) {
  if (text.empty() || text.find('(') == std::string_view::npos || text.back() != ')')
    throw InputError(fmt::format("{}: a factor of prod must be a single-variable law such as poly(VAR,DEGREE) or "
                                 "hill(VAR,P), got '{}'",
                                 where, text));
  const auto [name, args] = split_call(text, where);
  if (name == "prod") throw InputError(fmt::format("{}: a prod cannot hold another prod, got '{}'", where, text));
  const std::string& family_name = name;  // clang before 16 cannot capture a structured binding in a lambda
  const auto* known =
      std::find_if(std::begin(kFamilies), std::end(kFamilies), [&](const FamilyName& f) { return family_name == f.name; });
  if (known == std::end(kFamilies)) unknown_law(name, where);
  LawFactor f;
  f.family = known->family;
  const auto parts = split_arguments(args);
  auto expect = [&](bool ok, std::string_view syntax) {
    if (!ok) throw InputError(fmt::format("{}: expected {}, got '{}'", where, syntax, text));
  };
  switch (f.family) {
    case Family::poly: expect(parts.size() == 2, "poly(VAR,DEGREE)"); break;
    case Family::hill: expect(parts.size() == 1 || parts.size() == 2, "hill(VAR) or hill(VAR,P)"); break;
    case Family::mono: break;
    default: expect(parts.size() == 1, fmt::format("{}(VAR)", name)); break;
  }
  f.variable = parts[0];
  check_variable(f.variable, where);
  if (f.family == Family::poly) f.degree = parse_degree(parts[1], where);
  if (f.family == Family::hill && parts.size() == 2) f.exponent = parse_exponent(parts[1], where);
  if (f.family == Family::mono) f.knots = parse_knots(parts, text, where);
  return f;
}

double variable_value(const std::map<std::string, double>& variables, const std::string& name) {
  const auto it = variables.find(name);
  return it == variables.end() ? std::nan("") : it->second;
}

double sign(double v) { return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0); }

/// Shape-preserving end slope of PCHIP (Fritsch–Carlson, as in Moler's pchip): the three-point estimate,
/// zeroed when it points against the first interval and capped at 3δ0 where the data turn.
double end_slope(double h0, double h1, double d0, double d1) {
  const double m = ((2 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
  if (sign(m) != sign(d0)) return 0;
  if (sign(d0) != sign(d1) && std::fabs(m) > std::fabs(3 * d0)) return 3 * d0;
  return m;
}

/// mono: a + d1 + ... at the knots, a monotone cubic Hermite between them (PCHIP slopes: a weighted harmonic
/// mean of the neighbouring secants, zero at a flat or turning secant), straight lines beyond the ends.
double monotone_cubic(const std::vector<double>& K, const double* c, double x) {
  const std::size_t n = K.size();
  std::array<double, kMaxKnots> y{}, h{}, delta{}, m{};
  y[0] = c[0];
  for (std::size_t k = 0; k + 1 < n; ++k) {
    y[k + 1] = y[k] + c[k + 1];
    h[k] = K[k + 1] - K[k];
    delta[k] = c[k + 1] / h[k];
  }
  if (n == 2) {
    m[0] = m[1] = delta[0];
  } else {
    for (std::size_t k = 1; k + 1 < n; ++k) {
      if (!(delta[k - 1] * delta[k] > 0)) continue;  // m[k] stays 0
      const double w1 = 2 * h[k] + h[k - 1], w2 = h[k] + 2 * h[k - 1];
      m[k] = (w1 + w2) / (w1 / delta[k - 1] + w2 / delta[k]);
    }
    m[0] = end_slope(h[0], h[1], delta[0], delta[1]);
    m[n - 1] = end_slope(h[n - 2], h[n - 3], delta[n - 2], delta[n - 3]);
  }
  if (x < K[0]) return y[0] + m[0] * (x - K[0]);
  if (x > K[n - 1]) return y[n - 1] + m[n - 1] * (x - K[n - 1]);
  std::size_t k = 0;
  while (k + 2 < n && x >= K[k + 1]) ++k;
  const double t = (x - K[k]) / h[k], u = 1 - t, d = c[k + 1];
  // The Hermite cubic as y_k plus its rise over the segment: it gives the knot values exactly (y[k + 1] is
  // y[k] + d), stays exactly flat on a flat segment, and the clamp keeps rounding from stepping past the
  // segment's end values, which the cubic never crosses.
  const double rise = t * t * (3 - 2 * t) * d + h[k] * (t * u * u * m[k] - t * t * u * m[k + 1]);
  return y[k] + std::clamp(rise, std::min(0.0, d), std::max(0.0, d));
}

}  // namespace

int LawFactor::size() const {
  switch (family) {
    case Family::poly: return degree + 1;
    case Family::power: return 3;
    case Family::gauss2: return 6;
    case Family::sat: return 3;
    case Family::hill: return exponent > 0 ? 3 : 4;
    case Family::tanh: return 4;
    case Family::mono: return static_cast<int>(knots.size());
  }
  return 0;
}

std::vector<std::string> LawFactor::coefficient_suffixes(bool lone) const {
  std::vector<std::string> s;
  switch (family) {
    case Family::poly:
      for (int k = 0; k <= degree; ++k) s.push_back(std::to_string(k));
      break;
    case Family::power: s = {"k", "p", "c"}; break;
    case Family::gauss2: s = {"a1", "b1", "c1", "a2", "b2", "c2"}; break;
    case Family::sat: s = {"a", "b", "x0"}; break;
    case Family::hill: s = exponent > 0 ? std::vector<std::string>{"a", "b", "h"} : std::vector<std::string>{"a", "b", "h", "p"}; break;
    case Family::tanh: s = {"a", "b", "x1", "w"}; break;
    case Family::mono:
      s.push_back("a");
      for (std::size_t k = 1; k < knots.size(); ++k) s.push_back(fmt::format("d{}", k));
      break;
  }
  // A lone power or gauss2 keeps its published names (fdsp eqs. 13–14: a_c0_k, ...); every other factor,
  // and those two inside a product, name their variable so that the names in a law stay unique.
  const bool bare = lone && (family == Family::power || family == Family::gauss2);
  if (!bare)
    for (auto& suffix : s) suffix = variable + suffix;
  return s;
}

double LawFactor::evaluate(const double* c, double x) const {
  switch (family) {
    case Family::poly: {
      double sum = 0.0;
      for (int k = degree; k >= 0; --k) sum = sum * x + c[k];  // Horner
      return sum;
    }
    case Family::power: return c[0] * std::pow(x, c[1]) + c[2];
    case Family::gauss2: {
      const double g1 = (x - c[1]) / c[2], g2 = (x - c[4]) / c[5];
      return c[0] * std::exp(-g1 * g1) + c[3] * std::exp(-g2 * g2);
    }
    case Family::sat: return c[0] - c[1] * std::expm1(-x / c[2]);
    case Family::hill: {
      // Flat at a for x ≤ 0 (x^p has no real value below 0; currents are ≥ 0): the law stays monotone and
      // 0^p never meets 0/0. (h/x)^p written this way gives b, not inf/inf, when x^p overflows.
      if (x <= 0) return c[0];
      return c[0] + c[1] / (1 + std::pow(c[2] / x, exponent > 0 ? exponent : c[3]));
    }
    case Family::tanh:  // tanh is odd, so the bracket is exactly 0 at x = 0
      return c[0] + c[1] * (std::tanh((x - c[2]) / c[3]) + std::tanh(c[2] / c[3]));
    case Family::mono: return monotone_cubic(knots, c, x);
  }
  return std::nan("");
}

std::string LawFactor::text() const {
  switch (family) {
    case Family::poly: return fmt::format("poly({},{})", variable, degree);
    case Family::hill: return exponent > 0 ? fmt::format("hill({},{})", variable, exponent) : fmt::format("hill({})", variable);
    case Family::mono: return fmt::format("mono({},{})", variable, fmt::join(knots, ","));
    default: return fmt::format("{}({})", family_name(family), variable);
  }
}

bool ParameterLaw::polynomial() const {
  return kind == Kind::product &&
         std::all_of(factors.begin(), factors.end(), [](const LawFactor& f) { return f.family == Family::poly; });
}

bool ParameterLaw::single(Family family) const {
  return kind == Kind::product && factors.size() == 1 && factors[0].family == family;
}

std::vector<std::string> ParameterLaw::variables() const {
  std::vector<std::string> out;
  for (const auto& f : factors) out.push_back(f.variable);
  return out;
}

std::vector<std::string> ParameterLaw::coefficient_names(const std::string& name) const {
  switch (kind) {
    case Kind::free: return {name};
    case Kind::fixed: return {};
    case Kind::product: {
      std::vector<std::string> out;
      for (const auto& f : factors)
        for (const auto& suffix : f.coefficient_suffixes(factors.size() == 1)) out.push_back(fmt::format("{}_{}", name, suffix));
      return out;
    }
  }
  return {};
}

double ParameterLaw::evaluate(const double* c, const std::map<std::string, double>& variables) const {
  switch (kind) {
    case Kind::free: return c[0];
    case Kind::fixed: return fixed_value;
    case Kind::product: {
      double product = 1.0;
      for (const auto& f : factors) {
        product *= f.evaluate(c, variable_value(variables, f.variable));
        c += f.size();
      }
      return product;
    }
  }
  return std::nan("");
}

std::string ParameterLaw::text() const {
  switch (kind) {
    case Kind::free: return "free";
    case Kind::fixed: return fmt::format("{}", fixed_value);
    case Kind::product: {
      std::vector<std::string> parts;
      for (const auto& f : factors) parts.push_back(f.text());
      return parts.size() == 1 ? parts[0] : fmt::format("prod({})", fmt::join(parts, ","));
    }
  }
  return "";
}

ParameterLaw parse_law(std::string_view raw, std::string_view where) {
  const std::string_view text = trim(raw);
  ParameterLaw law;
  if (text == "free") return law;
  if (const ParsedNumber n = try_parse_number(text); n.status == NumberStatus::ok) {
    if (!std::isfinite(n.value)) throw InputError(fmt::format("{}: a fixed value must be finite", where));
    law.kind = ParameterLaw::Kind::fixed;
    law.fixed_value = n.value;
    return law;
  }
  law.kind = ParameterLaw::Kind::product;
  const auto [name, args] = split_call(text, where);
  if (name != "prod") {
    law.factors.push_back(parse_factor(text, where));
    return law;
  }
  std::set<std::string> seen;
  for (const auto& part : split_arguments(args)) {
    law.factors.push_back(parse_factor(part, where));
    if (!seen.insert(law.factors.back().variable).second)
      throw InputError(fmt::format("{}: '{}' has two factors in {} (each factor of a prod takes its own variable)", where,
                                   text, law.factors.back().variable));
  }
  return law;
}

std::map<std::string, ParameterLaw> parse_laws(std::string_view text, std::string_view where) {
  std::map<std::string, ParameterLaw> laws;
  std::size_t start = 0;
  while (start <= text.size()) {
    const auto end = std::min(text.find(';', start), text.size());
    const std::string_view item = trim(text.substr(start, end - start));
    start = end + 1;
    if (item.empty()) continue;
    const auto eq = item.find('=');
    if (eq == std::string_view::npos)
      throw InputError(fmt::format("{}: expected PARAM=LAW, got '{}'", where, item));
    const std::string name(trim(item.substr(0, eq)));
    if (laws.count(name)) throw InputError(fmt::format("{}: law for '{}' given twice", where, name));
    laws[name] = parse_law(item.substr(eq + 1), fmt::format("{} {}", where, name));
  }
  return laws;
}

}  // namespace dampbench
