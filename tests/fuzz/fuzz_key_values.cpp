// libFuzzer target: the small command-line languages: key=value lists (`--params`, `--optimizer-settings`),
// comma lists (`--columns`), numbers, unit overrides (`--units`). Bad input must end in an InputError.
#include <cstdint>
#include <string>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"
#include "engine/record/csv_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  auto guarded = [](auto&& fn) {
    try {
      fn();
    } catch (const dampbench::InputError&) {
    }
  };
  guarded([&] { (void)dampbench::parse_key_values(text, "--fuzz"); });
  guarded([&] { (void)dampbench::split_list(text, "--fuzz"); });
  guarded([&] { (void)dampbench::parse_number(text, "--fuzz"); });
  guarded([&] { (void)dampbench::parse_units_option(text); });
  (void)dampbench::try_parse_number(text);
  return 0;
}
