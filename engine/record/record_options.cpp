#include "engine/record/record_options.hpp"

#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"
#include "engine/record/csv_loader.hpp"
#include "engine/record/record_files.hpp"
#include "engine/record/record_transforms.hpp"

namespace dampbench {

void set_operating(Dataset& data, const std::string& text, std::string_view option) {
  for (const auto& [name, value] : parse_key_values(text, option)) {
    if (name != "I" && name != "V" && name != "phi" && name != "amp" && name != "freq")
      throw InputError(fmt::format("{}: unknown operating variable '{}' (known: I, V, phi, amp, freq)", option, name));
    data.operating[name] = parse_number(value, fmt::format("{} {}", option, name));
    data.operating_source[name] = std::string(option);
    data.operating_refused.erase(name);  // a stated constant replaces the column
    data.operating_signals.erase(name);
  }
}

std::vector<Dataset> load_records(const RecordOptions& options, bool require_force) {
  return as_data_error([&] {
    std::vector<Dataset> records = read_record_file(options, require_force);
    const std::vector<std::string> operating = operating_per_record(options.set, records.size());
    RecordOptions each = options;
    for (std::size_t r = 0; r < records.size(); ++r) {
      each.set = operating[r];
      records[r] = prepare_record(std::move(records[r]), each);
    }
    return records;
  });
}

Dataset load_record(const RecordOptions& options, bool require_force) {
  std::vector<Dataset> records = load_records(options, require_force);
  if (records.size() != 1)
    throw DataError(fmt::format("{}: gives {} records (a --columns range or --split); this takes one record per file: "
                                "pick one column (F=data[:,k]) or fit them together with `dampbench fit --data`",
                                options.path, records.size()));
  return std::move(records.front());
}

Dataset prepare_record(Dataset data, const RecordOptions& options) {
  if (data.is_system() && (!options.transform.empty() || !options.average.empty()))
    throw InputError(fmt::format("{}: --transform and --average-cycles act on a rig record's stroke; this is a system "
                                 "record (t, y, u: force in, displacement out)",
                                 data.source));
  if (options.periodic && !data.is_system())
    throw InputError(fmt::format("{}: --periodic applies to system records (t, y, u); this is a rig record (t, x, F)",
                                 data.source));
  data.periodic_input = options.periodic;
  if (options.transform == "slider-crank" || options.transform == "slider-crank-printed") {
    SliderCrank rig;
    rig.printed_torque = options.transform == "slider-crank-printed";
    data = to_rotary(data, rig);
  } else if (!options.transform.empty()) {
    throw InputError(fmt::format("--transform: expected slider-crank or slider-crank-printed, got '{}'", options.transform));
  }
  if (!options.average.empty()) {
    int cycles = 0, drop = 0;
    for (const auto& [key, value] : parse_key_values(options.average, "--average-cycles")) {
      const double n = parse_number(value, "--average-cycles " + key);
      if (n != std::floor(n) || n < 0) throw InputError(fmt::format("--average-cycles {}: expected a whole number, got '{}'", key, value));
      if (key == "cycles") cycles = static_cast<int>(n);
      else if (key == "drop") drop = static_cast<int>(n);
      else throw InputError(fmt::format("--average-cycles: unknown key '{}' (expected cycles, drop)", key));
    }
    data = average_cycles(data, cycles, drop);
  }
  if (options.conditions == "utfsm") {
    for (const auto& [k, v] : utfsm_conditions(data.name)) {
      data.operating[k] = v;
      data.operating_source[k] = "file name";
      data.operating_refused.erase(k);
      data.operating_signals.erase(k);
    }
  } else if (!options.conditions.empty()) {
    throw InputError(fmt::format("--conditions: expected utfsm, got '{}'", options.conditions));
  }
  if (!options.set.empty()) set_operating(data, options.set);
  return data;
}

}  // namespace dampbench
