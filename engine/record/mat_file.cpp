// MATLAB .mat files through libmatio (mat_file.hpp says why matio). Every mat_t and matvar_t lives in a
// unique_ptr whose deleter closes or frees it, so each return and each exception path releases what matio gave.
#include "engine/record/mat_file.hpp"

#include <matio.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <string_view>
#include <system_error>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"
#include "engine/record/mat_v5_scan.hpp"

namespace dampbench {
namespace {

struct MatFileCloser {
  void operator()(mat_t* file) const { Mat_Close(file); }
};
struct MatVarFreer {
  void operator()(matvar_t* variable) const { Mat_VarFree(variable); }
};
using MatFile = std::unique_ptr<mat_t, MatFileCloser>;
using MatVar = std::unique_ptr<matvar_t, MatVarFreer>;

/// zlib's largest compression ratio: no deflated byte of a file expands to more than this many bytes.
constexpr std::uintmax_t kMaxDeflateRatio = 1032;

/// MATLAB's limit on the length of a variable name.
constexpr std::size_t kMaxMatlabNameLength = 63;

/// Text that the header of a v5 or v7.3 file opens with; fixed (matio's default holds the time of writing) so that
/// the same columns give the same file.
constexpr const char* kV5Header = "MATLAB 5.0 MAT-file, written by dampbench";
constexpr const char* kV73Header = "MATLAB 7.3 MAT-file, written by dampbench";

/// How many messages matio (and HDF5 through it) logged since the matio lock was last taken: a v7.3 file that HDF5
/// cannot open still opens in matio, as a file without variables, and only these messages tell the two apart.
std::size_t& matio_message_count() {
  static std::size_t count = 0;
  return count;
}

/// Holds the lock every use of matio takes: matio keeps process-wide state (its log function) and Debian's HDF5,
/// which reads v7.3 files, is built without thread safety. The first lock routes matio's messages, and through
/// matio HDF5's error stacks, to a counter instead of stderr: the InputError or the "(unreadable)" entry says what
/// went wrong, where HDF5 would print a stack of a dozen lines for one damaged variable.
std::unique_lock<std::mutex> lock_matio() {
  static std::mutex mutex;
  std::unique_lock lock(mutex);
  static const bool messages_routed = [] {
    Mat_LogInitFunc("dampbench", [](int /*level*/, char* /*message*/) { ++matio_message_count(); });
    return true;
  }();
  (void)messages_routed;
  matio_message_count() = 0;
  return lock;
}

// ---- reading ------------------------------------------------------------------------------------------------

bool is_numeric_class(matio_classes class_type) {
  switch (class_type) {
    case MAT_C_DOUBLE: case MAT_C_SINGLE:
    case MAT_C_INT8: case MAT_C_UINT8: case MAT_C_INT16: case MAT_C_UINT16:
    case MAT_C_INT32: case MAT_C_UINT32: case MAT_C_INT64: case MAT_C_UINT64:
      return true;
    default:
      return false;
  }
}

/// Why a variable (its header, as matio lists it) is not a channel, e.g. "struct" or "3-D"; nullopt when it is one.
std::optional<std::string> why_not_a_channel(const matvar_t& variable) {
  switch (variable.class_type) {
    case MAT_C_CHAR: return "char";
    case MAT_C_CELL: return "cell";
    case MAT_C_STRUCT: return "struct";
    case MAT_C_SPARSE: return "sparse";
    case MAT_C_FUNCTION: return "function handle";
    case MAT_C_OBJECT: case MAT_C_OPAQUE: return "object";
    case MAT_C_EMPTY: return "no MATLAB class";  // e.g. an HDF5 dataset without MATLAB's class attribute
    default: break;
  }
  if (!is_numeric_class(variable.class_type)) return "unknown class";
  if (variable.isComplex) return "complex";
  if (variable.rank != 2 || variable.dims == nullptr) return fmt::format("{}-D", variable.rank);
  if (variable.dims[0] == 0 || variable.dims[1] == 0) return "empty";
  return std::nullopt;
}

/// True when rows × cols elements could come out of a file of `file_bytes` bytes: every element takes at least one
/// byte in the file before compression. A damaged header that claims more would make matio allocate its claim.
bool fits_in_file(std::size_t rows, std::size_t cols, std::uintmax_t file_bytes) {
  const std::uintmax_t most = file_bytes * kMaxDeflateRatio;
  return rows <= most && cols <= most / rows;
}

template <class T>
std::vector<double> widened(const void* data, std::size_t count) {
  std::vector<double> values(count);
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < count; ++i) {
    T value;
    std::memcpy(&value, bytes + i * sizeof(T), sizeof(T));
    values[i] = static_cast<double>(value);
  }
  return values;
}

/// The `count` values matio read into `variable`, as doubles; nullopt when its buffer holds fewer elements of its
/// type (a damaged file) or a type that is not a number.
std::optional<std::vector<double>> values_as_double(const matvar_t& variable, std::size_t count) {
  const std::size_t element_bytes = Mat_SizeOf(variable.data_type);
  if (variable.data == nullptr || element_bytes == 0 || variable.nbytes / element_bytes < count) return std::nullopt;
  switch (variable.data_type) {
    case MAT_T_DOUBLE: return widened<double>(variable.data, count);
    case MAT_T_SINGLE: return widened<float>(variable.data, count);
    case MAT_T_INT8: return widened<std::int8_t>(variable.data, count);
    case MAT_T_UINT8: return widened<std::uint8_t>(variable.data, count);
    case MAT_T_INT16: return widened<std::int16_t>(variable.data, count);
    case MAT_T_UINT16: return widened<std::uint16_t>(variable.data, count);
    case MAT_T_INT32: return widened<std::int32_t>(variable.data, count);
    case MAT_T_UINT32: return widened<std::uint32_t>(variable.data, count);
    case MAT_T_INT64: return widened<std::int64_t>(variable.data, count);
    case MAT_T_UINT64: return widened<std::uint64_t>(variable.data, count);
    default: return std::nullopt;
  }
}

/// What the reader checks before it lets matio read a variable's data.
struct FileLimits {
  std::string path;
  std::uintmax_t bytes = 0;
  std::optional<std::vector<V5Element>> v5;  ///< set for a v5 file
};

/// True unless the file is a v5 file whose `index`-th element is cut short or missing.
bool v5_variable_intact(std::size_t index, const FileLimits& limits) {
  return !limits.v5 ||
         (index < limits.v5->size() && v5_element_intact(limits.path, (*limits.v5)[index], limits.bytes));
}

/// Reads the data of `matrix`, a numeric 2-D variable or struct field whose header matio listed; nullopt when the
/// file cannot hold it or matio cannot read it.
std::optional<Channel> read_matrix(mat_t& file, matvar_t& matrix, const FileLimits& limits) {
  const std::size_t rows = matrix.dims[0], cols = matrix.dims[1];
  if (!fits_in_file(rows, cols, limits.bytes) || Mat_VarReadDataAll(&file, &matrix) != MATIO_E_NO_ERROR)
    return std::nullopt;
  auto values = values_as_double(matrix, rows * cols);
  if (!values) return std::nullopt;
  return Channel{rows, cols, std::move(*values)};
}

/// The 8 bytes every HDF5 file opens with when it has no user block.
bool starts_as_hdf5(const std::string& path) {
  constexpr std::string_view kHdf5Signature{"\x89HDF\r\n\x1a\n", 8};
  char head[8] = {};
  std::ifstream in(path, std::ios::binary);
  return in.read(head, sizeof head) && std::string_view(head, sizeof head) == kHdf5Signature;
}

/// The size of the regular file `path`; throws InputError when it is missing, not a file, or empty.
std::uintmax_t existing_file_size(const std::string& path) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status))
    throw InputError(fmt::format("{}: no such file (expected a MATLAB .mat file)", path));
  if (!std::filesystem::is_regular_file(status))
    throw InputError(fmt::format("{}: not a file (expected a MATLAB .mat file)", path));
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) throw InputError(fmt::format("{}: cannot read the file: {}", path, error.message()));
  if (size == 0) throw InputError(fmt::format("{}: empty file (expected a MATLAB .mat file)", path));
  return size;
}

