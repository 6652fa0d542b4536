#include "engine/model/model.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench {

int Model::parameter_index(std::string_view name) const {
  const auto params = parameters();
  std::string known;
  for (std::size_t i = 0; i < params.size(); ++i) {
    if (params[i].name == name) return static_cast<int>(i);
    known += (i ? ", " : "") + params[i].name;
  }
  throw InputError(fmt::format("model {} has no parameter '{}' (parameters: {})", id(), name, known));
}

std::string RecordBoundsRule::describe() const {
  std::string scale;
  auto factor = [&](const char* symbol, double exponent) {
    if (exponent == 0) return;
    const bool denominator = exponent < 0;
    const double e = std::abs(exponent);
    std::string f = e == 1 ? symbol : fmt::format("{}^{}", symbol, e);
    scale += (scale.empty() ? (denominator ? "1/" : "") : (denominator ? "/" : "*")) + f;
  };
  factor("F", force);
  factor("V", velocity);
  factor("X", amplitude);
  return fmt::format("{}..{} x {}{}", lower, upper, scale.empty() ? "1" : scale,
                     stiffening ? " (several records: inside each one's)" : "");
}

void Model::simulate_block(const CandidateBatch& batch, int first, int count, const Signals& data, double* out) const {
  std::vector<double> params(static_cast<std::size_t>(dim()));
  for (int i = 0; i < count; ++i) {
    for (int j = 0; j < dim(); ++j) params[static_cast<std::size_t>(j)] = batch.at(first + i, j);
    const std::vector<double> force = simulate(params, data);
    std::copy(force.begin(), force.end(), out + static_cast<std::size_t>(i) * data.size());
  }
}

}  // namespace dampbench
