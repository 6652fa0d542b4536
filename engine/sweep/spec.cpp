#include "engine/sweep/spec.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include "engine/record/csv_loader.hpp"
#include "engine/record/signals.hpp"
#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"
#include "engine/model/law_model.hpp"
#include "engine/model/parameter_law.hpp"
#include "engine/common/random.hpp"
#include "engine/sweep/fingerprint.hpp"
#include "datasets/synthetic/grids.hpp"
#include "models/fixtures.hpp"
#include "models/registry.hpp"

#ifndef DAMPBENCH_SHARED_DATA_DIR
#define DAMPBENCH_SHARED_DATA_DIR "../shared/data"
#endif

namespace dampbench::sweep {

namespace fs = std::filesystem;

bool Selection::matches(const std::string& name, const std::map<std::string, double>& variables) const {
  if (any.empty()) return true;
  for (const Condition& c : any) {
    bool ok = c.names.empty() || std::find(c.names.begin(), c.names.end(), name) != c.names.end();
    for (const auto& [var, values] : c.variables) {
      if (!ok) break;
      const auto it = variables.find(var);
      ok = it != variables.end() && std::any_of(values.begin(), values.end(), [&](double v) {
             return same_operating_value(it->second, v);
           });
    }
    if (ok) return true;
  }
  return false;
}

int PartSpec::model_index(std::string_view n) const {
  for (std::size_t i = 0; i < models.size(); ++i)
    if (models[i].name == n) return static_cast<int>(i);
  return -1;
}
int PartSpec::optimizer_index(std::string_view n) const {
  for (std::size_t i = 0; i < optimizers.size(); ++i)
    if (optimizers[i].label == n) return static_cast<int>(i);
  return -1;
}
std::vector<std::pair<int, int>> PartSpec::pairs(const SplitSpec& split) const {
  const auto listed = [](const std::vector<std::string>& names, const std::string& entry) {
    return names.empty() || std::find(names.begin(), names.end(), entry) != names.end();
  };
  std::vector<std::pair<int, int>> out;
  for (int m = 0; m < static_cast<int>(models.size()); ++m) {
    if (!listed(split.models, models[m].name)) continue;
    for (int o = 0; o < static_cast<int>(optimizers.size()); ++o)
      if (listed(split.optimizers, optimizers[o].label) && listed(models[m].optimizers, optimizers[o].label))
        out.emplace_back(m, o);
  }
  return out;
}

int PartSpec::split_index(std::string_view n) const {
  for (std::size_t i = 0; i < splits.size(); ++i)
    if (splits[i].name == n) return static_cast<int>(i);
  return -1;
}

std::string generated_dir() {
  if (const char* env = std::getenv("DAMPBENCH_GENERATED_DIR"); env && *env) return env;
  fs::path cache;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) cache = xdg;
  else if (const char* home = std::getenv("HOME"); home && *home) cache = fs::path(home) / ".cache";
  else cache = fs::temp_directory_path();
  // One folder per build identity, so that two builds sharing a cache never regenerate each other's grids.
  return (cache / "dampbench" / fmt::format("generated-{:016x}", hash_name(generator_identity()))).string();
}

std::string generator_identity() { return fmt::format("dampbench {} ({})", dampbench_version(), build_flags()); }

void ensure_generated(std::string_view text, std::vector<std::string>& notes) {
  constexpr std::string_view prefix = "@generated/";
  if (!text.starts_with(prefix)) return;
  const std::string_view rest = text.substr(prefix.size());
  const std::string grid(rest.substr(0, rest.find('/')));
  const auto& known = synthetic::grid_names();
  if (std::find(known.begin(), known.end(), grid) == known.end())
    throw InputError(fmt::format("'{}' names no synthetic grid (known: {})", text, fmt::join(known, ", ")));
  const std::string root = generated_dir();
  if (synthetic::ensure_grid(root, grid, generator_identity()) != synthetic::GridState::kPresent)
    notes.push_back(fmt::format("generated the synthetic grid '{}' into {}", grid, (fs::path(root) / grid).string()));
}

std::string shared_data_dir() {
  if (const char* env = std::getenv("DAMPBENCH_SHARED_DATA_DIR"); env && *env) return env;
  return DAMPBENCH_SHARED_DATA_DIR;
}

std::string resolve_path(std::string_view text, const std::string& folder) {
  auto under = [&](std::string_view prefix, const std::string& dir) -> std::optional<std::string> {
    if (!text.starts_with(prefix)) return std::nullopt;
    return (fs::path(dir) / fs::path(std::string(text.substr(prefix.size())))).lexically_normal().string();
  };
  if (auto p = under("@generated/", generated_dir())) return *p;
  if (auto p = under("@shared/", shared_data_dir())) return *p;
  const fs::path p{std::string(text)};
  if (p.is_absolute()) return p.lexically_normal().string();
  return (fs::path(folder) / p).lexically_normal().string();
}

}  // namespace dampbench::sweep
