#include "models/registry.hpp"

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench {
namespace {

struct Registry {
  std::vector<std::unique_ptr<Model>> owned;
  std::vector<const Model*> views;

  Registry() {
    for (auto make : {make_fvd_models, make_crfd_models, make_mrd_models, make_system_models})
      for (auto& m : make()) owned.push_back(std::move(m));
    for (const auto& m : owned) views.push_back(m.get());
  }
};

const Registry& registry() {
  static const Registry r;
  return r;
}

}  // namespace

std::span<const Model* const> all_models() { return registry().views; }

const Model& find_model(std::string_view id) {
  std::string known;
  for (const Model* m : all_models()) {
    if (m->id() == id) return *m;
    known += (known.empty() ? "" : ", ") + std::string(m->id());
  }
  throw InputError(fmt::format("unknown model '{}' (known: {})", id, known));
}

}  // namespace dampbench
