// libFuzzer target: a record file (engine/record/csv_loader.hpp) read and prepared as the sweeps and `fit` read
// it. Bad input must end in an InputError with a message; anything else (a crash, a sanitizer finding, another
// exception) is a bug. The first byte picks the loader options (force required, a units override, columns).
#include <cstdint>
#include <sstream>
#include <string>

#include "engine/common/error.hpp"
#include "engine/record/csv_loader.hpp"
#include "engine/record/signals.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  dampbench::CsvOptions options;
  options.require_force = (data[0] & 1) != 0;
  if (data[0] & 2) options.units = {{"x", "mm"}, {"F", "kN"}};
  if (data[0] & 4) options.columns = {"t", "x", "F"};
  std::istringstream in(std::string(reinterpret_cast<const char*>(data + 1), size - 1));
  try {
    const dampbench::Dataset d = dampbench::parse_csv(in, "fuzz.csv", options);
    (void)dampbench::prepare_signals(d);
  } catch (const dampbench::InputError&) {
  }
  return 0;
}