/// Opens `path` for reading; throws InputError saying why it is not a .mat file matio can read.
MatFile open_mat_file(const std::string& path) {
  if (!std::ifstream(path, std::ios::binary))
    throw InputError(fmt::format("{}: cannot open the file for reading: {}", path, std::strerror(errno)));
  MatFile file(Mat_Open(path.c_str(), MAT_ACC_RDONLY));
  if (file) return file;
  if (starts_as_hdf5(path))
    throw InputError(fmt::format("{}: an HDF5 file but not a MATLAB v7.3 .mat file (expected MATLAB's 512-byte "
                                 "header before the HDF5 data, as `save -v7.3` writes)", path));
  throw InputError(fmt::format("{}: not a MATLAB .mat file (matio could not open it as v4, v5 or v7.3)", path));
}

std::string listed_or_nothing(const std::vector<std::string>& entries) {
  return entries.empty() ? std::string("no variables") : fmt::format("{}", fmt::join(entries, ", "));
}

/// Adds `name` to `table`: the channel when there is one, "name (why not)" in `skipped` otherwise.
void add_entry(ChannelTable& table, std::string name, const std::optional<std::string>& why_not,
               std::optional<Channel> channel) {
  if (why_not || !channel) {
    table.skipped.push_back(fmt::format("{} ({})", name, why_not.value_or("unreadable")));
    return;
  }
  table.names.push_back(name);
  table.channels.emplace(std::move(name), std::move(*channel));
}

