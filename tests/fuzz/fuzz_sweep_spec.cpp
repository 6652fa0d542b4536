// libFuzzer target: a sweep file (engine/sweep/spec.hpp) parsed and checked, files not opened. Bad input must end
// in an InputError naming file, line and key; anything else is a bug.
#include <cstdint>
#include <string>

#include "engine/common/error.hpp"
#include "engine/sweep/spec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  dampbench::sweep::SpecOptions options;
  options.check_files = false;
  try {
    (void)dampbench::sweep::parse_sweep(text, "/nonexistent/fuzz/sweep.toml", options);
  } catch (const dampbench::InputError&) {
  }
  return 0;
}
