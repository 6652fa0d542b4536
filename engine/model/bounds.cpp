#include "engine/model/bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"
#include "engine/model/law_model.hpp"

namespace dampbench {

Bounds default_bounds(const Model& model) {
  Bounds b;
  for (const auto& p : model.parameters()) {
    b.lower.push_back(p.lower);
    b.upper.push_back(p.upper);
  }
  return b;
}

Bounds default_bounds(const Model& model, std::span<const Signals* const> records, RecordBox box) {
  Bounds b = default_bounds(model);
  const auto params = model.parameters();
  for (const RecordBoundsRule& rule : model.record_bounds_rules()) {
    const auto it = std::find_if(params.begin(), params.end(), [&](const ParameterInfo& p) { return p.name == rule.name; });
    if (it == params.end()) continue;  // a law model replaced the parameter by its law's coefficients
    // The smallest box that holds each record's own: parameters shared by records of different strokes and forces
    // must reach what a fit of any one of them reaches (a start built from the records' own fits lies inside it,
    // after clamp_into_box). A stiffening rule takes the largest box inside each record's own instead: its hull
    // would try the short stroke's fastest states on the long stroke's many samples.
    const bool intersect = rule.stiffening && box == RecordBox::joint;
    double lower = std::numeric_limits<double>::infinity(), upper = -lower;
    bool any = false;
    for (const Signals* r : records) {
      const double F = r->measured_max_abs, V = r->velocity_max_abs, X = 0.5 * r->displacement_ptp;
      if (!(F > 0 && V > 0 && X > 0)) continue;  // a constant record scales nothing
      const double scale = std::pow(F, rule.force) * std::pow(V, rule.velocity) * std::pow(X, rule.amplitude);
      const double lo = rule.lower * scale, hi = rule.upper * scale;
      lower = !any ? lo : intersect ? std::max(lower, lo) : std::min(lower, lo);
      upper = !any ? hi : intersect ? std::min(upper, hi) : std::max(upper, hi);
      any = true;
    }
    if (!(lower <= upper)) continue;
    const auto j = it - params.begin();
    b.lower[j] = lower;
    b.upper[j] = upper;
  }
  return b;
}

void clamp_into_box(const Model& model, const Bounds& box, std::span<double> point) {
  const auto* law = dynamic_cast<const LawModel*>(&model);
  if (law && law->applied_gauge()) {
    std::vector<int> summed;  // the gauge's free terms (a term with a law of its own has other coefficients)
    const auto params = model.parameters();
    for (const auto& name : law->applied_gauge()->sum_of)
      for (int j = 0; j < model.dim(); ++j)
        if (params[j].name == name) summed.push_back(j);
    double scale = 1.0;
    for (int j : summed) {
      const double v = point[j];
      if (v > box.upper[j] && box.upper[j] > 0) scale = std::min(scale, box.upper[j] / v);
      if (v < box.lower[j] && box.lower[j] < 0) scale = std::min(scale, box.lower[j] / v);
    }
    for (int j : summed) point[j] *= scale;
  }
  for (int j = 0; j < box.dim(); ++j) point[j] = std::clamp(point[j], box.lower[j], box.upper[j]);
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
