#pragma once
// What a structure model (sys.*, models/structure.cpp) gives beyond its displacement: the velocity, acceleration and
// hysteretic force of the same simulation, for `simulate` on a system record.
#include <optional>
#include <span>
#include <vector>

#include "engine/model/model.hpp"

namespace dampbench {

struct StructureResponse {
  std::vector<double> y_m, v_m_s, a_m_s2, z_N;  ///< at the record's samples
};

/// The response of a structure model at the record's samples, from the lanes simulate() runs (y has its bits); NaN
/// throughout for a candidate that blew up; nullopt when `model` is not a structure model.
std::optional<StructureResponse> structure_response(const Model& model, std::span<const double> params,
                                                    const Signals& data);

}  // namespace dampbench
