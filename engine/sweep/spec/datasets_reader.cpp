// [[datasets]]: the entries, their load options, and their files (one file, a list, or a glob), checked to exist
// when the sweep is about to run; "@generated/" grids are generated on first use.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "engine/common/key_values.hpp"
#include "engine/record/column_map.hpp"
#include "engine/record/csv_loader.hpp"
#include "engine/sweep/spec/reader.hpp"

namespace dampbench::sweep::spec_file {
namespace {

namespace fs = std::filesystem;

/// Expands a glob whose wildcards (*, ?) are in the file name only; sorted by name.
std::vector<std::string> expand_glob(const std::string& pattern) {
  const fs::path p(pattern);
  const std::string name = p.filename().string();
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");  // a bare pattern: the current folder
  auto match = [](std::string_view pat, std::string_view s, auto&& self) -> bool {
    if (pat.empty()) return s.empty();
    if (pat[0] == '*') return self(pat.substr(1), s, self) || (!s.empty() && self(pat, s.substr(1), self));
    if (s.empty()) return false;
    return (pat[0] == '?' || pat[0] == s[0]) && self(pat.substr(1), s.substr(1), self);
  };
  std::vector<std::string> out;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_regular_file()) continue;
    const std::string f = e.path().filename().string();
    if (match(name, f, match)) out.push_back(p.has_parent_path() ? (dir / f).string() : f);
  }
  std::sort(out.begin(), out.end());
  return out;
}

void check_load_options(const Reader& r, const toml::table& t, const std::string& key, const RecordOptions& load) {
  if (!load.units.empty()) r.check(t.get("units"), Reader::join(key, "units"), [&] { return parse_units_option(load.units); });
  if (!load.columns.empty())
    r.check(t.get("columns"), Reader::join(key, "columns"), [&] {
      return is_column_map(load.columns) ? parse_column_map(load.columns, "columns").size()
                                         : split_list(load.columns, "columns").size();
    });
  if (!load.scale.empty()) r.check(t.get("scale"), Reader::join(key, "scale"), [&] { return parse_key_values(load.scale, "scale"); });
  if (!load.remove_mean.empty())
    r.check(t.get("remove_mean"), Reader::join(key, "remove_mean"), [&] { return split_list(load.remove_mean, "remove_mean"); });
  if (!load.transform.empty() && load.transform != "slider-crank" && load.transform != "slider-crank-printed")
    r.fail(t.get("transform"), Reader::join(key, "transform"),
           fmt::format("expected slider-crank or slider-crank-printed, got '{}'", load.transform));
  if (!load.conditions.empty() && load.conditions != "utfsm")
    r.fail(t.get("conditions"), Reader::join(key, "conditions"), fmt::format("expected utfsm, got '{}'", load.conditions));
  if (!load.average.empty()) {
    r.check(t.get("average"), Reader::join(key, "average"), [&] {
      for (const auto& [k, v] : parse_key_values(load.average, "average")) {
        const double n = parse_number(v, "average " + k);
        if (n != std::floor(n) || n < 0) throw InputError(fmt::format("average {}: expected a whole number, got '{}'", k, v));
        if (k != "cycles" && k != "drop") throw InputError(fmt::format("average: unknown key '{}' (expected cycles, drop)", k));
      }
      return 0;
    });
  }
  if (!load.set.empty()) {
    r.check(t.get("set"), Reader::join(key, "set"), [&] {
      for (const auto& [k, v] : parse_key_values(load.set, "set")) {
        if (k != "I" && k != "V" && k != "phi" && k != "amp" && k != "freq")
          throw InputError(fmt::format("set: unknown operating variable '{}' (known: I, V, phi, amp, freq)", k));
        parse_number(v, "set " + k);
      }
      return 0;
    });
  }
}

RecordOptions read_load_options(const Reader& r, const toml::table& t, const std::string& key) {
  RecordOptions load;
  load.units = r.string(t, "units", key).value_or("");
  load.columns = r.string(t, "columns", key).value_or("");
  load.transform = r.string(t, "transform", key).value_or("");
  load.average = r.string(t, "average", key).value_or("");
  load.conditions = r.string(t, "conditions", key).value_or("");
  load.set = r.string(t, "set", key).value_or("");
  // A rig's raw export (engine/record/record_files.hpp); one record per file here: no split, no column range.
  load.skip_header = static_cast<int>(r.integer(t, "skip_header", key, -1, 0));
  load.scale = r.string(t, "scale", key).value_or("");
  load.smooth_samples = static_cast<int>(r.integer(t, "smooth", key, 0, 2));
  load.remove_mean = r.string(t, "remove_mean", key).value_or("");
  load.whole_cycles = r.boolean(t, "whole_cycles", key, false);
  check_load_options(r, t, key, load);
  return load;
}

