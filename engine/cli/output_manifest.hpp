#pragma once
// What a sweep wrote into its output folder, so that the next run into the same folder leaves no stale file:
// `outputs.txt` lists the files of the last run (paths relative to the folder, one per line). A run that
// produces fewer tables (another spec after --fresh, a --store elsewhere, --no-report, a report that failed)
// removes the files the previous run listed and this one did not write. Only listed tables and reports
// (.csv, .md, .html) inside the folder are removed: the store, a user's own files, anything reached through a
// symlink outside the folder and anything written by an older dampbench without a list stay.
#include <filesystem>
#include <string>
#include <vector>

namespace dampbench::cli {

inline constexpr const char* kOutputManifest = "outputs.txt";

/// Removes the files the folder's previous manifest lists and `written` does not, then writes the manifest of
/// `written` (relative paths; "./a.csv" and "a.csv" name one file). Entries that are absolute, leave the folder
/// (`..`, a symlink) or are not .csv, .md or .html are ignored, not removed. A listed file that cannot be removed
/// stays listed and is added to `kept` with the reason. Returns the removed files' relative paths.
std::vector<std::string> replace_output_manifest(const std::filesystem::path& out_dir,
                                                 const std::vector<std::string>& written,
                                                 std::vector<std::string>* kept = nullptr);

}  // namespace dampbench::cli
