// Tests for engine/csv_loader: formats, units, computed derivatives, every error message, and a real file.
#include "engine/record/csv_loader.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "engine/common/error.hpp"
#include "tests/test_support.hpp"

#ifndef DAMPBENCH_SHARED_DATA_DIR
#error "DAMPBENCH_SHARED_DATA_DIR must name the folder with the real test data"
#endif

namespace dampbench {
namespace {

Dataset parse_text(const std::string& text, const CsvOptions& options = {}, const std::string& source = "data.csv") {
  std::istringstream in(text);
  return parse_csv(in, source, options);
}

using testing::error_of;

/// The message of parsing `text` as "data.csv".
std::string parse_error(const std::string& text, const CsvOptions& options = {}) {
  return error_of([&] { parse_text(text, options); });
}

using testing::HasText;

CsvOptions with_columns(std::vector<std::string> columns) {
  CsvOptions options;
  options.columns = std::move(columns);
  return options;
}

/// `n` comma-separated rows "k*0.01, k, 2k" (t in s; x and F in the header's units), one per line.
std::string linear_rows(int n) {
  std::string rows;
  for (int k = 0; k < n; ++k) rows += fmt::format("{},{},{}\n", 0.01 * k, k, 2 * k);
  return rows;
}

// ---- formats and units -----------------------------------------------------------------------------------

TEST(CsvLoader, OperatingCommentSetsOperatingVariables) {
  const Dataset d = parse_text("# test at 1 A\n# operating: I=1,amp=0.01, freq = 2\nt,x,F\n" + linear_rows(10));
  EXPECT_DOUBLE_EQ(d.operating.at("I"), 1.0);
  EXPECT_DOUBLE_EQ(d.operating.at("amp"), 0.01);
  EXPECT_DOUBLE_EQ(d.operating.at("freq"), 2.0);
  EXPECT_TRUE(HasText(parse_error("# operating: T=3\nt,x,F\n" + linear_rows(10)),
                      "data.csv:1: operating: unknown operating variable 'T'"));
  EXPECT_TRUE(HasText(parse_error("# operating: I=one\nt,x,F\n" + linear_rows(10)),
                      "data.csv:1: operating I: expected a number, got 'one'"));
}

TEST(CsvLoader, HeaderUnitsAreConvertedToSi) {
  const Dataset data = parse_text("t[s],x[mm],F[kN]\n" + linear_rows(10));
  ASSERT_EQ(data.size(), 10u);
  EXPECT_DOUBLE_EQ(data.t_s[3], 0.03);
  EXPECT_DOUBLE_EQ(data.x_m[3], 0.003);   // 3 mm
  EXPECT_DOUBLE_EQ(data.F_N[3], 6000.0);  // 6 kN
  EXPECT_EQ(data.name, "data");
  EXPECT_EQ(data.source, "data.csv");
  EXPECT_TRUE(data.operating.empty());
}

TEST(CsvLoader, HeaderUnitsMayBeSeparatedBySpaces) {
  const Dataset data = parse_text("t [ms], x [cm], F [lbf]\n" + linear_rows(10));
  EXPECT_DOUBLE_EQ(data.t_s[3], 3e-5);                   // 0.03 ms
  EXPECT_DOUBLE_EQ(data.x_m[3], 0.03);                   // 3 cm
  EXPECT_NEAR(data.F_N[3], 6 * 4.4482216152605, 1e-12);  // 6 lbf
}

TEST(CsvLoader, NoUnitMeansSi) {
  const Dataset data = parse_text("t,x,F\n" + linear_rows(10));
  EXPECT_DOUBLE_EQ(data.x_m[3], 3.0);
  EXPECT_DOUBLE_EQ(data.F_N[3], 6.0);
}

TEST(CsvLoader, UnitsOptionOverridesHeader) {
  CsvOptions options;
  options.units = parse_units_option("x=cm,F=kN");
  const Dataset data = parse_text("t,x[mm],F\n" + linear_rows(10), options);
  EXPECT_DOUBLE_EQ(data.x_m[3], 0.03);    // 3 cm, not 3 mm
  EXPECT_DOUBLE_EQ(data.F_N[3], 6000.0);  // 6 kN
}

TEST(CsvLoader, UnitsOptionForAbsentColumnIsIgnored) {
  CsvOptions options;
  options.units = parse_units_option("v=mm/s");
  EXPECT_EQ(parse_text("t,x,F\n" + linear_rows(10), options).size(), 10u);
}

TEST(CsvLoader, ParseUnitsOption) {
  const auto units = parse_units_option("x=mm, F=kN");
  EXPECT_EQ(units, (std::map<std::string, std::string>{{"x", "mm"}, {"F", "kN"}}));
  EXPECT_TRUE(parse_units_option("").empty());
}

TEST(CsvLoader, WhitespaceSeparatedWithColumnsOption) {
  // like the real data files: t [s], x [mm], v [mm/s], F [N], no header
  std::string text;
  for (int k = 0; k < 8; ++k) text += fmt::format("  {:.3f}\t-0.0123  {}   -45.6\n", 0.001 * k, 1.23 + k);
  CsvOptions options = with_columns({"t", "x", "v", "F"});
  options.units = parse_units_option("x=mm,v=mm/s");
  const Dataset data = parse_text(text, options);
  ASSERT_EQ(data.size(), 8u);
  EXPECT_DOUBLE_EQ(data.t_s[7], 0.007);
  EXPECT_DOUBLE_EQ(data.x_m[0], -0.0123e-3);
  EXPECT_DOUBLE_EQ(data.v_m_s[2], 3.23e-3);  // taken from the file, not differentiated (x is constant)
  EXPECT_DOUBLE_EQ(data.F_N[5], -45.6);
  // a is the derivative of the file's v: 1 mm/s per ms = 1 m/s²
  for (double a : data.a_m_s2) EXPECT_NEAR(a, 1.0, 1e-9);
}

TEST(CsvLoader, ColumnsOptionMayCarryUnits) {
  const Dataset data = parse_text(linear_rows(10), with_columns({"t", "x[mm]", "F[kN]"}));
  EXPECT_DOUBLE_EQ(data.x_m[3], 0.003);
  EXPECT_DOUBLE_EQ(data.F_N[3], 6000.0);
}

TEST(CsvLoader, ColumnsOptionRenamesHeaderColumns) {
  const Dataset data = parse_text("time[ms],stroke[mm],load\n" + linear_rows(10), with_columns({"t", "x", "F[kN]"}));
  EXPECT_DOUBLE_EQ(data.t_s[3], 3e-5);    // header unit kept
  EXPECT_DOUBLE_EQ(data.x_m[3], 0.003);   // header unit kept
  EXPECT_DOUBLE_EQ(data.F_N[3], 6000.0);  // unit from --columns
}

TEST(CsvLoader, AcceptsExponentsAndLeadingPlus) {
  std::string text = "t,x,F\n";
  for (int k = 0; k < 8; ++k) text += fmt::format("{}e-2,+1.5E+1,-2.5e0\n", k);
  const Dataset data = parse_text(text);
  EXPECT_DOUBLE_EQ(data.t_s[2], 0.02);
  EXPECT_DOUBLE_EQ(data.x_m[0], 15.0);
  EXPECT_DOUBLE_EQ(data.F_N[0], -2.5);
}

TEST(CsvLoader, SkipsCommentsBlankLinesAndCarriageReturns) {
  std::string text = "# rig 3, test 17\n\n   # units below\nt,x,F\r\n";
  for (int k = 0; k < 10; ++k) text += fmt::format("{},{},{}\r\n", 0.01 * k, k, 2 * k) + (k == 4 ? "# pause\n" : "");
  text += "\n\n  \n";
  const Dataset data = parse_text(text);
  ASSERT_EQ(data.size(), 10u);
  EXPECT_DOUBLE_EQ(data.x_m[9], 9.0);
}

TEST(CsvLoader, CommentsDoNotShiftLineNumbers) {
  // line 1 comment, line 2 blank, line 3 header, lines 4-6 data, line 7 comment, line 8 bad
  const std::string text = "# comment\n\nt,x,F\n0,0,0\n1,1,1\n2,2,2\n# note\n3,abc,3\n";
  EXPECT_TRUE(HasText(parse_error(text), "data.csv:8: column 2 ('x'): expected a number, got 'abc'"));
}

TEST(CsvLoader, ComputesVelocityAndAccelerationOfASine) {
  // x = X sin(2π f t + φ), 1 Hz, 1 kHz, one period: v = X ω cos, a = -X ω² sin
  const double amp = 0.01, omega = 2 * std::numbers::pi, phase = 0.4;
  std::string text = "t,x[mm],F\n";
  for (int k = 0; k <= 1000; ++k)
    text += fmt::format("{:.17g},{:.17g},0\n", k * 1e-3, 1e3 * amp * std::sin(omega * k * 1e-3 + phase));
  const Dataset data = parse_text(text);
  ASSERT_EQ(data.size(), 1001u);
  ASSERT_EQ(data.v_m_s.size(), 1001u);
  ASSERT_EQ(data.a_m_s2.size(), 1001u);
  double v_error = 0, a_error = 0;
  for (std::size_t k = 0; k < data.size(); ++k) {
    const double arg = omega * data.t_s[k] + phase;
    v_error = std::max(v_error, std::abs(data.v_m_s[k] - amp * omega * std::cos(arg)));
    a_error = std::max(a_error, std::abs(data.a_m_s2[k] + amp * omega * omega * std::sin(arg)));
  }
  EXPECT_LT(v_error, 1e-6 * amp * omega);  // 3rd/4th-order scheme at 1000 samples per cycle
  EXPECT_LT(a_error, 1e-3 * amp * omega * omega);
}

TEST(CsvLoader, OperatingColumnsGiveTheirMean) {
  std::string text = "t,x,F,I[mA],V,phi[rad]\n";
  for (int k = 0; k < 8; ++k)
    text += fmt::format("{},0,0,{},{},{}\n", k, k % 2 ? 500 : 1500, 2.5, std::numbers::pi / 2);
  const Dataset data = parse_text(text);
  EXPECT_DOUBLE_EQ(data.operating.at("I"), 1.0);  // mean of 0.5 A and 1.5 A
  EXPECT_DOUBLE_EQ(data.operating.at("V"), 2.5);
  EXPECT_NEAR(data.operating.at("phi"), 90.0, 1e-12);  // π/2 rad in degrees
  EXPECT_EQ(data.operating.size(), 3u);
}

TEST(CsvLoader, ForceIsOptionalWhenNotRequired) {
  std::string text = "t,x\n";
  for (int k = 0; k < 8; ++k) text += fmt::format("{},{}\n", k, k);
  CsvOptions options;
  options.require_force = false;
  const Dataset data = parse_text(text, options);
  EXPECT_FALSE(data.has_force());
  EXPECT_EQ(data.size(), 8u);
}

TEST(CsvLoader, FileAndVelocityAndAccelerationColumns) {
  std::string text = "t,x,v,a,F\n";
  for (int k = 0; k < 8; ++k) text += fmt::format("{},0,{},{},0\n", k, 10 + k, 20 + k);
  const Dataset data = parse_text(text);
  EXPECT_DOUBLE_EQ(data.v_m_s[3], 13.0);
  EXPECT_DOUBLE_EQ(data.a_m_s2[3], 23.0);
}

TEST(CsvLoader, NameIsTheStemOfTheSource) {
  EXPECT_EQ(parse_text("t,x,F\n" + linear_rows(8), {}, "rig/test_17.csv").name, "test_17");
}

// ---- errors --------------------------------------------------------------------------------------------------

TEST(CsvLoaderErrors, MissingColumn) {
  std::string text = "t,x\n";
  for (int k = 0; k < 8; ++k) text += fmt::format("{},{}\n", k, k);
  EXPECT_EQ(parse_error(text), "data.csv: missing column 'F' (columns found: t, x)");
  EXPECT_EQ(parse_error("F,v\n1,2\n"), "data.csv: missing columns 't', 'x' (columns found: F, v)");
}

TEST(CsvLoaderErrors, NonNumericCell) {
  std::string text = "t,x,F\n" + linear_rows(5) + "0.05,5,abc\n";
  EXPECT_TRUE(HasText(parse_error(text), "data.csv:7: column 3 ('F'): expected a number, got 'abc'"));
  EXPECT_TRUE(HasText(parse_error("t,x,F\n0,1,\n"), "data.csv:2: column 3 ('F'): expected a number, got ''"));
}

TEST(CsvLoaderErrors, NonFiniteCell) {
  for (const char* value : {"nan", "inf", "-inf", "NaN"}) {
    const std::string text = "t,x,F\n" + linear_rows(5) + fmt::format("0.05,5,{}\n", value);
    EXPECT_TRUE(
        HasText(parse_error(text), fmt::format("data.csv:7: column 3 ('F'): value is not finite ('{}')", value)));
  }
  EXPECT_TRUE(HasText(parse_error("t,x,F\n0,1e999,0\n"), "data.csv:2: column 2 ('x'): value out of range ('1e999')"));
  // A command column (I, V, phi) that simulate --fixed-step and inverse follow sample by sample: a gap in it is
  // refused where it is, not held or interpolated over.
  EXPECT_TRUE(HasText(parse_error("t,x,F,I\n0,0,0,0.5\n0.01,1,2,nan\n"),
                      "data.csv:3: column 4 ('I'): value is not finite ('nan')"));
}

TEST(CsvLoaderErrors, WrongCellCount) {
  const std::string text = "t,x,v,F\n0,0,0,0\n1,1,1,1\n2,2,2,2\n3,3,3,3\n4,4,4,4\n5,5,5\n";
  EXPECT_TRUE(HasText(parse_error(text), "data.csv:7: expected 4 values, got 3"));
  EXPECT_TRUE(HasText(parse_error("t,x,F\n0,0,0,0\n"), "data.csv:2: expected 3 values, got 4"));
}

TEST(CsvLoaderErrors, TimeMustIncrease) {
  // t in ms: 0, 10, 20 (lines 2-4), then 20 again at line 5 — reported in seconds
  std::string text = "t[ms],x,F\n";
  for (int k = 0; k <= 2; ++k) text += fmt::format("{},0,0\n", 10 * k);
  text += "20,0,0\n";  // line 5: 20 after 20
  EXPECT_TRUE(HasText(parse_error(text), "data.csv:5: time must increase strictly (0.02 s after 0.02 s)"));
  const std::string later = "t,x,F\n0,0,0\n0.005,0,0\n0.01,0,0\n0.015,0,0\n0.016,0,0\n0.018,0,0\n0.02,0,0\n0.02,0,0\n";
  EXPECT_TRUE(HasText(parse_error(later), "data.csv:9: time must increase strictly (0.02 s after 0.02 s)"));
  EXPECT_TRUE(HasText(parse_error("t,x,F\n0,0,0\n0.5,0,0\n0.25,0,0\n"),
                      "data.csv:4: time must increase strictly (0.25 s after 0.5 s)"));
}

TEST(CsvLoaderErrors, TooFewSamples) {
  EXPECT_EQ(parse_error("t,x,F\n" + linear_rows(3)), "data.csv: 3 samples; at least 8 are needed");
  CsvOptions options;
  options.min_samples = 20;
  EXPECT_EQ(parse_error("t,x,F\n" + linear_rows(10), options), "data.csv: 10 samples; at least 20 are needed");
  options.min_samples = 1;  // derivatives still need 4
  EXPECT_EQ(parse_error("t,x,F\n" + linear_rows(3), options), "data.csv: 3 samples; at least 4 are needed");
  EXPECT_EQ(parse_text("t,x,F\n" + linear_rows(4), options).size(), 4u);
}

TEST(CsvLoaderErrors, UnknownUnitInHeader) {
  EXPECT_EQ(parse_error("t,x[furlong],F\n" + linear_rows(10)),
            "data.csv:1: unknown unit 'furlong' for column 'x' (known: m, mm, cm, um, in, rad, deg)");
  EXPECT_TRUE(HasText(parse_error("# comment\n\nt,x,F[kp]\n" + linear_rows(10)), "data.csv:3: unknown unit 'kp'"));
  EXPECT_TRUE(HasText(parse_error("t,x[mm,F\n" + linear_rows(10)), "data.csv:1: header cell 'x[mm'"));
}

TEST(CsvLoaderErrors, UnknownUnitInOptions) {
  EXPECT_EQ(error_of([] { parse_units_option("x=furlong"); }),
            "--units: unknown unit 'furlong' for column 'x' (known: m, mm, cm, um, in, rad, deg)");
  EXPECT_EQ(error_of([] { parse_units_option("q=mm"); }),
            "--units: unknown column 'q' (known: t, x, v, a, F, y, u, I, V, phi)");
  EXPECT_EQ(error_of([] { parse_units_option("x=mm,x=cm"); }), "--units: 'x' given twice");
  CsvOptions options;
  options.units = {{"x", "furlong"}};  // built by hand, not validated by parse_units_option
  EXPECT_TRUE(HasText(parse_error("t,x,F\n" + linear_rows(10), options), "data.csv: --units: unknown unit 'furlong'"));
  EXPECT_TRUE(HasText(parse_error(linear_rows(10), with_columns({"t", "x[yd]", "F"})),
                      "data.csv: --columns: unknown unit 'yd' for column 'x'"));
}

TEST(CsvLoaderErrors, UnknownColumnNames) {
  EXPECT_EQ(parse_error("t,x,F,q\n0,0,0,0\n"), "data.csv:1: unknown column 'q' (known: t, x, v, a, F, y, u, I, V, phi)");
  EXPECT_TRUE(HasText(parse_error("time,x,F,load\n0,0,0,0\n"), "data.csv:1: unknown columns 'time', 'load'"));
  EXPECT_TRUE(
      HasText(parse_error(linear_rows(10), with_columns({"t", "x", "f"})), "data.csv: --columns: unknown column 'f'"));
  EXPECT_TRUE(HasText(parse_error("t,x,x\n0,0,0\n"), "data.csv:1: column 'x' given twice"));
}

TEST(CsvLoaderErrors, NoHeaderAndNoColumns) {
  EXPECT_EQ(parse_error(linear_rows(10)),
            "data.csv: no header row and no --columns given; expected a header like t,x,F or --columns t,x,v,F");
}

TEST(CsvLoaderErrors, ColumnsCountMustMatchHeader) {
  EXPECT_TRUE(HasText(parse_error("a,b,c\n" + linear_rows(10), with_columns({"t", "x"})),
                      "data.csv:1: --columns gives 2 names but the header has 3 columns"));
}

TEST(CsvLoaderErrors, EmptyFile) {
  EXPECT_TRUE(HasText(parse_error(""), "data.csv: no data"));
  EXPECT_TRUE(HasText(parse_error("# only a comment\n\n"), "data.csv: no data"));
}

// ---- files -----------------------------------------------------------------------------------------------------

/// A fresh directory under the system temporary directory, removed at the end of the test.
class CsvFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
    dir_ = std::filesystem::temp_directory_path() / fmt::format("dampbench-test-csv-{}", stamp);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(CsvFile, LoadsFromDisk) {
  const std::string path = (dir_ / "run 3.csv").string();
  std::ofstream(path) << "t,x[mm],F\n" << linear_rows(10);
  const Dataset data = load_csv(path, {});
  EXPECT_EQ(data.name, "run 3");
  EXPECT_EQ(data.source, path);
  EXPECT_DOUBLE_EQ(data.x_m[9], 0.009);
  // x is linear in t (1 mm per 10 ms): v = 0.1 m/s, a = 0, also at the ends
  for (double v : data.v_m_s) EXPECT_NEAR(v, 0.1, 1e-9);
  for (double a : data.a_m_s2) EXPECT_NEAR(a, 0.0, 1e-6);
}

TEST_F(CsvFile, ErrorsNameThePath) {
  const std::string path = (dir_ / "short.csv").string();
  std::ofstream(path) << "t,x,F\n" << linear_rows(2);
  EXPECT_EQ(error_of([&] { load_csv(path, {}); }), path + ": 2 samples; at least 8 are needed");
}

TEST_F(CsvFile, MissingFile) {
  const std::string path = (dir_ / "nope.csv").string();
  EXPECT_EQ(error_of([&] { load_csv(path, {}); }), "cannot open data file '" + path + "'");
}

TEST(CsvRealData, MrDamperFileLoads) {
  const std::string path = std::string(DAMPBENCH_SHARED_DATA_DIR) + "/utfsm-mr-damper/10mm1Hz1A.txt";
  if (!std::filesystem::exists(path))
    GTEST_SKIP() << "real data not found at " << path << ": ../shared/data is beside the repository in CI";
  CsvOptions options = with_columns({"t", "x", "v", "F"});
  options.units = parse_units_option("x=mm,v=mm/s");
  const Dataset data = load_csv(path, options);
  EXPECT_EQ(data.name, "10mm1Hz1A");
  ASSERT_GT(data.size(), 1000u);
  const auto [x_min, x_max] = std::minmax_element(data.x_m.begin(), data.x_m.end());
  EXPECT_NEAR(*x_max, 0.0097, 0.05 * 0.0097);  // data README: x ≈ ±9.7 mm
  EXPECT_NEAR(*x_min, -0.0097, 0.05 * 0.0097);
  const auto [v_min, v_max] = std::minmax_element(data.v_m_s.begin(), data.v_m_s.end());
  EXPECT_NEAR(*v_max, 0.0626, 0.05 * 0.0626);  // data README: v ≈ ±62.6 mm/s
  EXPECT_NEAR(*v_min, -0.0626, 0.05 * 0.0626);
  EXPECT_EQ(data.F_N.size(), data.size());
  EXPECT_EQ(data.a_m_s2.size(), data.size());
}

}  // namespace
}  // namespace dampbench
