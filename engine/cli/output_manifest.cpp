#include "engine/cli/output_manifest.hpp"

#include <algorithm>
#include <fstream>
#include <set>

#include "engine/common/text_file.hpp"

namespace dampbench::cli {

namespace {

namespace fs = std::filesystem;

/// The kinds of file a run writes (tables .csv and .md, the report .html): nothing else is ever removed, whatever
/// the manifest says (the store, its -wal, -shm and .lock, a user's files).
bool output_kind(const fs::path& p) {
  const std::string ext = p.extension().string();
  return ext == ".csv" || ext == ".md" || ext == ".html";
}

/// A manifest line as a normal relative path ("./a.csv" and "a.csv" are one file), or empty when it is absolute,
/// leaves the folder (`..`) or is not an output kind.
fs::path listed_output(std::string line) {
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.pop_back();
  const fs::path p = fs::path(line).lexically_normal();
  if (line.empty() || p.is_absolute() || p.empty() || !output_kind(p)) return {};
  if (std::ranges::any_of(p, [](const fs::path& part) { return part == ".."; })) return {};
  return p;
}

/// `file` resolves to a place inside `folder` (a symlinked subfolder may lead elsewhere).
bool resolves_inside(const fs::path& file, const fs::path& folder) {
  std::error_code ec;
  const fs::path f = fs::weakly_canonical(file, ec), d = fs::weakly_canonical(folder, ec);
  if (ec) return false;
  const auto [end, _] = std::mismatch(d.begin(), d.end(), f.begin(), f.end());
  return end == d.end();
}

}  // namespace

std::vector<std::string> replace_output_manifest(const fs::path& out_dir, const std::vector<std::string>& written,
                                                 std::vector<std::string>* kept) {
  std::set<std::string> now;
  for (const auto& w : written) now.insert(fs::path(w).lexically_normal().generic_string());
  std::set<std::string> listed = now;  // the new manifest: what was written, and stale files that could not go
  std::vector<std::string> removed;
  std::ifstream previous(out_dir / kOutputManifest);
  for (std::string line; std::getline(previous, line);) {
    if (line.empty() || line.front() == '#') continue;
    const fs::path p = listed_output(line);
    if (p.empty() || now.contains(p.generic_string())) continue;
    const fs::path file = out_dir / p;
    std::error_code ec;
    if (!fs::is_regular_file(fs::symlink_status(file, ec)) || !resolves_inside(file, out_dir)) continue;
    if (fs::remove(file, ec)) {
      removed.push_back(p.generic_string());
    } else {
      listed.insert(p.generic_string());
      if (kept) kept->push_back(p.generic_string() + " (" + ec.message() + ")");
    }
  }
  std::string text = "# Files the last `dampbench run` wrote into this folder; the next run into it removes those it "
                     "does not write again.\n";
  for (const auto& f : listed) text += f + "\n";
  write_text_file((out_dir / kOutputManifest).string(), text);
  return removed;
}

}  // namespace dampbench::cli
