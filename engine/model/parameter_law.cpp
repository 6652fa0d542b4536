#include "engine/model/parameter_law.hpp"

#include <cmath>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"

namespace dampbench {
namespace {

const char* const kVariables[] = {"I", "V", "phi", "amp", "freq", "w"};

void check_variable(const std::string& v, std::string_view where) {
  for (const char* known : kVariables)
    if (v == known) return;
  throw InputError(fmt::format("{}: unknown operating variable '{}' (known: I, V, phi, amp, freq, w)", where, v));
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
    throw InputError(fmt::format("{}: expected a number, poly(VAR,DEGREE), prod(poly(...),...), power(VAR) or "
                                 "gauss2(VAR), got '{}'",
                                 where, text));
  return {std::string(trim(text.substr(0, open))), std::string(text.substr(open + 1, text.size() - open - 2))};
}

std::pair<std::string, int> parse_poly(std::string_view text, std::string_view where) {
  const auto [name, args] = split_call(text, where);
  const auto parts = split_arguments(args);
  if (name != "poly" || parts.size() != 2)
    throw InputError(fmt::format("{}: expected poly(VAR,DEGREE), got '{}'", where, text));
  check_variable(parts[0], where);
  const double degree = parse_number(parts[1], fmt::format("{}: polynomial degree", where));
  if (degree != std::floor(degree) || degree < 0 || degree > 6)
    throw InputError(fmt::format("{}: polynomial degree must be a whole number from 0 to 6, got '{}'", where, parts[1]));
  return {parts[0], static_cast<int>(degree)};
}

double variable_value(const std::map<std::string, double>& variables, const std::string& name) {
  const auto it = variables.find(name);
  return it == variables.end() ? std::nan("") : it->second;
}

}  // namespace

std::vector<std::string> ParameterLaw::coefficient_names(const std::string& name) const {
  switch (kind) {
    case Kind::free: return {name};
    case Kind::fixed: return {};
    case Kind::polynomial: {
      std::vector<std::string> out;
      for (const auto& [var, degree] : factors)
        for (int k = 0; k <= degree; ++k) out.push_back(fmt::format("{}_{}{}", name, var, k));
      return out;
    }
    case Kind::power: return {name + "_k", name + "_p", name + "_c"};
    case Kind::gaussian2:
      return {name + "_a1", name + "_b1", name + "_c1", name + "_a2", name + "_b2", name + "_c2"};
  }
  return {};
}

double ParameterLaw::evaluate(const double* c, const std::map<std::string, double>& variables) const {
  switch (kind) {
    case Kind::free: return c[0];
    case Kind::fixed: return fixed_value;
    case Kind::polynomial: {
      double product = 1.0;
      int offset = 0;
      for (const auto& [var, degree] : factors) {
        const double x = variable_value(variables, var);
        double sum = 0.0;
        for (int k = degree; k >= 0; --k) sum = sum * x + c[offset + k];  // Horner
        product *= sum;
        offset += degree + 1;
      }
      return product;
    }
    case Kind::power: return c[0] * std::pow(variable_value(variables, variable), c[1]) + c[2];
    case Kind::gaussian2: {
      const double x = variable_value(variables, variable);
      const double g1 = (x - c[1]) / c[2], g2 = (x - c[4]) / c[5];
      return c[0] * std::exp(-g1 * g1) + c[3] * std::exp(-g2 * g2);
    }
  }
  return std::nan("");
}

std::string ParameterLaw::text() const {
  switch (kind) {
    case Kind::free: return "free";
    case Kind::fixed: return fmt::format("{}", fixed_value);
    case Kind::polynomial: {
      std::vector<std::string> polys;
      for (const auto& [var, degree] : factors) polys.push_back(fmt::format("poly({},{})", var, degree));
      return polys.size() == 1 ? polys[0] : fmt::format("prod({})", fmt::join(polys, ","));
    }
    case Kind::power: return fmt::format("power({})", variable);
    case Kind::gaussian2: return fmt::format("gauss2({})", variable);
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
  const auto [name, args] = split_call(text, where);
  if (name == "poly") {
    law.kind = ParameterLaw::Kind::polynomial;
    law.factors.push_back(parse_poly(text, where));
  } else if (name == "prod") {
    law.kind = ParameterLaw::Kind::polynomial;
    for (const auto& part : split_arguments(args)) law.factors.push_back(parse_poly(part, where));
  } else if (name == "power" || name == "gauss2") {
    law.kind = name == "power" ? ParameterLaw::Kind::power : ParameterLaw::Kind::gaussian2;
    law.variable = std::string(trim(args));
    check_variable(law.variable, where);
  } else {
    throw InputError(fmt::format("{}: unknown law '{}' (known: poly, prod, power, gauss2, free, or a number)", where, name));
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
