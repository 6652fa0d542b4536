#pragma once
// The v5 .mat format checked before libmatio reads it (engine/record/mat_file.cpp): matio sizes its allocations from
// a variable's header (dimensions, name, a struct's field names and fields) before it checks them against the bytes
// behind them, and reads a variable cut short or a broken zlib stream as zeros without an error. These checks walk
// the same bytes first, so a damaged file costs an "(unreadable)" entry, not gigabytes or wrong values.
#include <cstdint>
#include <string>
#include <vector>

namespace dampbench {

/// A top-level element of a v5 file (one variable): where its bytes start after its tag, how many its tag claims,
/// whether they are a zlib stream.
struct V5Element {
  std::uintmax_t offset = 0;
  std::uint32_t bytes = 0;
  bool compressed = false;
  bool swapped = false;  ///< the file's byte order is not this machine's
};

/// The top-level elements of the v5 file `path`, from their tags, in the order matio lists the variables.
std::vector<V5Element> v5_elements(const std::string& path, std::uintmax_t file_bytes);

/// True when all of `element` is in the file and, if compressed, its zlib stream is whole. matio checks neither: a
/// variable cut short by a truncated file or a full disk comes back with uninitialised or zero values and no error.
bool v5_element_intact(const std::string& path, const V5Element& element, std::uintmax_t file_bytes);

/// What the pre-scan of a v5 element says about handing it to Mat_VarReadNextInfo.
enum class V5Verdict {
  listable,    ///< matio may list it; its data may still be cut short (v5_element_intact says)
  unreadable,  ///< matio may list it, but its dimensions claim more values than its bytes hold
  unsafe,      ///< matio would allocate from a size in its header that its bytes cannot back: never hand it over
};

/// The pre-scan of `element` : walks its header the way Mat_VarReadNextInfo does and checks each size matio allocates from.
V5Verdict scan_v5_element(const std::string& path, const V5Element& element, std::uintmax_t file_bytes);

}  // namespace dampbench
