// Records from a rig's text export and from a table of channels (engine/record/record_files.hpp, column_map.hpp,
// text_channels.hpp, preprocess.hpp): hand-computed answers and the messages of bad input.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/common/error.hpp"
#include "engine/record/column_map.hpp"
#include "engine/record/preprocess.hpp"
#include "engine/record/record_files.hpp"
#include "engine/record/record_options.hpp"
#include "engine/record/text_channels.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

namespace fs = std::filesystem;

TEST(ColumnMap, CommasInsideBracketsBelongToTheIndex) {
  const auto picks = parse_column_map("t=time, x=data[:,0], F=data[:,1:6], u=rec[1,:]");
  ASSERT_EQ(picks.size(), 4u);
  EXPECT_EQ(picks[0].channel, "time");
  EXPECT_EQ(picks[0].axis, ColumnPick::Axis::whole);
  EXPECT_EQ(picks[1].axis, ColumnPick::Axis::column);
  EXPECT_EQ(picks[1].first, 0u);
  EXPECT_EQ(picks[1].last, 1u);
  EXPECT_FALSE(picks[1].range);
  EXPECT_TRUE(picks[2].range);
  EXPECT_EQ(picks[2].first, 1u);
  EXPECT_EQ(picks[2].last, 6u);
  EXPECT_EQ(picks[3].axis, ColumnPick::Axis::row);
  EXPECT_EQ(picks[3].first, 1u);
}

TEST(ColumnMap, MalformedEntriesAreNamed) {
  EXPECT_NE(testing::error_of([] { parse_column_map("q=data[:,0]"); }).find("unknown record column 'q'"), std::string::npos);
  EXPECT_NE(testing::error_of([] { parse_column_map("x=data[0]"); }).find("expected two indices"), std::string::npos);
  EXPECT_NE(testing::error_of([] { parse_column_map("x=data[:,3:1]"); }).find("is empty"), std::string::npos);
  EXPECT_NE(testing::error_of([] { parse_column_map("x=a,x=b"); }).find("column 'x' given twice"), std::string::npos);
  EXPECT_NE(testing::error_of([] { parse_column_map("x=data[:,-1]"); }).find("counted from 0"), std::string::npos);
  EXPECT_NE(testing::error_of([] { parse_column_map("x=data[:,inf]"); }).find("counted from 0"), std::string::npos);
  EXPECT_NE(testing::error_of([] { parse_column_map("x=data[:,1e300]"); }).find("counted from 0"), std::string::npos);
}

ChannelTable three_by_four() {
  ChannelTable t;
  t.source = "m.mat";
  t.names = {"data", "time"};
  t.channels["data"] = {3, 4, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}};  // column-major: column j is 3j+1 .. 3j+3
  t.channels["time"] = {3, 1, {0, 0.5, 1}};
  return t;
}

TEST(ColumnMap, PicksColumnsRowsAndRanges) {
  const ChannelTable t = three_by_four();
  EXPECT_EQ(pick_vectors(t, parse_column_map("x=data[:,2]")[0]), (std::vector<std::vector<double>>{{7, 8, 9}}));
  EXPECT_EQ(pick_vectors(t, parse_column_map("x=data[1,:]")[0]), (std::vector<std::vector<double>>{{2, 5, 8, 11}}));
  EXPECT_EQ(pick_vectors(t, parse_column_map("F=data[:,1:3]")[0]),
            (std::vector<std::vector<double>>{{4, 5, 6}, {7, 8, 9}}));
  EXPECT_EQ(pick_vectors(t, parse_column_map("t=#1")[0]), (std::vector<std::vector<double>>{{0, 0.5, 1}}));
  const std::string missing = testing::error_of([&] { pick_vectors(t, parse_column_map("t=tiempo")[0]); });
  EXPECT_NE(missing.find("m.mat: --columns 't=tiempo': no channel 'tiempo' in the file (it holds: data (3x4), time (3x1))"),
            std::string::npos)
      << missing;
  const std::string range = testing::error_of([&] { pick_vectors(t, parse_column_map("x=data[:,4]")[0]); });
  EXPECT_NE(range.find("column 4 out of range: 'data' is 3x4"), std::string::npos) << range;
  EXPECT_NE(testing::error_of([&] { pick_vectors(t, parse_column_map("x=data")[0]); }).find("is a 3x4 matrix"),
            std::string::npos);
}

