#pragma once
// The time histories of `dampbench structure` as a self-contained SVG page (structure.svg): the damper storey's
// drift bare and with the damper, its absolute acceleration, and the damper's force with its command.
#include <string>

#include "engine/structure/seismic.hpp"

namespace dampbench::cli {

/// `title` heads the page; `bare` and `damped` are the two runs of one record (the same output rows).
std::string structure_svg(const std::string& title, int storey, const structure::SeismicResponse& bare,
                          const structure::SeismicResponse& damped, const std::string& command_name);

}  // namespace dampbench::cli
