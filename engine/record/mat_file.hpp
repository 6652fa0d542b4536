#pragma once
// MATLAB .mat files: a file's numeric matrices and the numeric fields of its structs read as a channel table, and
// columns written as a .mat file.
// Debian's libmatio does the format work because it reads every version MATLAB writes: v4, v5 (compressed or
// not) and v7.3 (HDF5, `save -v7.3`), so a record saved by any MATLAB release loads the same way. matio.h stays
// out of this header: only mat_file.cpp and what links it see the library. Calls into matio are serialized (matio
// and Debian's HDF5 are not thread-safe), so both functions may be called from any thread.
#include <string>
#include <utility>
#include <vector>

#include "engine/record/channel_table.hpp"

namespace dampbench {

/// True when `path` names a MATLAB file: its extension is .mat, in any case. `--data` and `simulate -o` read and
/// write such a path as a .mat file, any other as text.
bool is_mat_path(const std::string& path);

/// Reads every variable of `path` that is a real numeric 2-D matrix (double, single, int8 ... uint64, logical) as
/// a channel of doubles under its variable name, column-major; `names` lists them in the file's order (a v7.3 file
/// lists its variables by name: HDF5 keeps no order of creation for them). A struct gives its fields that are such
/// matrices, in the struct's field order, as channels "s.field"; a struct array of several elements (any shape,
/// e.g. one element per test) gives "s(k).field" with MATLAB's 1-based linear index k, element by element and field
/// by field in each (an array of one element is a struct: "s.field").
/// Its channels come in `names` where the struct stands among the variables. Fields are followed one level only.
/// Other variables go to `skipped` as "name (why)", and other fields as "s.field (why)" or "s(k).field (why)":
/// char, cell, struct (a struct in a field), sparse, complex, object, function handle, 3-D (any rank above 2),
/// empty, no MATLAB class (an HDF5 dataset without MATLAB's class attribute, or with one matio cannot read),
/// unreadable (a damaged or truncated variable or field; a damaged v5 struct is one entry "s (unreadable)"); a
/// struct without elements, fields or any numeric field is one entry "s (struct with no numeric field)". The
/// variables of a damaged v5 file that matio cannot even list are counted as "N unlisted variables (unreadable)".
/// int64 and uint64 values beyond 2^53 round to the nearest double. Throws InputError naming the path: a missing,
/// empty or unreadable file, a file that is not a .mat file (an HDF5 file without MATLAB's header among them), a
/// damaged v7.3 file HDF5 cannot open, a file without any numeric matrix (listing what it has).
ChannelTable read_mat_file(const std::string& path);

/// The .mat versions write_mat_file writes: v5 (MATLAB's `save -v7`, zlib-compressed) and v7.3 (HDF5, deflated).
/// v5 is the default: after a failed v7.3 write (a full disk) matio leaves HDF5 objects open, and Debian's HDF5 can
/// crash while it closes them at the exit of the process.
enum class MatVersion { v5, v73 };

/// Writes each column as an N × 1 double variable of that name, in the given order. Names must be MATLAB variable
/// names (a letter, then letters, digits or '_'; at most 63 characters) and distinct. Throws InputError "cannot
/// write PATH: ..." before creating the file for a bad name, and when matio cannot create or write the file or the
/// file read back is incomplete (a full disk); the partial file is removed. The same columns give the same bytes
/// in a v5 file (the header holds no time).
void write_mat_file(const std::string& path, const std::vector<std::pair<std::string, std::vector<double>>>& columns,
                    MatVersion version = MatVersion::v5);

}  // namespace dampbench
