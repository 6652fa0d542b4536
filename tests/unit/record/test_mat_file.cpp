// Tests for engine/record/mat_file: columns written and read back bit for bit (v5 and v7.3), matrices of several
// classes, structs and struct arrays, and the variables and fields that are not channels (written here with matio
// itself, as v4, v5 and v7.3 files), damaged files, and the messages for files that are missing, not .mat files, or
// cannot be written.
#include "engine/record/mat_file.hpp"

#include <matio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <zlib.h>

#include "engine/common/error.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

using testing::error_of;
using testing::HasText;
using testing::test_temp_dir;
using MatColumns = std::vector<std::pair<std::string, std::vector<double>>>;

/// Doubles whose bits a conversion on the way would change: a third, the edges of the exponent range, a negative
/// zero, the smallest denormal, an infinity and a NaN.
std::vector<double> awkward_doubles() {
  return {1.0 / 3.0, 1e-300, -0.0, 1e300, 5e-324, -std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::quiet_NaN(), -2.5, 0.1};
}

bool same_double_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void expect_round_trip_bit_exact(MatVersion version) {
  const auto path = (test_temp_dir("mat_file") / "columns.mat").string();
  std::vector<double> t(9);
  for (std::size_t i = 0; i < t.size(); ++i) t[i] = 0.001 * static_cast<double>(i);
  write_mat_file(path, {{"t", t}, {"F", awkward_doubles()}}, version);

  const ChannelTable table = read_mat_file(path);
  EXPECT_EQ(table.source, path);
  // v5 keeps the order of writing; a v7.3 file lists its variables by name (HDF5 keeps no creation order).
  EXPECT_EQ(table.names, (version == MatVersion::v5 ? std::vector<std::string>{"t", "F"}
                                                    : std::vector<std::string>{"F", "t"}));
  EXPECT_TRUE(table.skipped.empty());
  const Channel& F = table.channels.at("F");
  EXPECT_EQ(F.rows, awkward_doubles().size());
  EXPECT_EQ(F.cols, 1u);
  EXPECT_TRUE(same_double_bits(F.values, awkward_doubles()));
  EXPECT_TRUE(same_double_bits(table.channels.at("t").values, t));
}

TEST(MatFile, V5RoundTripIsBitExact) { expect_round_trip_bit_exact(MatVersion::v5); }

TEST(MatFile, V73RoundTripIsBitExact) { expect_round_trip_bit_exact(MatVersion::v73); }

TEST(MatFile, WrittenFilesAreCompressedAndV5FilesReproducible) {
  const auto dir = test_temp_dir("mat_file");
  const MatColumns zeros = {{"x", std::vector<double>(10000, 0.0)}};
  write_mat_file((dir / "a.mat").string(), zeros);
  write_mat_file((dir / "b.mat").string(), zeros);
  write_mat_file((dir / "c.mat").string(), zeros, MatVersion::v73);
  EXPECT_LT(std::filesystem::file_size(dir / "a.mat"), 1000u);  // 80 000 bytes of data
  EXPECT_LT(std::filesystem::file_size(dir / "c.mat"), 20000u);
  EXPECT_EQ(file_bytes(dir / "a.mat"), file_bytes(dir / "b.mat"));  // no time of writing in the header
}

// ---- variables of other classes, written with matio itself ------------------------------------------------

struct MatioFileCloser {
  void operator()(mat_t* file) const { Mat_Close(file); }
};

/// Writes `variable` (then frees it) into `file`.
void put_variable(mat_t* file, matvar_t* variable, matio_compression compression) {
  ASSERT_NE(variable, nullptr);
  EXPECT_EQ(Mat_VarWrite(file, variable, compression), MATIO_E_NO_ERROR) << variable->name;
  Mat_VarFree(variable);
}

matvar_t* double_matrix(const char* name, std::vector<std::size_t> dims, std::vector<double> values) {
  return Mat_VarCreate(name, MAT_C_DOUBLE, MAT_T_DOUBLE, static_cast<int>(dims.size()), dims.data(), values.data(), 0);
}

matvar_t* char_variable(const char* name, std::string text) {
  std::size_t dims[2] = {1, text.size()};
  return Mat_VarCreate(name, MAT_C_CHAR, MAT_T_UTF8, 2, dims, text.data(), 0);
}

/// A struct (array) `name` of the given dimensions and fields, each field unset until set_field.
matvar_t* struct_variable(const char* name, std::vector<std::size_t> dims, std::vector<const char*> fields) {
  fields.push_back(nullptr);
  return Mat_VarCreateStruct2(name, static_cast<int>(dims.size()), dims.data(), fields.data());
}

/// Sets field `field` of element `index` (0-based, linear) of the struct `s` to `value`, which `s` then owns.
void set_field(matvar_t* s, const char* field, std::size_t index, matvar_t* value) {
  ASSERT_NE(s, nullptr);
  ASSERT_NE(value, nullptr);
  EXPECT_EQ(Mat_VarSetStructFieldByName(s, field, index, value), nullptr) << field;  // the field was unset
}

