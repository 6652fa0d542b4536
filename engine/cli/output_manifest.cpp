#include "engine/cli/output_manifest.hpp"

#include <algorithm>
#include <fstream>
#include <set>

#include "engine/common/text_file.hpp"

namespace dampbench::cli {

namespace {

/// A manifest entry that names a file inside the folder: relative, without `..`, not the manifest itself.
bool inside_folder(const std::filesystem::path& p) {
  if (p.empty() || p.is_absolute() || p == kOutputManifest) return false;
  return std::ranges::none_of(p, [](const std::filesystem::path& part) { return part == ".."; });
}

}  // namespace

std::vector<std::string> replace_output_manifest(const std::filesystem::path& out_dir,
                                                 const std::vector<std::string>& written) {
  namespace fs = std::filesystem;
  const std::set<std::string> now(written.begin(), written.end());
  std::vector<std::string> removed;
  std::ifstream previous(out_dir / kOutputManifest);
  for (std::string line; std::getline(previous, line);) {
    if (line.empty() || line.front() == '#' || now.contains(line)) continue;
    const fs::path file = out_dir / line;
    std::error_code ec;
    if (inside_folder(line) && fs::is_regular_file(file, ec) && fs::remove(file, ec)) removed.push_back(line);
  }
  std::string text = "# Files the last `dampbench run` wrote into this folder; the next run into it removes those it "
                     "does not write again.\n";
  for (const auto& f : now) text += f + "\n";
  write_text_file((out_dir / kOutputManifest).string(), text);
  return removed;
}

}  // namespace dampbench::cli
