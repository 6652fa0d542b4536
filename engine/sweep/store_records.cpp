#include "engine/sweep/store_records.hpp"

#include <algorithm>
#include <optional>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "engine/sweep/spec.hpp"

namespace dampbench::sweep {

std::vector<StoreRecord> reload_store_records(const StoreHeader& h, const Loader& loader) {
  std::vector<std::optional<SweepSpec>> specs(h.parts.size());
  std::vector<std::string> spec_errors(h.parts.size());
  for (std::size_t p = 0; p < h.parts.size(); ++p) try {
      SpecOptions o;
      o.datasets_optional = true;  // a missing file is reported per record below
      specs[p] = parse_sweep(h.parts[p].source, h.parts[p].path, o);
    } catch (const std::exception& e) {
      spec_errors[p] = e.what();
    }
  std::vector<StoreRecord> out(h.datasets.size());
  tbb::parallel_for(std::size_t{0}, h.datasets.size(), [&](std::size_t i) {
    const StoreDataset& d = h.datasets[i];
    StoreRecord& r = out[i];
    const auto p = static_cast<std::size_t>(d.part);
    if (!specs[p]) {
      r.unavailable = fmt::format("the sweep file could not be read again: {}", spec_errors[p]);
      return;
    }
    const auto& list = specs[p]->parts.at(0).datasets;
    const auto it = std::find_if(list.begin(), list.end(), [&](const auto& s) { return s.name == d.name; });
    if (it == list.end()) {
      r.unavailable = fmt::format("its file ({}) is no longer found", d.path);
      return;
    }
    r.loaded = load_dataset(*it, loader);
    if (!r.loaded.ok())
      r.unavailable = r.loaded.error;
    else if (r.loaded.hash != d.hash)
      r.unavailable = fmt::format("{} changed since the store was written (hash {}, stored {})", d.path, r.loaded.hash, d.hash);
  });
  return out;
}

}  // namespace dampbench::sweep