/// A 1 × 1 struct s with the field gain = 2.5.
matvar_t* struct_with_gain() {
  matvar_t* s = struct_variable("s", {1, 1}, {"gain"});
  set_field(s, "gain", 0, double_matrix("gain", {1, 1}, {2.5}));
  return s;
}

/// A file with, in this order: A (3 × 4 double, A(r, c) = 1 + r + 3c), label (char), v (1 × 5 int16), s (a struct
/// with gain = 2.5), z (complex), cube (2 × 2 × 2), flag (1 × 3 logical), f32 (2 × 1 single).
void write_mixed_file(const std::string& path, mat_ft version, matio_compression compression) {
  const std::unique_ptr<mat_t, MatioFileCloser> file(Mat_CreateVer(path.c_str(), nullptr, version));
  ASSERT_NE(file, nullptr);
  std::vector<double> a(12);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = 1.0 + static_cast<double>(i);
  put_variable(file.get(), double_matrix("A", {3, 4}, a), compression);
  put_variable(file.get(), char_variable("label", "damper"), compression);
  std::int16_t v[5] = {-32768, -1, 0, 1, 32767};
  std::size_t row5[2] = {1, 5};
  put_variable(file.get(), Mat_VarCreate("v", MAT_C_INT16, MAT_T_INT16, 2, row5, v, 0), compression);
  put_variable(file.get(), struct_with_gain(), compression);
  double re[2] = {1, 2}, im[2] = {3, 4};
  mat_complex_split_t z = {re, im};
  std::size_t col2[2] = {2, 1};
  put_variable(file.get(), Mat_VarCreate("z", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, col2, &z, MAT_F_COMPLEX), compression);
  put_variable(file.get(), double_matrix("cube", {2, 2, 2}, std::vector<double>(8, 1.0)), compression);
  std::uint8_t flag[3] = {1, 0, 1};
  std::size_t row3[2] = {1, 3};
  put_variable(file.get(), Mat_VarCreate("flag", MAT_C_UINT8, MAT_T_UINT8, 2, row3, flag, MAT_F_LOGICAL), compression);
  float f32[2] = {0.1f, -3.5f};
  put_variable(file.get(), Mat_VarCreate("f32", MAT_C_SINGLE, MAT_T_SINGLE, 2, col2, f32, 0), compression);
}

void expect_mixed_file_read(mat_ft version, matio_compression compression) {
  const auto path = (test_temp_dir("mat_file") / "mixed.mat").string();
  write_mixed_file(path, version, compression);
  const ChannelTable table = read_mat_file(path);

  // v5 keeps the order of writing; a v7.3 file lists its variables by name.
  const std::vector<std::string> expected = version == MAT_FT_MAT73
                                                ? std::vector<std::string>{"A", "f32", "flag", "s.gain", "v"}
                                                : std::vector<std::string>{"A", "v", "s.gain", "flag", "f32"};
  EXPECT_EQ(table.names, expected);
  const std::vector<std::string> skipped_expected = {"label (char)", "z (complex)", "cube (3-D)"};
  for (const auto& entry : skipped_expected)
    EXPECT_NE(std::find(table.skipped.begin(), table.skipped.end(), entry), table.skipped.end()) << entry;
  EXPECT_EQ(table.skipped.size(), skipped_expected.size());

  const Channel& A = table.channels.at("A");
  ASSERT_EQ(A.rows, 3u);
  ASSERT_EQ(A.cols, 4u);
  for (std::size_t i = 0; i < A.values.size(); ++i) EXPECT_EQ(A.values[i], 1.0 + static_cast<double>(i));
  EXPECT_EQ(A.at(2, 0), 3.0);
  EXPECT_EQ(A.at(0, 1), 4.0);
  EXPECT_EQ(A.at(2, 3), 12.0);

  const Channel& v = table.channels.at("v");
  EXPECT_EQ(v.rows, 1u);
  EXPECT_EQ(v.cols, 5u);
  EXPECT_EQ(v.values, (std::vector<double>{-32768, -1, 0, 1, 32767}));
  EXPECT_EQ(table.channels.at("flag").values, (std::vector<double>{1, 0, 1}));
  EXPECT_EQ(table.channels.at("f32").values, (std::vector<double>{0.1f, -3.5f}));
  EXPECT_EQ(table.channels.at("s.gain").values, std::vector<double>{2.5});
}

TEST(MatFile, V5MatricesOfEachKindAndSkippedVariables) { expect_mixed_file_read(MAT_FT_MAT5, MAT_COMPRESSION_NONE); }

TEST(MatFile, V5CompressedMatricesOfEachKindAndSkippedVariables) {
  expect_mixed_file_read(MAT_FT_MAT5, MAT_COMPRESSION_ZLIB);
}