/// The number of elements of `variable`, the product of its dimensions; nullopt when it has none or the product
/// overflows (a damaged header).
std::optional<std::size_t> element_count(const matvar_t& variable) {
  if (variable.rank <= 0 || variable.dims == nullptr) return std::nullopt;
  std::size_t count = 1;
  for (int d = 0; d < variable.rank; ++d)
    if (__builtin_mul_overflow(count, variable.dims[d], &count)) return std::nullopt;
  return count;
}

/// True when matio holds a field pointer for each of the `elements` × `fields` slots of the struct `variable` and
/// a name for each field: Mat_VarGetStructFieldByIndex checks neither, and a damaged header leaves them short.
bool holds_all_fields(const matvar_t& variable, std::size_t elements, std::size_t fields) {
  std::size_t slots = 0;
  if (__builtin_mul_overflow(elements, fields, &slots)) return false;
  if (variable.data == nullptr || variable.data_size != static_cast<int>(sizeof(matvar_t*)) ||
      variable.nbytes / sizeof(matvar_t*) < slots)
    return false;
  char* const* names = Mat_VarGetStructFieldnames(&variable);
  return names != nullptr && std::all_of(names, names + fields, [](const char* name) { return name != nullptr; });
}

/// The channel name of field `field` of element `element` (0-based, in MATLAB's linear order) of the struct
/// `name` that has `elements` elements: "name.field" for a single struct, "name(k).field" for a struct array, k
/// being MATLAB's 1-based linear index (the same for a 1 × K, a K × 1 or any other shape).
std::string struct_field_name(std::string_view name, std::size_t element, std::size_t elements,
                              std::string_view field) {
  if (elements == 1) return fmt::format("{}.{}", name, field);
  return fmt::format("{}({}).{}", name, element + 1, field);
}

/// Why a struct field (its header) is not a channel: why_not_a_channel, except that a field without class or rank
/// is "empty": a v5 file may store an unset field ([]) as an element of no bytes, which matio lists so.
std::optional<std::string> why_field_not_a_channel(const matvar_t& field) {
  if (field.class_type == MAT_C_EMPTY && field.rank == 0) return "empty";
  return why_not_a_channel(field);
}

/// Frees the data matio read into `field` once its values are copied, so that a struct array of long records
/// holds one field's buffer at a time beside its channels rather than all of them until the struct is freed.
void release_field_data(matvar_t& field) {
  if (field.mem_conserve || field.isComplex) return;
  std::free(field.data);
  field.data = nullptr;
}

/// Adds the fields of the struct `variable`, the `index`-th variable of the file, to `table`: element by element in
/// MATLAB's linear order and, in each, field by field in the struct's order; a real numeric 2-D field is a channel
/// named as struct_field_name says, any other field is "that name (why not)" in `skipped`. Fields of a struct in a
/// field are not followed: that field is skipped as "(struct)". A struct without elements, without fields or
/// without a numeric field anywhere is one entry, "name (struct with no numeric field)".
void add_struct(mat_t& file, matvar_t& variable, std::size_t index, const FileLimits& limits, ChannelTable& table) {
  const std::string name = variable.name;
  const std::size_t fields = Mat_VarGetNumberOfFields(&variable);
  const std::optional<std::size_t> elements = element_count(variable);
  if (!elements) {
    add_entry(table, name, "unreadable", std::nullopt);
    return;
  }
  if (*elements == 0 || fields == 0) {
    add_entry(table, name, "struct with no numeric field", std::nullopt);
    return;
  }
  // A cut v5 struct is unreadable as a whole: the field headers matio listed may come from the cut part.
  if (!holds_all_fields(variable, *elements, fields) || !v5_variable_intact(index, limits)) {
    add_entry(table, name, "unreadable", std::nullopt);
    return;
  }
  char* const* field_names = Mat_VarGetStructFieldnames(&variable);
  struct Entry {
    std::string name;
    matvar_t* field;
    std::optional<std::string> why_not;
  };
  std::vector<Entry> entries;
  bool any_candidate = false;  // a numeric field, or one matio could not list that may have been one
  for (std::size_t element = 0; element < *elements; ++element) {
    for (std::size_t f = 0; f < fields; ++f) {
      matvar_t* field = Mat_VarGetStructFieldByIndex(&variable, f, element);
      std::optional<std::string> why_not = field != nullptr ? why_field_not_a_channel(*field) : "unreadable";
      any_candidate = any_candidate || field == nullptr || !why_not;
      entries.push_back({struct_field_name(name, element, *elements, field_names[f]), field, std::move(why_not)});
    }
  }
  if (!any_candidate) {
    add_entry(table, name, "struct with no numeric field", std::nullopt);
    return;
  }
  for (Entry& entry : entries) {
    if (!entry.why_not && table.channels.contains(entry.name)) entry.why_not = "named twice";
    std::optional<Channel> channel;
    if (!entry.why_not) {
      channel = read_matrix(file, *entry.field, limits);
      release_field_data(*entry.field);
    }
    add_entry(table, std::move(entry.name), entry.why_not, std::move(channel));
  }
}

