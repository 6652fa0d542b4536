// libFuzzer target: the task-group messages MPI ranks exchange (engine/distributed/group_codec.hpp). Any bytes
// must decode to a record or end in a DataError; a record that decodes must re-encode to bytes that decode and
// re-encode to the same bytes. Seeds: every group of a real store, encoded (scripts/fuzz.sh sets DAMPBENCH_FUZZ_SEED_STORE
// and DAMPBENCH_FUZZ_SEED_DIR, and LLVMFuzzerInitialize writes them before the corpus is read).
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>
#include <string_view>

#include "engine/common/error.hpp"
#include "engine/distributed/group_codec.hpp"
#include "engine/sweep/store.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const char* store_path = std::getenv("DAMPBENCH_FUZZ_SEED_STORE");
  const char* dir = std::getenv("DAMPBENCH_FUZZ_SEED_DIR");
  if (!store_path || !dir) return 0;
  const auto store = dampbench::sweep::Store::open(store_path);
  dampbench::sweep::GroupQuery query;
  query.traces = true;
  for (const auto& g : store.groups(query)) {
    const std::string bytes = dampbench::distributed::encode_group(g);
    (void)dampbench::distributed::decode_group(bytes);  // a seed that does not decode is a bug: DataError ends here
    std::ofstream(std::string(dir) + "/group-" + std::to_string(g.index), std::ios::binary) << bytes;
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  dampbench::sweep::GroupRecord record;
  try {
    record = dampbench::distributed::decode_group(std::string_view(reinterpret_cast<const char*>(data), size));
  } catch (const dampbench::DataError&) {
    return 0;
  }
  // Every field is written, so a decoded record re-encodes to bytes that decode to itself: same bytes again.
  const std::string bytes = dampbench::distributed::encode_group(record);
  if (dampbench::distributed::encode_group(dampbench::distributed::decode_group(bytes)) != bytes) std::abort();
  return 0;
}