TEST(MatFile, V73MatricesOfEachKindAndSkippedVariables) { expect_mixed_file_read(MAT_FT_MAT73, MAT_COMPRESSION_ZLIB); }

TEST(MatFile, V4Matrix) {
  const auto path = (test_temp_dir("mat_file") / "old.mat").string();
  {
    const std::unique_ptr<mat_t, MatioFileCloser> file(Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT4));
    ASSERT_NE(file, nullptr);
    put_variable(file.get(), double_matrix("B", {2, 3}, {1, 2, 3, 4, 5, 6}), MAT_COMPRESSION_NONE);
  }
  const ChannelTable table = read_mat_file(path);
  ASSERT_EQ(table.names, std::vector<std::string>{"B"});
  EXPECT_EQ(table.channels.at("B").rows, 2u);
  EXPECT_EQ(table.channels.at("B").at(1, 2), 6.0);
}

// ---- structs and struct arrays ---------------------------------------------------------------------------

/// tests(k).x (k from 1): 3 + k of awkward_doubles(), from the k-th on, as a column.
std::vector<double> test_x(std::size_t k) {
  const std::vector<double> awkward = awkward_doubles();
  std::vector<double> x(3 + k);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = awkward[(i + k) % awkward.size()];
  return x;
}

/// tests(k).F (k from 1): k + 1 int16 from -32768 to 32767, as a row.
std::vector<std::int16_t> test_F(std::size_t k) {
  std::vector<std::int16_t> F(k + 1);
  for (std::size_t i = 0; i < F.size(); ++i) F[i] = static_cast<std::int16_t>(100 * k + i);
  F.front() = -32768;
  F.back() = 32767;
  return F;
}

/// rig.t: the first 5 of awkward_doubles(); rig.x: the last 5.
std::vector<double> rig_t() {
  const std::vector<double> awkward = awkward_doubles();
  return {awkward.begin(), awkward.begin() + 5};
}
std::vector<double> rig_x() {
  const std::vector<double> awkward = awkward_doubles();
  return {awkward.end() - 5, awkward.end()};
}

/// A file with, in this order: rig (a struct: t 5 × 1 double, x 1 × 5 double, label char), gain (1 × 1 double),
/// tests (a 1 × 3 struct array: x test_x(k), F test_F(k), note char).
void write_struct_file(const std::string& path, mat_ft version, matio_compression compression) {
  const std::unique_ptr<mat_t, MatioFileCloser> file(Mat_CreateVer(path.c_str(), nullptr, version));
  ASSERT_NE(file, nullptr);
  matvar_t* rig = struct_variable("rig", {1, 1}, {"t", "x", "label"});
  set_field(rig, "t", 0, double_matrix("t", {5, 1}, rig_t()));
  set_field(rig, "x", 0, double_matrix("x", {1, 5}, rig_x()));
  set_field(rig, "label", 0, char_variable("label", "damper 7"));
  put_variable(file.get(), rig, compression);
  put_variable(file.get(), double_matrix("gain", {1, 1}, {2.5}), compression);
  matvar_t* tests = struct_variable("tests", {1, 3}, {"x", "F", "note"});
  const char* notes[] = {"first", "second", "third"};
  for (std::size_t k = 1; k <= 3; ++k) {
    set_field(tests, "x", k - 1, double_matrix("x", {3 + k, 1}, test_x(k)));
    std::vector<std::int16_t> F = test_F(k);
    std::size_t row[2] = {1, F.size()};
    set_field(tests, "F", k - 1, Mat_VarCreate("F", MAT_C_INT16, MAT_T_INT16, 2, row, F.data(), 0));
    set_field(tests, "note", k - 1, char_variable("note", notes[k - 1]));
  }
  put_variable(file.get(), tests, compression);
}

void expect_struct_file_read(mat_ft version, matio_compression compression) {
  const auto path = (test_temp_dir("mat_file") / "structs.mat").string();
  write_struct_file(path, version, compression);
  const ChannelTable table = read_mat_file(path);

  // A struct's channels stand where the struct stands: v5 keeps the order of writing, a v7.3 file lists its
  // variables by name; fields keep the struct's order in both.
  std::vector<std::string> expected = {"rig.t", "rig.x"};
  expected.insert(version == MAT_FT_MAT73 ? expected.begin() : expected.end(), "gain");
  for (const char* name : {"tests(1).x", "tests(1).F", "tests(2).x", "tests(2).F", "tests(3).x", "tests(3).F"})
    expected.emplace_back(name);
  EXPECT_EQ(table.names, expected);
  EXPECT_EQ(table.skipped, (std::vector<std::string>{"rig.label (char)", "tests(1).note (char)",
                                                     "tests(2).note (char)", "tests(3).note (char)"}));

  const Channel& t = table.channels.at("rig.t");
  EXPECT_EQ(t.rows, 5u);
  EXPECT_EQ(t.cols, 1u);
  EXPECT_TRUE(same_double_bits(t.values, rig_t()));
  const Channel& x = table.channels.at("rig.x");
  EXPECT_EQ(x.rows, 1u);
  EXPECT_EQ(x.cols, 5u);
  EXPECT_TRUE(same_double_bits(x.values, rig_x()));
  EXPECT_EQ(table.channels.at("gain").values, std::vector<double>{2.5});
  for (std::size_t k = 1; k <= 3; ++k) {
    const Channel& test_x_k = table.channels.at(fmt::format("tests({}).x", k));
    EXPECT_EQ(test_x_k.rows, 3 + k) << k;
    EXPECT_EQ(test_x_k.cols, 1u) << k;
    EXPECT_TRUE(same_double_bits(test_x_k.values, test_x(k))) << k;
    const Channel& test_F_k = table.channels.at(fmt::format("tests({}).F", k));
    EXPECT_EQ(test_F_k.rows, 1u) << k;
    EXPECT_EQ(test_F_k.cols, k + 1) << k;
    const std::vector<std::int16_t> F = test_F(k);
    EXPECT_EQ(test_F_k.values, std::vector<double>(F.begin(), F.end())) << k;
  }
}

