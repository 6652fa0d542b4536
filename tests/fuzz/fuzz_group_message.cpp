// libFuzzer target: the task-group messages MPI ranks exchange (engine/distributed/group_codec.hpp). Any bytes
// must decode to a record or end in a DataError; a record that decodes must survive encode → decode unchanged
// (compare_records). Seeds: every group of a real store, encoded (scripts/fuzz.sh sets DAMPBENCH_FUZZ_SEED_STORE
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
  for (const auto& g : store.groups(query))
    std::ofstream(std::string(dir) + "/group-" + std::to_string(g.index), std::ios::binary)
        << dampbench::distributed::encode_group(g);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  dampbench::sweep::GroupRecord record;
  try {
    record = dampbench::distributed::decode_group(std::string_view(reinterpret_cast<const char*>(data), size));
  } catch (const dampbench::DataError&) {
    return 0;
  }
  const auto again = dampbench::distributed::decode_group(dampbench::distributed::encode_group(record));
  if (!dampbench::sweep::compare_records(record, again).empty()) std::abort();
  return 0;
}
