// libFuzzer target: the results store reader (engine/sweep/store.hpp). The input is written to a file and opened
// as a store, header and every group read back with traces; the corpus starts from a real store (scripts/fuzz.sh
// writes one), so mutations reach the decoding of rows and blobs. A damaged store must end in a StoreError
// (or InputError) with a message; anything else is a bug.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "engine/common/error.hpp"
#include "engine/sweep/store.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path =
      (std::filesystem::temp_directory_path() / ("dampbench_fuzz_store_" + std::to_string(::getpid()) + ".sqlite")).string();
  for (const char* suffix : {"", "-wal", "-shm"}) std::remove((path + suffix).c_str());
  if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  }
  try {
    const dampbench::sweep::Store store = dampbench::sweep::Store::open(path);
    (void)store.header();
    (void)store.finished();
    dampbench::sweep::GroupQuery query;
    query.traces = true;
    (void)store.groups(query);
  } catch (const dampbench::InputError&) {
  }
  return 0;
}