TEST(MatFile, V5StructFieldsAndStructArraysAreChannels) { expect_struct_file_read(MAT_FT_MAT5, MAT_COMPRESSION_NONE); }

TEST(MatFile, V5CompressedStructFieldsAndStructArraysAreChannels) {
  expect_struct_file_read(MAT_FT_MAT5, MAT_COMPRESSION_ZLIB);
}

TEST(MatFile, V73StructFieldsAndStructArraysAreChannels) {
  expect_struct_file_read(MAT_FT_MAT73, MAT_COMPRESSION_ZLIB);
}

/// 6000 doubles (48 000 bytes, more than the 32 KiB below which matio reads a compressed field with its struct).
std::vector<double> long_record() {
  std::vector<double> y(6000);
  for (std::size_t i = 0; i < y.size(); ++i) y[i] = std::sin(1e3 * static_cast<double>(i));
  return y;
}

/// A file with, in this order: meta (a struct whose fields are none of them a numeric matrix), runs (a 2 × 1
/// struct array: y long_record() then an empty matrix, inner a struct, n an int32), none (a 0 × 0 struct array
/// with a field), bare (a struct without fields).
void write_struct_fields_file(const std::string& path, mat_ft version, matio_compression compression) {
  const std::unique_ptr<mat_t, MatioFileCloser> file(Mat_CreateVer(path.c_str(), nullptr, version));
  ASSERT_NE(file, nullptr);
  const auto inner_struct = [] {
    matvar_t* inner = struct_variable("inner", {1, 1}, {"a"});
    set_field(inner, "a", 0, double_matrix("a", {1, 1}, {1.0}));
    return inner;
  };

  matvar_t* meta = struct_variable("meta", {1, 1}, {"inner", "parts", "z", "cube", "none"});
  set_field(meta, "inner", 0, inner_struct());
  std::size_t row2[2] = {1, 2};
  matvar_t* parts = Mat_VarCreate("parts", MAT_C_CELL, MAT_T_CELL, 2, row2, nullptr, 0);
  Mat_VarSetCell(parts, 0, double_matrix("", {1, 1}, {3.0}));
  Mat_VarSetCell(parts, 1, char_variable("", "text"));
  set_field(meta, "parts", 0, parts);
  double re[2] = {1, 2}, im[2] = {3, 4};
  mat_complex_split_t z = {re, im};
  std::size_t col2[2] = {2, 1};
  set_field(meta, "z", 0, Mat_VarCreate("z", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, col2, &z, MAT_F_COMPLEX));
  set_field(meta, "cube", 0, double_matrix("cube", {2, 2, 2}, std::vector<double>(8, 1.0)));
  put_variable(file.get(), meta, compression);  // meta.none stays unset: matio writes it as []

  matvar_t* runs = struct_variable("runs", {2, 1}, {"y", "inner", "n"});
  set_field(runs, "y", 0, double_matrix("y", {long_record().size(), 1}, long_record()));
  std::size_t none[2] = {0, 0};
  set_field(runs, "y", 1, Mat_VarCreate("y", MAT_C_EMPTY, MAT_T_DOUBLE, 2, none, nullptr, 0));
  for (std::size_t k = 0; k < 2; ++k) {
    set_field(runs, "inner", k, inner_struct());
    std::int32_t n = static_cast<std::int32_t>(k) - 7;
    std::size_t one[2] = {1, 1};
    set_field(runs, "n", k, Mat_VarCreate("n", MAT_C_INT32, MAT_T_INT32, 2, one, &n, 0));
  }
  put_variable(file.get(), runs, compression);

  put_variable(file.get(), struct_variable("none", {0, 0}, {"a"}), compression);
  put_variable(file.get(), struct_variable("bare", {1, 1}, {}), compression);
}