TEST(ColumnMap, AStructArraysFieldGivesOneVectorPerElement) {
  ChannelTable t;
  t.source = "s.mat";
  t.names = {"tests(1).x", "tests(2).x", "tests(3).x", "tests(1).F"};
  t.channels["tests(1).x"] = {2, 1, {1, 2}};
  t.channels["tests(2).x"] = {1, 3, {3, 4, 5}};
  t.channels["tests(3).x"] = {1, 1, {6}};
  t.channels["tests(1).F"] = {2, 1, {7, 8}};
  EXPECT_EQ(pick_vectors(t, parse_column_map("x=tests(:).x")[0]),
            (std::vector<std::vector<double>>{{1, 2}, {3, 4, 5}, {6}}));
  EXPECT_EQ(pick_vectors(t, parse_column_map("F=tests(:).F")[0]), (std::vector<std::vector<double>>{{7, 8}}));
  EXPECT_EQ(pick_vectors(t, parse_column_map("x=tests(2).x")[0]), (std::vector<std::vector<double>>{{3, 4, 5}}));
  const std::string missing = testing::error_of([&] { pick_vectors(t, parse_column_map("x=runs(:).x")[0]); });
  EXPECT_NE(missing.find("no channel 'runs(k).x' for k = 1, 2, ..."), std::string::npos) << missing;
  t.skipped = {"tests(4).x (empty)"};
  t.names.push_back("tests(5).x");
  t.channels["tests(5).x"] = {1, 1, {9}};
  const std::string gap = testing::error_of([&] { pick_vectors(t, parse_column_map("x=tests(:).x")[0]); });
  EXPECT_NE(gap.find("element 4 has no numeric 'tests(4).x' (tests(4).x (empty))"), std::string::npos) << gap;
  ChannelTable one;  // a struct array of one element is named as a struct
  one.source = "one.mat";
  one.names = {"tests.x"};
  one.channels["tests.x"] = {2, 1, {1, 2}};
  EXPECT_EQ(pick_vectors(one, parse_column_map("x=tests(:).x")[0]), (std::vector<std::vector<double>>{{1, 2}}));
}

/// A rig export: a 7-line header block, three tests of 8 samples (CHANNEL1 = 1, 2, ..., 24 V; CHANNEL0 a tenth of
/// it) between DAQ Pause and Resume events.
std::string rig_export() {
  std::string text =
      "Header Size:  7\nVersion:  2\nSampling Interval:  0.005\nSampling Rate:  200\nSample Count:  24\n"
      "Device Serial Number:  0\nSample Number, Date/Time, CHANNEL0, CHANNEL1, Events\n";
  for (int k = 1; k <= 24; ++k) {
    const char* event = k == 1 ? ", DAQ Start" : k % 8 == 0 ? ", DAQ Pause" : k % 8 == 1 ? ", DAQ Resume" : "";
    text += std::to_string(k) + ",   04/29/2022 12:11:14.596 PM, " + std::to_string(k / 10.0).substr(0, 3) + ", " +
            std::to_string(k) + ".0" + event + "\n";
  }
  return text;
}

TEST(TextChannels, HeaderBlockNumericColumnsAndEvents) {
  std::istringstream in(rig_export());
  const ChannelTable t = parse_text_channels(in, "rig.txt", std::nullopt);
  EXPECT_EQ(t.names, (std::vector<std::string>{"Sample Number", "CHANNEL0", "CHANNEL1"}));
  EXPECT_EQ(t.skipped, (std::vector<std::string>{"Date/Time (text)"}));
  ASSERT_TRUE(t.sampling_interval_s);
  EXPECT_EQ(*t.sampling_interval_s, 0.005);
  EXPECT_EQ(t.channels.at("CHANNEL1").values[4], 5.0);
  EXPECT_EQ(t.channels.at("CHANNEL0").values[4], 0.5);
  ASSERT_EQ(t.events.size(), 24u);
  EXPECT_EQ(t.events[7], "DAQ Pause");
  EXPECT_EQ(t.events[8], "DAQ Resume");
  EXPECT_EQ(t.events[1], "");
}

TEST(TextChannels, ABlockOfAnotherShapeIsNamed) {
  std::string text = rig_export();
  text.replace(text.find("Header Size:  7"), 15, "Header Size:  5");  // line 5 is not the names line
  std::istringstream in(text);
  const std::string message = testing::error_of([&] { parse_text_channels(in, "rig.txt", std::nullopt); });
  EXPECT_NE(message.find("rig.txt:5: a header block of another shape"), std::string::npos) << message;
  EXPECT_NE(message.find("another shape"), std::string::npos) << message;
}

class RecordFiles : public ::testing::Test {
 protected:
  fs::path dir_ = testing::test_temp_dir("record_files");
  std::string write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }
};

