#include "engine/model/bounds.hpp"

#include <cmath>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"

namespace dampbench {

Bounds default_bounds(const Model& model) {
  Bounds b;
  for (const auto& p : model.parameters()) {
    b.lower.push_back(p.lower);
    b.upper.push_back(p.upper);
  }
  return b;
}

void override_bounds(Bounds& bounds, const Model& model, std::string_view text, std::string_view option) {
  for (const auto& [name, range] : parse_key_values(text, option)) {
    const int j = model.parameter_index(name);
    const auto colon = range.find(':');
    if (colon == std::string::npos)
      throw InputError(fmt::format("{} {}: expected lo:hi, got '{}'", option, name, range));
    const std::string what = fmt::format("{} {}", option, name);
    bounds.lower[j] = parse_number(trim(std::string_view(range).substr(0, colon)), what + " lower bound");
    bounds.upper[j] = parse_number(trim(std::string_view(range).substr(colon + 1)), what + " upper bound");
  }
  validate_bounds(bounds, model, option);
}

void validate_bounds(const Bounds& bounds, const Model& model, std::string_view option) {
  const auto params = model.parameters();
  if (bounds.dim() != model.dim() || bounds.upper.size() != bounds.lower.size())
    throw InputError(fmt::format("{}: {} bounds given, model {} has {} parameters", option, bounds.dim(),
                                 model.id(), model.dim()));
  for (int j = 0; j < bounds.dim(); ++j) {
    const double lo = bounds.lower[j], hi = bounds.upper[j];
    if (!std::isfinite(lo) || !std::isfinite(hi))
      throw InputError(fmt::format("{} {}: bounds must be finite numbers", option, params[j].name));
    if (lo > hi)
      throw InputError(fmt::format("{} {}: lower bound {:g} is greater than upper bound {:g}", option,
                                   params[j].name, lo, hi));
  }
}

}  // namespace dampbench