void expect_struct_fields_read(mat_ft version, matio_compression compression) {
  const auto path = (test_temp_dir("mat_file") / "struct_fields.mat").string();
  write_struct_fields_file(path, version, compression);
  const ChannelTable table = read_mat_file(path);

  EXPECT_EQ(table.names, (std::vector<std::string>{"runs(1).y", "runs(1).n", "runs(2).n"}));
  std::vector<std::string> skipped = table.skipped;
  std::sort(skipped.begin(), skipped.end());  // a v7.3 file lists its variables by name
  EXPECT_EQ(skipped, (std::vector<std::string>{"bare (struct with no numeric field)",
                                               "meta (struct with no numeric field)",
                                               "none (struct with no numeric field)", "runs(1).inner (struct)",
                                               "runs(2).inner (struct)", "runs(2).y (empty)"}));
  if (version != MAT_FT_MAT73) {
    EXPECT_EQ(table.skipped, (std::vector<std::string>{"meta (struct with no numeric field)", "runs(1).inner (struct)",
                                                       "runs(2).y (empty)", "runs(2).inner (struct)",
                                                       "none (struct with no numeric field)",
                                                       "bare (struct with no numeric field)"}));
  }
  const Channel& y = table.channels.at("runs(1).y");
  EXPECT_EQ(y.rows, long_record().size());
  EXPECT_EQ(y.cols, 1u);
  EXPECT_TRUE(same_double_bits(y.values, long_record()));
  EXPECT_EQ(table.channels.at("runs(1).n").values, std::vector<double>{-7});
  EXPECT_EQ(table.channels.at("runs(2).n").values, std::vector<double>{-6});
}

TEST(MatFile, V5StructFieldsThatAreNotChannels) { expect_struct_fields_read(MAT_FT_MAT5, MAT_COMPRESSION_NONE); }

TEST(MatFile, V5CompressedStructFieldsThatAreNotChannels) {
  expect_struct_fields_read(MAT_FT_MAT5, MAT_COMPRESSION_ZLIB);
}

TEST(MatFile, V73StructFieldsThatAreNotChannels) { expect_struct_fields_read(MAT_FT_MAT73, MAT_COMPRESSION_ZLIB); }

// ---- damaged files and messages ---------------------------------------------------------------------------

TEST(MatFile, TruncatedVariableIsSkippedAsUnreadable) {
  for (const matio_compression compression : {MAT_COMPRESSION_NONE, MAT_COMPRESSION_ZLIB}) {
    const auto path = (test_temp_dir("mat_file") / "cut.mat").string();
    {
      const std::unique_ptr<mat_t, MatioFileCloser> file(Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT5));
      ASSERT_NE(file, nullptr);
      std::vector<double> ramp(1000);
      for (std::size_t i = 0; i < ramp.size(); ++i) ramp[i] = std::sin(static_cast<double>(i));
      put_variable(file.get(), double_matrix("a", {1000, 1}, ramp), compression);
      put_variable(file.get(), double_matrix("b", {1000, 1}, ramp), compression);
    }
    const auto size = std::filesystem::file_size(path);
    std::filesystem::resize_file(path, size - (size - 128) / 4);  // into b's data
    const ChannelTable table = read_mat_file(path);
    EXPECT_EQ(table.names, std::vector<std::string>{"a"}) << compression;
    EXPECT_EQ(table.skipped, std::vector<std::string>{"b (unreadable)"}) << compression;
  }
}

TEST(MatFile, TruncatedStructIsUnreadable) {
  for (const matio_compression compression : {MAT_COMPRESSION_NONE, MAT_COMPRESSION_ZLIB}) {
    const auto path = (test_temp_dir("mat_file") / "cut_struct.mat").string();
    {
      const std::unique_ptr<mat_t, MatioFileCloser> file(Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT5));
      ASSERT_NE(file, nullptr);
      put_variable(file.get(), double_matrix("a", {3, 1}, {1, 2, 3}), compression);
      matvar_t* tests = struct_variable("tests", {1, 3}, {"x", "note"});
      for (std::size_t k = 0; k < 3; ++k) {
        set_field(tests, "x", k, double_matrix("x", {long_record().size(), 1}, long_record()));
        set_field(tests, "note", k, char_variable("note", "run"));
      }
      put_variable(file.get(), tests, compression);
    }
    const auto size = std::filesystem::file_size(path);
    std::filesystem::resize_file(path, size - (size - 128) / 4);  // into the data of tests(3).x
    const ChannelTable table = read_mat_file(path);
    EXPECT_EQ(table.names, std::vector<std::string>{"a"}) << compression;
    EXPECT_EQ(table.skipped, std::vector<std::string>{"tests (unreadable)"}) << compression;
  }
}

/// The byte count in the tag of the top-level element that starts at `offset` of a v5 file.
std::uint32_t element_bytes_at(const std::string& path, std::streamoff offset) {
  std::uint32_t bytes = 0;
  std::ifstream in(path, std::ios::binary);
  in.seekg(offset + 4);
  in.read(reinterpret_cast<char*>(&bytes), sizeof bytes);
  return bytes;
}

