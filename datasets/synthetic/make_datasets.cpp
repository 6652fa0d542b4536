// Writes the synthetic datasets of one paper (or all) into a folder.
// Usage: make_datasets fvd|crfd|mfm|fdsp|all OUTPUT_DIR [seed]
#include <cstdio>
#include <exception>
#include <string>

#include "datasets/synthetic/synthetic.hpp"

int main(int argc, char** argv) {
  using namespace dampbench::synthetic;
  if (argc < 3) {
    std::fprintf(stderr, "usage: make_datasets fvd|crfd|mfm|fdsp|all OUTPUT_DIR [seed]\n");
    return 2;
  }
  const std::string paper = argv[1];
  const std::filesystem::path dir = argv[2];
  try {
    const std::uint64_t seed = argc > 3 ? std::stoull(argv[3]) : 2024;
    if (paper == "fvd" || paper == "all") write_fvd(paper == "all" ? dir / "fvd" : dir, seed);
    if (paper == "crfd" || paper == "all") write_crfd(paper == "all" ? dir / "crfd" : dir, seed);
    if (paper == "mfm" || paper == "all") write_mfm(paper == "all" ? dir / "mfm" : dir, seed);
    if (paper == "fdsp" || paper == "all") write_fdsp(paper == "all" ? dir / "fdsp" : dir, seed);
    if (paper != "fvd" && paper != "crfd" && paper != "mfm" && paper != "fdsp" && paper != "all") {
      std::fprintf(stderr, "make_datasets: unknown paper '%s' (known: fvd, crfd, mfm, fdsp, all)\n", paper.c_str());
      return 2;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_datasets: %s\n", e.what());
    return 2;
  }
  return 0;
}
