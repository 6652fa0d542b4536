// libFuzzer target: a record file read and prepared as the sweeps and `fit` read it: a plain record file
// (engine/record/csv_loader.hpp), or a rig's text export turned into records by the --columns mapping, gains,
// the split into tests and the preprocessing (engine/record/text_channels.hpp, record_files.hpp). Bad input must
// end in an InputError with a message; anything else (a crash, a sanitizer finding, another exception) is a bug.
// The first byte picks the reader and its options: bit 3 the rig export; then force required (bit 0), units
// (bit 1), columns (bit 2) for a plain file; a mapping of CHANNEL0/CHANNEL1 (bit 4), the split at events (bit 5),
// smoothing and mean removal (bit 6), whole cycles (bit 7) for an export. Input that starts with "MATLAB" is a
// .mat file (engine/record/mat_file.hpp), read from a scratch file as v4/v5 only: the v7.3 path is HDF5's own
// reader, whose damaged-attribute handling AddressSanitizer flags inside HDF5 1.10 itself.
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include <unistd.h>

#include "engine/common/error.hpp"
#include "engine/record/csv_loader.hpp"
#include "engine/record/mat_file.hpp"
#include "engine/record/record_files.hpp"
#include "engine/record/signals.hpp"
#include "engine/record/text_channels.hpp"

namespace {

void plain_file(std::uint8_t options_byte, std::istringstream& in) {
  dampbench::CsvOptions options;
  options.require_force = (options_byte & 1) != 0;
  if (options_byte & 2) options.units = {{"x", "mm"}, {"F", "kN"}};
  if (options_byte & 4) options.columns = {"t", "x", "F"};
  const dampbench::Dataset d = dampbench::parse_csv(in, "fuzz.csv", options);
  (void)dampbench::prepare_signals(d);
}

void rig_export(std::uint8_t options_byte, std::istringstream& in) {
  const dampbench::ChannelTable table = dampbench::parse_text_channels(in, "fuzz.txt", std::nullopt);
  dampbench::RecordOptions o;
  if (options_byte & 16) o.columns = "x=CHANNEL1,F=CHANNEL0";
  o.scale = (options_byte & 16) ? "x=10e-3,F=980.665" : "";
  if (options_byte & 32) o.split = "events";
  if (options_byte & 64) o.smooth_samples = 5, o.remove_mean = "x";
  o.whole_cycles = (options_byte & 128) != 0;
  for (const dampbench::Dataset& d : dampbench::records_from_channels(table, o, (options_byte & 1) != 0))
    (void)dampbench::prepare_signals(d);
}

void mat_file(std::uint8_t options_byte, std::string bytes) {
  if (bytes.size() >= 128 && bytes[126] == 'I' && bytes[127] == 'M') bytes[124] = 0, bytes[125] = 1;  // v5, never v7.3
  const std::string path = "/tmp/dampbench_fuzz_" + std::to_string(::getpid()) + ".mat";
  std::ofstream(path, std::ios::binary) << bytes;
  try {
    dampbench::RecordOptions o;
    if (options_byte & 16) o.columns = "t=#0,x=data[:,0],F=data[:,1:3]";
    for (const dampbench::Dataset& d : dampbench::records_from_channels(dampbench::read_mat_file(path), o, true))
      (void)dampbench::prepare_signals(d);
  } catch (const dampbench::InputError&) {
    std::remove(path.c_str());
    throw;
  }
  std::remove(path.c_str());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  std::istringstream in(bytes);
  try {
    if (bytes.starts_with("MATLAB")) mat_file(data[0], bytes);
    else if (data[0] & 8) rig_export(data[0], in);
    else plain_file(data[0], in);
  } catch (const dampbench::InputError&) {
  }
  return 0;
}