TEST(MatFile, CutZlibStreamIsUnreadable) {
  // What a full disk leaves of matio's compressed write: b's tag counts only the bytes that reached the disk, and
  // its zlib stream stops short; matio reads it without an error.
  const auto path = (test_temp_dir("mat_file") / "cut_stream.mat").string();
  std::vector<double> noise(2000);
  for (std::size_t i = 0; i < noise.size(); ++i) noise[i] = std::sin(1e3 * static_cast<double>(i));
  write_mat_file(path, {{"a", noise}, {"b", noise}});
  const std::streamoff b_offset = 128 + 8 + element_bytes_at(path, 128);
  const auto b_bytes = static_cast<std::uint32_t>(element_bytes_at(path, b_offset) / 2);
  std::filesystem::resize_file(path, static_cast<std::uintmax_t>(b_offset) + 8 + b_bytes);
  std::fstream io(path, std::ios::binary | std::ios::in | std::ios::out);
  io.seekp(b_offset + 4);
  io.write(reinterpret_cast<const char*>(&b_bytes), sizeof b_bytes);
  io.close();
  const ChannelTable table = read_mat_file(path);
  EXPECT_EQ(table.names, std::vector<std::string>{"a"});
  EXPECT_EQ(table.skipped, std::vector<std::string>{"b (unreadable)"});
}

TEST(MatFile, VariablesAfterADamagedHeaderAreCounted) {
  const auto path = (test_temp_dir("mat_file") / "cut_header.mat").string();
  {
    const std::unique_ptr<mat_t, MatioFileCloser> file(Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT5));
    ASSERT_NE(file, nullptr);
    put_variable(file.get(), double_matrix("a", {3, 1}, {1, 2, 3}), MAT_COMPRESSION_NONE);
    put_variable(file.get(), double_matrix("b", {3, 1}, {4, 5, 6}), MAT_COMPRESSION_NONE);
  }
  // The file's header is 128 bytes; a's element (an 8-byte tag, then its bytes) follows; b's header is cut 12 bytes
  // into it, before its dimensions.
  std::filesystem::resize_file(path, 128 + 8 + element_bytes_at(path, 128) + 12);
  const ChannelTable table = read_mat_file(path);
  EXPECT_EQ(table.names, std::vector<std::string>{"a"});
  EXPECT_EQ(table.skipped, std::vector<std::string>{"1 unlisted variable (unreadable)"});
}

TEST(MatFile, TruncatedV73FileIsDamaged) {
  const auto path = (test_temp_dir("mat_file") / "cut73.mat").string();
  write_mat_file(path, {{"t", std::vector<double>(1000, 1.0)}}, MatVersion::v73);
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 200);
  EXPECT_TRUE(HasText(error_of([&] { read_mat_file(path); }), path + ": a damaged .mat file"));
}

TEST(MatFile, SizeBeyondTheFileIsUnreadableNotAllocated) {
  const auto path = (test_temp_dir("mat_file") / "huge.mat").string();
  {
    const std::unique_ptr<mat_t, MatioFileCloser> file(Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT5));
    ASSERT_NE(file, nullptr);
    put_variable(file.get(), double_matrix("a", {3, 1}, {1, 2, 3}), MAT_COMPRESSION_NONE);
  }
  // An uncompressed v5 variable's dimensions are two int32 at bytes 160..167 (after the file header, the variable's
  // tag, its flags); 100 000 × 100 000 doubles would be 80 GB.
  std::fstream io(path, std::ios::binary | std::ios::in | std::ios::out);
  const std::int32_t huge[2] = {100000, 100000};
  io.seekp(160);
  io.write(reinterpret_cast<const char*>(huge), sizeof huge);
  io.close();
  EXPECT_TRUE(HasText(error_of([&] { read_mat_file(path); }), "found: a (unreadable)"));
}

// ---- v5 files written byte by byte: headers whose sizes their bytes cannot back ----------------------------

/// Appends `words` to `bytes` as 32-bit integers in this machine's byte order (the file header says which).
void append_words(std::string& bytes, std::initializer_list<std::uint32_t> words) {
  for (const std::uint32_t word : words) bytes.append(reinterpret_cast<const char*>(&word), sizeof word);
}

void append_doubles(std::string& bytes, std::initializer_list<double> values) {
  for (const double value : values) bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
}

/// The 128-byte header of a v5 file: text, subsystem offset, version 0x0100 and 'IM' in this machine's order.
std::string v5_file_header() {
  std::string header = "MATLAB 5.0 MAT-file, written by hand";
  header.resize(124, ' ');
  const std::uint16_t version_and_mark[2] = {0x0100, 0x4d49};
  header.append(reinterpret_cast<const char*>(version_and_mark), sizeof version_and_mark);
  return header;
}