/// The files of one entry, or nothing when an optional entry is skipped (with a line in `notes`).
std::optional<std::vector<std::string>> entry_files(const Reader& r, const toml::table& t, const std::string& key,
                                                    const SpecOptions& options, bool required,
                                                    std::vector<std::string>& notes) {
  const std::string folder = fs::path(r.path()).parent_path().string();
  std::vector<std::string> files;
  const toml::node* source_node = t.get("file") ? t.get("file") : t.get("files") ? t.get("files") : t.get("glob");
  const std::string source_key = Reader::join(key, t.get("file") ? "file" : t.get("files") ? "files" : "glob");
  if (options.check_files)  // "@generated/" grids are generated on first use
    for (const auto& text : r.strings(*source_node, source_key))
      r.check(source_node, source_key, [&] { ensure_generated(text, notes); });
  if (t.get("glob")) {
    const std::string pattern = resolve_path(r.required_string(t, "glob", key), folder);
    if (options.check_files) {
      files = expand_glob(pattern);
      if (files.empty()) {
        if (!required) {
          notes.push_back(fmt::format("{}: skipped (optional): no file matches '{}'", r.where(source_node, source_key), pattern));
          return std::nullopt;
        }
        r.fail(source_node, source_key, fmt::format("no file matches '{}'", pattern));
      }
    }
  } else {
    for (const auto& f : r.strings(*source_node, source_key)) files.push_back(resolve_path(f, folder));
    if (files.empty()) r.fail(source_node, source_key, "expected at least one file");
  }
  if (options.check_files) {
    for (const auto& f : files) {
      std::error_code ec;
      if (fs::is_regular_file(f, ec)) continue;
      if (!required) {
        notes.push_back(fmt::format("{}: skipped (optional): missing files", r.where(source_node, source_key)));
        return std::nullopt;
      }
      r.fail(source_node, source_key, fmt::format("cannot open data file '{}'", f));
    }
  }
  return files;
}

}  // namespace

void read_datasets(const Reader& r, const toml::table& root, const SpecOptions& options, PartSpec& part,
                   std::vector<std::string>& notes) {
  const toml::node* datasets = root.get("datasets");
  if (!datasets || !datasets->is_array_of_tables() || datasets->as_array()->empty())
    r.fail(datasets, "datasets", "expected one or more [[datasets]] tables");
  std::map<std::string, std::string> seen;  // dataset name → where
  const auto& a = *datasets->as_array();
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string key = fmt::format("datasets[{}]", i);
    const toml::table& t = *a.get(i)->as_table();
    r.only_keys(t, key, {"name", "label", "file", "files", "glob", "units", "columns", "transform", "average",
                         "conditions", "set", "required", "skip_header", "scale", "smooth", "remove_mean", "whole_cycles"});
    const std::string name = r.required_string(t, "name", key);
    if (std::find(part.collections.begin(), part.collections.end(), name) != part.collections.end())
      r.fail(t.get("name"), Reader::join(key, "name"), fmt::format("dataset entry name '{}' is used twice", name));
    part.collections.push_back(name);
    const RecordOptions load = read_load_options(r, t, key);
    const bool required = r.boolean(t, "required", key, true) && !options.datasets_optional;
    const int sources = (t.get("file") != nullptr) + (t.get("files") != nullptr) + (t.get("glob") != nullptr);
    if (sources != 1) r.fail(&t, key, "expected exactly one of 'file', 'files' and 'glob'");
    const auto files = entry_files(r, t, key, options, required, notes);
    if (!files) continue;
    const bool single = t.get("file") != nullptr;
    const toml::node* source_node = t.get("file") ? t.get("file") : t.get("files") ? t.get("files") : t.get("glob");
    const std::string source_key = Reader::join(key, t.get("file") ? "file" : t.get("files") ? "files" : "glob");
    for (const auto& f : *files) {
      DatasetSpec d;
      d.collection = name;
      d.name = single ? name : fs::path(f).stem().string();
      d.label = single ? r.string(t, "label", key).value_or(name) : d.name;
      d.load = load;
      d.load.path = f;
      if (auto [it, fresh] = seen.emplace(d.name, key); !fresh)
        r.fail(source_node, source_key, fmt::format("dataset name '{}' is already used by {}", d.name, it->second));
      part.datasets.push_back(std::move(d));
    }
  }
}

}  // namespace dampbench::sweep::spec_file
