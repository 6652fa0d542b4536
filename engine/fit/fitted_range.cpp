#include "engine/fit/fitted_range.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "engine/model/law_model.hpp"
#include "engine/record/signals.hpp"

namespace dampbench {

FittedRange::FittedRange(const Model& model, const std::vector<std::map<std::string, double>>& fitted) {
  const auto* law = dynamic_cast<const LawModel*>(&model);
  if (!law) return;
  for (const std::string& v : law->law_variables())
    for (const auto& record : fitted) {
      const auto it = record.find(v);
      if (it == record.end()) continue;
      const auto range = range_.try_emplace(v, it->second, it->second).first;
      range->second.first = std::min(range->second.first, it->second);
      range->second.second = std::max(range->second.second, it->second);
    }
}

std::string FittedRange::outside(const std::map<std::string, double>& record) const {
  std::string out;
  for (const auto& [name, range] : range_) {
    const auto it = record.find(name);
    if (it == record.end()) continue;
    const double v = it->second;
    if ((v >= range.first && v <= range.second) || same_operating_value(v, range.first) ||
        same_operating_value(v, range.second))
      continue;
    out += fmt::format("{}{} = {:g} (fitted on {:g} to {:g})", out.empty() ? "" : ", ", name, v, range.first,
                       range.second);
  }
  return out;
}

}  // namespace dampbench