/// A top-level v5 element holding the miMATRIX `contents` (what follows its tag); `claimed` replaces the count in
/// the miMATRIX tag when given. Compressed, the miMATRIX element, tag and all, is a zlib stream in a miCOMPRESSED
/// element, as MATLAB, scipy and matio write them.
std::string v5_element(const std::string& contents, bool compressed, std::optional<std::uint32_t> claimed = {}) {
  std::string matrix;
  append_words(matrix, {14, claimed.value_or(static_cast<std::uint32_t>(contents.size()))});  // miMATRIX
  matrix += contents;
  if (!compressed) return matrix;
  uLongf packed_bytes = compressBound(static_cast<uLong>(matrix.size()));
  std::string packed(packed_bytes, '\0');
  EXPECT_EQ(compress(reinterpret_cast<Bytef*>(packed.data()), &packed_bytes,
                     reinterpret_cast<const Bytef*>(matrix.data()), static_cast<uLong>(matrix.size())),
            Z_OK);
  packed.resize(packed_bytes);
  std::string element;
  append_words(element, {15, static_cast<std::uint32_t>(packed.size())});  // miCOMPRESSED
  return element + packed;
}

/// The contents of an m × 1 double matrix named with one letter.
std::string double_column_contents(char name, std::initializer_list<double> values) {
  std::string contents;
  append_words(contents, {6, 8, 6, 0});                                    // array flags: mxDOUBLE_CLASS
  append_words(contents, {5, 8, static_cast<std::uint32_t>(values.size()), 1});  // dimensions: m × 1
  append_words(contents, {(1u << 16) | 1u, static_cast<std::uint32_t>(name)});   // the name, packed in its tag
  append_words(contents, {9, static_cast<std::uint32_t>(8 * values.size())});    // miDOUBLE
  append_doubles(contents, values);
  return contents;
}

/// The contents of the struct `tests` of dims[0] × dims[1] elements whose field names are 8 bytes long and
/// `names_bytes` long together (the tag claims it; "t" and "x" follow). When `fields_follow`, each element (at most
/// the first two) has t = 1 and x = 2, else the element ends after the names.
std::string struct_contents(std::uint32_t rows, std::uint32_t cols, std::uint32_t names_bytes, bool fields_follow) {
  std::string contents;
  append_words(contents, {6, 8, 2, 0});           // array flags: mxSTRUCT_CLASS
  append_words(contents, {5, 8, rows, cols});     // dimensions
  append_words(contents, {1, 5});                 // the name: 5 int8
  contents.append("tests\0\0\0", 8);
  append_words(contents, {(4u << 16) | 5u, 8});   // field-name length 8, packed in its tag
  append_words(contents, {1, names_bytes});       // the field names: int8
  contents.append("t\0\0\0\0\0\0\0x\0\0\0\0\0\0\0", 16);
  if (!fields_follow) return contents;
  for (std::uint64_t k = 0; k < std::min<std::uint64_t>(std::uint64_t{rows} * cols, 2); ++k) {
    for (const double value : {1.0, 2.0}) {
      std::string field;
      append_words(field, {6, 8, 6, 0});
      append_words(field, {5, 8, 1, 1});
      append_words(field, {1, 0});  // a field element has no name of its own
      append_words(field, {9, 8});
      append_doubles(field, {value});
      append_words(contents, {14, static_cast<std::uint32_t>(field.size())});
      contents += field;
    }
  }
  return contents;
}

/// Writes a v5 file of a = [1; 2; 3], then `middle`, then b = [4; 5], each element compressed or not.
std::string write_a_then_b(const std::string& file_name, const std::string& middle, bool compressed) {
  const auto path = (test_temp_dir("mat_file") / file_name).string();
  std::ofstream out(path, std::ios::binary);
  out << v5_file_header() << v5_element(double_column_contents('a', {1, 2, 3}), compressed) << middle
      << v5_element(double_column_contents('b', {4, 5}), compressed);
  return path;
}

TEST(MatFile, HandWrittenV5StructIsRead) {
  // The layout the tests below damage, intact: tests.t and tests.x are channels between a and b.
  for (const bool compressed : {false, true}) {
    const std::string path =
        write_a_then_b("hand_struct.mat", v5_element(struct_contents(1, 1, 16, true), compressed), compressed);
    const ChannelTable table = read_mat_file(path);
    EXPECT_EQ(table.names, (std::vector<std::string>{"a", "tests.t", "tests.x", "b"})) << compressed;
    EXPECT_TRUE(table.skipped.empty()) << compressed;
    EXPECT_EQ(table.channels.at("tests.x").values, std::vector<double>{2.0}) << compressed;
  }
}