/// Adds the `index`-th variable of the file to `table`: a channel when it is a numeric matrix matio reads, its
/// fields when it is a struct, "name (why not)" in `skipped` otherwise.
void add_variable(mat_t& file, matvar_t& variable, std::size_t index, const FileLimits& limits, ChannelTable& table) {
  if (variable.class_type == MAT_C_STRUCT) {
    add_struct(file, variable, index, limits, table);
    return;
  }
  const std::string name = variable.name;
  std::optional<std::string> why_not = why_not_a_channel(variable);
  if (!why_not && table.channels.contains(name)) why_not = "named twice";
  std::optional<Channel> channel;
  if (!why_not && v5_variable_intact(index, limits)) channel = read_matrix(file, variable, limits);
  add_entry(table, name, why_not, std::move(channel));
}

/// Adds every variable of an open file to `table`. Headers come one after the other, data only for the numeric
/// matrices and the numeric fields of structs: a cell's data is never read. Of a compressed v5 variable matio
/// inflates only the start, except of a struct or a cell: to list their fields it inflates all of it, and keeps the
/// data of each field or cell smaller than its inflate window (32 KiB).
void add_variables(mat_t& file, const FileLimits& limits, ChannelTable& table) {
  std::size_t index = 0;
  for (;; ++index) {
    // A header whose sizes its bytes cannot back would have matio allocate them (gigabytes for a damaged file of
    // a few hundred bytes): it is not handed to matio, and listing stops there as at a header matio cannot read.
    V5Verdict verdict = V5Verdict::listable;
    if (limits.v5 && index < limits.v5->size())
      verdict = scan_v5_element(limits.path, (*limits.v5)[index], limits.bytes);
    if (verdict == V5Verdict::unsafe) break;
    const MatVar variable{Mat_VarReadNextInfo(&file)};
    if (!variable) break;
    // MATLAB keeps the class data of the objects in a file in an unnamed uint8 variable (its "subsystem").
    if (variable->name == nullptr || variable->name[0] == '\0') continue;
    if (verdict == V5Verdict::unreadable) {
      add_entry(table, variable->name, "unreadable", std::nullopt);
      continue;
    }
    add_variable(file, *variable, index, limits, table);
  }
  // matio stops at the first variable whose header it cannot read; the v5 elements after it are named by count.
  if (limits.v5 && index < limits.v5->size()) {
    const std::size_t unlisted = limits.v5->size() - index;
    table.skipped.push_back(fmt::format("{} unlisted variable{} (unreadable)", unlisted, unlisted > 1 ? "s" : ""));
  }
}

}  // namespace

bool is_mat_path(const std::string& path) {
  return lowercase(std::filesystem::path(path).extension().string()) == ".mat";
}

ChannelTable read_mat_file(const std::string& path) {
  FileLimits limits;
  limits.path = path;
  limits.bytes = existing_file_size(path);
  ChannelTable table;
  table.source = path;
  bool matio_complained = false;
  {
    const auto lock = lock_matio();
    const MatFile file = open_mat_file(path);
    if (Mat_GetVersion(file.get()) == MAT_FT_MAT5) limits.v5 = v5_elements(path, limits.bytes);
    add_variables(*file, limits, table);
    matio_complained = matio_message_count() > 0;
  }
  if (table.names.empty() && table.skipped.empty() && matio_complained)
    throw InputError(fmt::format("{}: a damaged .mat file: matio reported errors and found no variable in it", path));
  if (table.names.empty())
    throw InputError(
        fmt::format("{}: no numeric matrix in the file (found: {})", path, listed_or_nothing(table.skipped)));
  return table;
}

