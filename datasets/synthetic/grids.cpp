#include "datasets/synthetic/grids.hpp"

#include <fstream>
#include <sstream>
#include <system_error>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include "datasets/synthetic/synthetic.hpp"
#include "engine/common/error.hpp"

namespace dampbench::synthetic {

namespace fs = std::filesystem;

const std::vector<std::string>& grid_names() {
  static const std::vector<std::string> names{"fvd", "crfd", "crfd-neutral", "mfm", "mfm-neutral", "fdsp", "fdsp-neutral"};
  return names;
}

void write_grid(const std::string& name, const fs::path& dir, std::uint64_t seed) {
  if (name == "fvd") return write_fvd(dir, seed);
  if (name == "crfd") return write_crfd(dir, seed);
  if (name == "crfd-neutral") return write_crfd_neutral(dir, seed);
  if (name == "mfm") return write_mfm(dir, seed);
  if (name == "mfm-neutral") return write_mfm_neutral(dir, seed);
  if (name == "fdsp") return write_fdsp(dir, seed);
  if (name == "fdsp-neutral") return write_fdsp_neutral(dir, seed);
  throw InputError(fmt::format("unknown synthetic grid '{}' (known: {})", name, fmt::join(grid_names(), ", ")));
}

namespace {

std::string stamp_text(const std::string& name, const std::string& identity) {
  return fmt::format("{}\ngrid {} seed {}\n", identity, name, kGridSeed);
}

std::string read_stamp(const fs::path& dir) {
  std::ifstream in(dir / "stamp");
  std::ostringstream text;
  text << in.rdbuf();
  return in ? text.str() : std::string();
}

}  // namespace

GridState ensure_grid(const fs::path& root, const std::string& name, const std::string& identity) {
  const fs::path dir = root / name;
  const std::string stamp = stamp_text(name, identity);
  std::error_code ec;
  const bool existed = fs::exists(dir, ec);
  if (existed && read_stamp(dir) == stamp) return GridState::kPresent;

  // Host and process in the name: the ranks of an MPI job on several nodes may share the cache folder.
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  const fs::path tmp = root / fmt::format(".{}.tmp-{}-{}", name, host, ::getpid());
  try {
    fs::remove_all(tmp);
    write_grid(name, tmp, kGridSeed);
    std::ofstream out(tmp / "stamp");
    out << stamp;
    out.flush();
    if (!out) throw InputError(fmt::format("cannot write '{}'", (tmp / "stamp").string()));
    if (existed) fs::remove_all(dir);
    fs::rename(tmp, dir, ec);
    if (ec) {  // another process placed the grid first: it is the same grid if its stamp matches
      fs::remove_all(tmp);
      if (read_stamp(dir) != stamp) throw fs::filesystem_error("cannot move the new grid into place", tmp, dir, ec);
    }
  } catch (const fs::filesystem_error& e) {
    std::error_code ignore;
    fs::remove_all(tmp, ignore);
    throw InputError(fmt::format("cannot write the synthetic grid '{}' into '{}': {} (set DAMPBENCH_GENERATED_DIR "
                                 "to a writable folder)",
                                 name, root.string(), e.code().message()));
  } catch (...) {
    std::error_code ignore;
    fs::remove_all(tmp, ignore);
    throw;
  }
  return existed ? GridState::kRegenerated : GridState::kGenerated;
}

}  // namespace dampbench::synthetic
