#pragma once
// The synthetic grids that presets name "@generated/<grid>/...": generated on first use into a cache
// folder, so that every preset runs from every build (`dampbench run` calls ensure_grid before it expands
// a dataset glob; `dampbench datasets generate` does it ahead of time).
//
// A grid folder holds the records and a `stamp` file naming what made them: the dampbench version and
// build flags (libmvec results may differ in the last bit between builds), the grid and its seed. A folder
// whose stamp differs is regenerated; a new grid is written into a temporary folder and renamed into place,
// so a killed generation or two processes generating at once never leave a half-written grid behind.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace dampbench::synthetic {

/// The seed of every generated grid (the noise streams are keyed by it and the file name).
inline constexpr std::uint64_t kGridSeed = 2024;

/// Grid names: "fvd", "crfd", "crfd-neutral", "mfm", "mfm-neutral", "fdsp", "fdsp-neutral" (datasets/README.md).
const std::vector<std::string>& grid_names();

/// Writes grid `name` into `dir` (created). Throws InputError for an unknown name.
void write_grid(const std::string& name, const std::filesystem::path& dir, std::uint64_t seed = kGridSeed);

/// What ensure_grid did.
enum class GridState { kPresent, kGenerated, kRegenerated };

/// Makes sure `root/name` holds grid `name` as this build makes it (`identity` names the build, e.g.
/// "dampbench 0.2.0 (Release,native=OFF,...)"); generates or regenerates it otherwise. Throws InputError
/// naming the folder when it cannot be written.
GridState ensure_grid(const std::filesystem::path& root, const std::string& name, const std::string& identity);

}  // namespace dampbench::synthetic