// ---- writing ------------------------------------------------------------------------------------------------

namespace {

bool is_matlab_name(std::string_view name) {
  const auto is_letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
  const auto is_digit = [](char c) { return c >= '0' && c <= '9'; };
  if (name.empty() || name.size() > kMaxMatlabNameLength || !is_letter(name.front())) return false;
  for (char c : name)
    if (!is_letter(c) && !is_digit(c) && c != '_') return false;
  return true;
}

/// Throws InputError for a name MATLAB could not load and for a name given twice, before any file exists.
void check_column_names(const std::string& path,
                        const std::vector<std::pair<std::string, std::vector<double>>>& columns) {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    const std::string& name = columns[i].first;
    if (!is_matlab_name(name))
      throw InputError(fmt::format("cannot write {}: '{}' is not a MATLAB variable name (expected a letter, then "
                                   "letters, digits or '_', at most {} characters)", path, name, kMaxMatlabNameLength));
    for (std::size_t j = 0; j < i; ++j)
      if (columns[j].first == name)
        throw InputError(fmt::format("cannot write {}: column '{}' given twice", path, name));
  }
}

/// Writes `values` as the N × 1 double variable `name`; false when matio fails.
bool write_column(mat_t& file, const std::string& name, const std::vector<double>& values) {
  std::size_t dims[2] = {values.size(), 1};
  // MAT_F_DONT_COPY_DATA: matio reads the caller's buffer while writing and never writes to it or frees it.
  const MatVar variable{Mat_VarCreate(name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims,
                                      const_cast<double*>(values.data()), MAT_F_DONT_COPY_DATA)};
  return variable && Mat_VarWrite(&file, variable.get(), MAT_COMPRESSION_ZLIB) == MATIO_E_NO_ERROR;
}

/// Removes what a failed write left at `path` (a regular file only: a device such as /dev/full stays) and throws
/// InputError "cannot write PATH: what".
[[noreturn]] void fail_written_file(const std::string& path, const std::string& what) {
  std::error_code ignored;
  if (std::filesystem::is_regular_file(path, ignored)) std::filesystem::remove(path, ignored);
  throw InputError(fmt::format("cannot write {}: {}", path, what));
}

/// True when the v5 file at `path` holds `variables` intact elements. matio's v5 writer does not check its writes:
/// a full disk leaves a cut zlib stream and no error, so the written file is read back element by element. A device
/// or a pipe cannot be read back, and passes.
bool v5_file_complete(const std::string& path, std::size_t variables) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return true;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error || size < 128) return false;  // not even the file's header
  const std::vector<V5Element> elements = v5_elements(path, size);
  return elements.size() == variables && std::all_of(elements.begin(), elements.end(), [&](const V5Element& e) {
           return v5_element_intact(path, e, size);
         });
}

/// Creates (or truncates) `path` as an empty .mat file of `version`; throws InputError when matio cannot.
MatFile create_mat_file(const std::string& path, MatVersion version) {
  const bool v73 = version == MatVersion::v73;
  errno = 0;
  MatFile file(Mat_CreateVer(path.c_str(), v73 ? kV73Header : kV5Header, v73 ? MAT_FT_MAT73 : MAT_FT_MAT5));
  if (!file) {
    const std::string reason = errno != 0 ? fmt::format(": {}", std::strerror(errno)) : std::string();
    throw InputError(fmt::format("cannot write {}: matio could not create the file{}", path, reason));
  }
  return file;
}

}  // namespace

void write_mat_file(const std::string& path, const std::vector<std::pair<std::string, std::vector<double>>>& columns,
                    MatVersion version) {
  check_column_names(path, columns);
  const auto lock = lock_matio();
  MatFile file = create_mat_file(path, version);
  for (const auto& [name, values] : columns) {
    if (!write_column(*file, name, values)) {
      file.reset();
      fail_written_file(path, fmt::format("matio could not write variable '{}'", name));
    }
  }
  if (Mat_Close(file.release()) != MATIO_E_NO_ERROR) fail_written_file(path, "matio could not finish the file");
  if (version == MatVersion::v5 && !v5_file_complete(path, columns.size()))
    fail_written_file(path, "the file on disk is incomplete (is the disk full?)");
}

}  // namespace dampbench
