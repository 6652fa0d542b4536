#include "engine/model/model.hpp"

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

}  // namespace dampbench
