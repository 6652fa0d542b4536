#pragma once
// A law model stepped sample by sample (engine/model/stepper.hpp): its laws evaluated at the variables each
// set_parameters gives, with each driver lag's u integrated between, and its base model stepped.
#include <memory>

#include "engine/model/law_model.hpp"
#include "engine/model/stepper.hpp"

namespace dampbench {

/// The stepper of `model` over its base's stepper `base`.
std::unique_ptr<ModelStepper> make_law_stepper(const LawModel& model, std::unique_ptr<ModelStepper> base);

}  // namespace dampbench