TEST_F(RecordFiles, AnExportSplitsIntoItsTestsWithGainsAndCurrents) {
  RecordOptions o;
  o.path = write("rig.txt", rig_export());
  o.columns = "x=CHANNEL1,F=CHANNEL0";
  o.scale = "x=10e-3,F=980.665";
  o.split = "events";
  o.set = "I=0,0.5,1,amp=0.01";
  const std::vector<Dataset> records = load_records(o, true);
  ASSERT_EQ(records.size(), 3u);
  for (std::size_t r = 0; r < 3; ++r) {
    EXPECT_EQ(records[r].name, "rig#" + std::to_string(r + 1));
    EXPECT_EQ(records[r].operating.at("I"), 0.5 * static_cast<double>(r));
    EXPECT_EQ(records[r].operating.at("amp"), 0.01);
    ASSERT_EQ(records[r].size(), 8u);
    for (std::size_t k = 0; k < 8; ++k) {
      const double volts = static_cast<double>(8 * r + k + 1);
      EXPECT_EQ(records[r].x_m[k], volts * 10e-3);  // gain applied, no unit
      EXPECT_EQ(records[r].F_N[k], std::stod(std::to_string(volts / 10).substr(0, 3)) * 980.665);
      EXPECT_EQ(records[r].t_s[k], static_cast<double>(k) * 0.005);  // each test's time from its own start
    }
  }
  o.set = "I=0,1";
  EXPECT_NE(testing::error_of([&] { load_records(o, true); }).find("--set I: 2 values for 3 records"), std::string::npos);
  o.set = "";
  EXPECT_NE(testing::error_of([&] { load_record(o, true); }).find("gives 3 records"), std::string::npos);
}

TEST_F(RecordFiles, ScaleAndSplitErrorsNameTheOption) {
  RecordOptions o;
  o.path = write("rig.txt", rig_export());
  o.columns = "x=CHANNEL1,F=CHANNEL0";
  o.scale = "q=2";
  EXPECT_NE(testing::error_of([&] { load_records(o, true); }).find("--scale q: the record has no column 'q'"),
            std::string::npos);
  o.scale = "";
  o.split = "gaps";
  EXPECT_NE(testing::error_of([&] { load_records(o, true); }).find("--split: expected events or nan, got 'gaps'"),
            std::string::npos);
}

TEST_F(RecordFiles, RowsOfNaNSeparateTests) {
  RecordOptions o;
  std::string text = "time,disp,force\n";
  for (int k = 0; k < 16; ++k) text += std::to_string(k) + "," + std::to_string(k + 1) + ",10\n" + (k == 7 ? "NaN,NaN,NaN\n" : "");
  o.path = write("nan.csv", text);
  o.columns = "t=time,x=disp,F=force";
  o.split = "nan";
  const auto records = load_records(o, true);
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[1].x_m, (std::vector<double>{9, 10, 11, 12, 13, 14, 15, 16}));
  EXPECT_EQ(records[1].t_s, (std::vector<double>{0, 1, 2, 3, 4, 5, 6, 7}));
}

TEST_F(RecordFiles, APlainFileReadAsChannelsKeepsItsCommentsOutAndItsHeaderUnits) {
  std::string text = "# a comment line\n\nt,x[mm],F[kN]\n";
  for (int k = 0; k < 10; ++k) text += std::to_string(k * 0.01) + "," + std::to_string(k) + "," + std::to_string(k % 3) + "\n";
  RecordOptions o;
  o.path = write("plain.csv", text);
  const Dataset plain = load_record(o, true);
  o.split = "nan";  // reads the file as channels: one test, no NaN rows
  const std::vector<Dataset> channels = load_records(o, true);
  ASSERT_EQ(channels.size(), 1u);
  EXPECT_EQ(channels[0].x_m, plain.x_m);  // mm → m from the header, as the plain loader does
  EXPECT_EQ(channels[0].F_N, plain.F_N);
  EXPECT_EQ(channels[0].t_s, plain.t_s);
  EXPECT_EQ(plain.x_m[3], 3e-3);
}

TEST(Preprocess, CentredMovingAverageByHand) {
  const std::vector<double> v{1, 2, 3, 4, 5};
  EXPECT_EQ(centred_moving_average(v, 3), (std::vector<double>{1.5, 2, 3, 4, 4.5}));
  EXPECT_EQ(centred_moving_average(v, 4), (std::vector<double>{1.5, 2, 2.5, 3.5, 4}));  // k-2 .. k+1
  std::vector<double> w{1, 2, 6};
  remove_mean(w);
  EXPECT_EQ(w, (std::vector<double>{-2, -1, 3}));
}

TEST(Preprocess, WholeCyclesRunFromTheFirstToTheLastUpwardCrossing) {
  const std::vector<double> x{0, -1, 1, 2, -2, -1, 1, 1, -1, 3};  // mean 0.3: upward at 2, 6 and 9
  EXPECT_EQ(whole_cycles_span(x, "r"), (std::pair<std::size_t, std::size_t>{2, 9}));
  EXPECT_NE(testing::error_of([] { whole_cycles_span({0, 1, 2, 3}, "r"); }).find("crosses its mean upward 1 time"),
            std::string::npos);
}

}  // namespace
}  // namespace dampbench
