#pragma once
// Errors raised at the boundary (files, sweep specs, command-line values). Hot loops never throw:
// a failed candidate is a +inf metric, not an exception (DESIGN.md, "Performance principles").
#include <stdexcept>
#include <string>

namespace dampbench {

/// Bad user input. The message names where (file, line, option) and what was expected.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace dampbench