TEST(MatFile, StructHeaderClaimingMoreThanItsBytesIsNotHandedToMatio) {
  // What libFuzzer found: a struct whose field-name tag claims 458 MB (so 229 million 2-byte field names: matio
  // allocated their 458 MB, then 3.7 GB of field pointers for the 1 × 2 struct) in an element of a few dozen bytes.
  // A header is damaged just as badly when its dimensions claim more elements × fields than the bytes could hold
  // (here 1 × 2^31 − 1 elements × 2 fields, 34 GB of pointers). matio is never given such an element: it and the
  // variables after it are counted as unlisted, the variables before it read as usual.
  for (const bool compressed : {false, true}) {
    for (const auto& [what, contents] :
         {std::pair<std::string, std::string>{"field names", struct_contents(1, 2, 458865152u, false)},
          {"dimensions", struct_contents(1, 0x7fffffffu, 16, true)}}) {
      const std::string path = write_a_then_b("claims.mat", v5_element(contents, compressed), compressed);
      const ChannelTable table = read_mat_file(path);
      EXPECT_EQ(table.names, std::vector<std::string>{"a"}) << what << compressed;
      EXPECT_EQ(table.skipped, std::vector<std::string>{"2 unlisted variables (unreadable)"}) << what << compressed;
    }
  }
  // As in the fuzzer's file, the struct is the last element and its tag also claims more bytes than the file has.
  const auto path = (test_temp_dir("mat_file") / "claims_last.mat").string();
  {
    const std::string contents = struct_contents(1, 2, 458865152u, false);
    std::ofstream out(path, std::ios::binary);
    out << v5_file_header() << v5_element(double_column_contents('a', {1, 2, 3}), false)
        << v5_element(contents, false, static_cast<std::uint32_t>(contents.size() + 600));
  }
  const ChannelTable table = read_mat_file(path);
  EXPECT_EQ(table.names, std::vector<std::string>{"a"});
  EXPECT_EQ(table.skipped, std::vector<std::string>{"1 unlisted variable (unreadable)"});
}

TEST(MatFile, MissingFileNamesThePath) {
  const auto path = (test_temp_dir("mat_file") / "missing.mat").string();
  EXPECT_THROW(read_mat_file(path), InputError);
  const std::string message = error_of([&] { read_mat_file(path); });
  EXPECT_TRUE(HasText(message, path + ": no such file"));
}

TEST(MatFile, TextFileRenamedMatIsNotAMatFile) {
  const auto path = test_temp_dir("mat_file") / "record.mat";
  testing::write_text(path, "t,x,F\n0,0.001,12.5\n0.001,0.002,13.0\n");
  EXPECT_THROW(read_mat_file(path.string()), InputError);
  EXPECT_TRUE(HasText(error_of([&] { read_mat_file(path.string()); }), path.string() + ": not a MATLAB .mat file"));
}

TEST(MatFile, EmptyFileAndFolderAreNotMatFiles) {
  const auto dir = test_temp_dir("mat_file");
  testing::write_text(dir / "empty.mat", "");
  EXPECT_TRUE(HasText(error_of([&] { read_mat_file((dir / "empty.mat").string()); }), "empty.mat: empty file"));
  EXPECT_TRUE(HasText(error_of([&] { read_mat_file(dir.string()); }), dir.string() + ": not a file"));
}

TEST(MatFile, FileWithoutNumericMatrixListsWhatItHas) {
  const auto path = (test_temp_dir("mat_file") / "text.mat").string();
  {
    const std::unique_ptr<mat_t, MatioFileCloser> file(Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT5));
    ASSERT_NE(file, nullptr);
    put_variable(file.get(), char_variable("label", "damper"), MAT_COMPRESSION_NONE);
    matvar_t* s = struct_variable("s", {1, 1}, {"operator"});
    set_field(s, "operator", 0, char_variable("operator", "A. N. Other"));
    put_variable(file.get(), s, MAT_COMPRESSION_NONE);
  }
  const std::string message = error_of([&] { read_mat_file(path); });
  EXPECT_TRUE(HasText(message, path + ": no numeric matrix in the file (found: label (char), s (struct with no "
                                      "numeric field))"));
}

TEST(MatFile, WriteErrorsNameThePath) {
  const auto dir = test_temp_dir("mat_file");
  const std::string nowhere = (dir / "no_such_folder" / "out.mat").string();
  EXPECT_TRUE(HasText(error_of([&] { write_mat_file(nowhere, {{"x", {1.0}}}); }), "cannot write " + nowhere + ": "));
  EXPECT_TRUE(HasText(error_of([&] { write_mat_file(nowhere, {{"x", {1.0}}}, MatVersion::v73); }),
                      "cannot write " + nowhere + ": "));

  const std::string out = (dir / "out.mat").string();
  EXPECT_TRUE(HasText(error_of([&] { write_mat_file(out, {{"x[mm]", {1.0}}}); }),
                      "cannot write " + out + ": 'x[mm]' is not a MATLAB variable name"));
  EXPECT_TRUE(HasText(error_of([&] { write_mat_file(out, {{"x", {1.0}}, {"x", {2.0}}}); }),
                      "cannot write " + out + ": column 'x' given twice"));
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace dampbench
