#pragma once
// Every model dampbench knows, by id (the names of docs/models.md are the contract).
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "engine/model/model.hpp"

namespace dampbench {

/// All models, in a stable order (family by family, as in docs/models.md).
std::span<const Model* const> all_models();

/// The model with this id; throws InputError "unknown model 'x' (known: ...)".
const Model& find_model(std::string_view id);

/// Model families (one per source paper); each returns its models.
std::vector<std::unique_ptr<Model>> make_fvd_models();
std::vector<std::unique_ptr<Model>> make_crfd_models();
std::vector<std::unique_ptr<Model>> make_mrd_models();
/// Structures driven by a force (system records t, y, u).
std::vector<std::unique_ptr<Model>> make_system_models();

}  // namespace dampbench
