// A sweep file: one part, or a file of parts (`include`); each part read by the readers of its kinds, and the
// spec hash over the parts' canonical forms.
#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/common/random.hpp"
#include "engine/sweep/spec/reader.hpp"

namespace dampbench::sweep {
namespace spec_file {
namespace {

namespace fs = std::filesystem;

/// Canonical JSON of the keys that decide results (not titles, labels, tables, regressions or the published numbers).
std::string canonical(const toml::table& root) {
  toml::table copy = root;
  for (const char* k : {"title", "tables", "regressions", "reproduction"}) copy.erase(k);
  if (auto* d = copy.get("datasets"); d && d->is_array()) {
    for (auto& e : *d->as_array())
      if (e.is_table()) e.as_table()->erase("label");
  }
  std::ostringstream out;
  out << toml::json_formatter{copy};
  return out.str();
}

PartSpec read_part_table(const Reader& r, const toml::table& root, const SpecOptions& options,
                         std::vector<std::string>& notes) {
  PartSpec part;
  r.only_keys(root, "", {"name", "title", "seed", "runs", "metric", "metrics", "models", "bounds", "optimizer",
                         "optimizers", "datasets", "splits", "tables", "regressions", "reproduction"});
  part.path = r.path();
  part.name = r.required_string(root, "name", "");
  part.title = r.string(root, "title", "").value_or(part.name);
  part.seed = static_cast<std::uint64_t>(r.integer(root, "seed", "", 1, 0));
  part.runs = static_cast<int>(r.integer(root, "runs", "", 50, 1));
  read_metrics(r, root, part);
  read_models(r, root, part);
  read_optimizers(r, root, part);
  // Tables and splits name datasets entries: read entry names first, files last (a bad bound is
  // reported before a missing file).
  const toml::node* datasets = root.get("datasets");
  if (!datasets || !datasets->is_array_of_tables() || datasets->as_array()->empty())
    r.fail(datasets, "datasets", "expected one or more [[datasets]] tables");
  for (const toml::node& d : *datasets->as_array()) {
    const toml::node* n = d.as_table()->get("name");
    if (n && n->is_string()) part.collections.emplace_back(*n->value<std::string>());
  }
  read_splits(r, root, part);
  check_auto_laws(r, root, part);
  check_holds(r, root, part);
  read_tables(r, root, part);
  read_regressions(r, root, part);
  read_reproduction(r, root, part, options.check_files);
  part.collections.clear();
  read_datasets(r, root, options, part, notes);
  part.canonical = canonical(root);
  return part;
}

std::string hex64(std::uint64_t v) { return fmt::format("{:016x}", v); }

/// `extends = "base.toml"`: the base file's keys, each replaced whole by the extending file's key of the same name,
/// so that a preset on other records (a neutral truth's grid) keeps its paper's models, splits and tables in one
/// place. The base is a sweep file of one part in the same folder (its relative paths are read from there); it may
/// extend another, up to kMaxExtends files deep.
constexpr int kMaxExtends = 4;

toml::table extended(const Reader& r, const toml::table& root, const std::string& path, int depth = 1) {
  const toml::node* base = root.get("extends");
  if (!base->is_string()) r.fail(base, "extends", "expected the path of a sweep file in the same folder");
  const std::string folder = fs::path(path).parent_path().string();
  const std::string base_path = resolve_path(*base->value<std::string>(), folder);
  if (fs::path(base_path).parent_path() != fs::path(folder).lexically_normal())
    r.fail(base, "extends", fmt::format("'{}' is not in this file's folder (its relative paths would change meaning)",
                                        base_path));
  const std::string text = r.check(base, "extends", [&] { return read_text(base_path, "extended sweep file"); });
  toml::table merged = parse_toml(text, base_path);
  if (merged.contains("include"))
    r.fail(base, "extends", fmt::format("'{}' includes other files; the base must be one part", base_path));
  if (merged.contains("extends")) {
    if (depth >= kMaxExtends)
      r.fail(base, "extends", fmt::format("more than {} files extend each other from here (a loop?)", kMaxExtends));
    merged = extended(Reader(base_path), merged, base_path, depth + 1);
  }
  for (const auto& [key, value] : root)
    if (key != "extends") merged.insert_or_assign(key, toml::node_view<const toml::node>(value));
  return merged;
}

}  // namespace

PartSpec read_part(std::string_view text, const std::string& path, const SpecOptions& options,
                   std::vector<std::string>& notes) {
  const Reader r(path);
  const toml::table root = parse_toml(text, path);
  std::vector<std::string> part_notes;
  PartSpec part;
  if (root.contains("extends")) {
    // Keys of the merged part are copies, without their lines: messages name the file and the key.
    const toml::table merged = extended(r, root, path);
    part = read_part_table(r, merged, options, part_notes);
    // The stored source is the merged part, so that a store re-reads its tables without the base.
    std::ostringstream source;
    source << toml::toml_formatter{merged};
    part.source = source.str();
  } else {
    part = read_part_table(r, root, options, part_notes);
    part.source = std::string(text);
  }
  notes.insert(notes.end(), part_notes.begin(), part_notes.end());
  return part;
}

std::string read_text(const std::string& path, std::string_view what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("cannot open {} '{}'", what, path));
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

namespace {

SweepSpec parse_sweep_text(std::string_view text, const std::string& path, const SpecOptions& options) {
  SweepSpec spec;
  spec.path = path;
  std::vector<std::string> notes;
  const toml::table root = parse_toml(text, path);
  if (const toml::node* inc = root.get("include")) {
    const Reader r(path);
    r.only_keys(root, "", {"name", "title", "include", "include_optional"});
    spec.name = r.required_string(root, "name", "");
    spec.title = r.string(root, "title", "").value_or(spec.name);
    auto files = r.strings(*inc, "include");
    const auto optional = r.strings(root, "include_optional", "");
    files.insert(files.end(), optional.begin(), optional.end());
    if (files.empty()) r.fail(inc, "include", "expected one or more sweep files");
    for (std::size_t i = 0; i < files.size(); ++i) {
      const std::string p = resolve_path(files[i], fs::path(path).parent_path().string());
      const std::string t = r.check(inc, "include", [&] { return read_text(p, "included sweep file"); });
      SpecOptions part_options = options;
      part_options.datasets_optional |= i + optional.size() >= files.size();
      spec.parts.push_back(read_part(t, p, part_options, notes));
      for (std::size_t k = 0; k + 1 < spec.parts.size(); ++k)
        if (spec.parts[k].name == spec.parts.back().name)
          r.fail(inc, "include", fmt::format("two included files are named '{}'", spec.parts.back().name));
    }
  } else {
    spec.parts.push_back(read_part(text, path, options, notes));
    spec.name = spec.parts[0].name;
    spec.title = spec.parts[0].title;
  }
  // The salt names the meaning of the keys: a file without a budget means the automatic budget since sweep-2, and
  // without a precision the float32 search lanes of precision = "mixed" since sweep-3, and the automatic budget
  // lengthens its restarts and waits for one to confirm the best since sweep-4, asks a second opinion since sweep-5,
  // and its default cap makes room for the second opinion and local stages since sweep-6, so a store written under
  // an earlier meaning is not resumed by a build that reads the same text differently.
  std::uint64_t h = hash_name("dampbench-sweep-6");
  for (const auto& p : spec.parts) h = hash_key({h, hash_name(p.name), hash_name(p.canonical)});
  spec.hash = hex64(h);
  spec.notes = std::move(notes);
  return spec;
}

}  // namespace
}  // namespace spec_file

SweepSpec parse_sweep(std::string_view text, const std::string& path, const SpecOptions& options) {
  return as_data_error([&] { return spec_file::parse_sweep_text(text, path, options); });
}

SweepSpec load_sweep(const std::string& path, const SpecOptions& options) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw DataError(fmt::format("cannot open preset file '{}'", path));
  return parse_sweep(spec_file::read_text(path, "preset file"), path, options);
}

}  // namespace dampbench::sweep
