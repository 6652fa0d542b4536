// Where operating variables come from (Dataset::operating_source, Signals::law_variable_source): each way a
// record states one is named, later ways override earlier ones and say so, and a column of I that varies over
// the test is refused for laws instead of averaged.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "engine/common/error.hpp"
#include "engine/model/law_model.hpp"
#include "engine/model/parameter_law.hpp"
#include "engine/record/csv_loader.hpp"
#include "engine/record/excitation.hpp"
#include "engine/record/record_options.hpp"
#include "engine/record/signals.hpp"
#include "models/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

using testing::error_of;

/// Ten samples of a 0.1 m, 1 Hz-like ramp and back, with an extra column `extra` ("" for none).
std::string record_text(const std::string& comment, const std::string& extra_name,
                        const std::vector<double>& extra = {}) {
  std::string text = comment.empty() ? "" : "# operating: " + comment + "\n";
  text += "t,x,F" + (extra_name.empty() ? "" : "," + extra_name) + "\n";
  const double x[] = {0, 0.05, 0.1, 0.05, 0, -0.05, -0.1, -0.05, 0, 0.05};
  for (int k = 0; k < 10; ++k) {
    text += std::to_string(0.1 * k) + "," + std::to_string(x[k]) + ",1";
    if (!extra_name.empty()) text += "," + std::to_string(extra[k]);
    text += "\n";
  }
  return text;
}

Dataset parse_rig(const std::string& text, const std::string& source = "rig.csv") {
  std::istringstream in(text);
  return parse_csv(in, source, {});
}

TEST(OperatingSources, EachWayARecordStatesAVariableIsNamed) {
  const Dataset comment = parse_rig(record_text("I=0.5,amp=0.1", ""));
  EXPECT_EQ(comment.operating.at("I"), 0.5);
  EXPECT_EQ(comment.operating_source.at("I"), "file comment");
  EXPECT_EQ(comment.operating_source.at("amp"), "file comment");

  const Dataset column = parse_rig(record_text("", "I", {0.50, 0.51, 0.49, 0.50, 0.50, 0.51, 0.49, 0.50, 0.50, 0.50}));
  EXPECT_NEAR(column.operating.at("I"), 0.5, 1e-12);
  EXPECT_EQ(column.operating_source.at("I"), "column mean");
  EXPECT_TRUE(column.operating_refused.empty());  // spread 0.02 A = 4 % of 0.5 A: noise

  Dataset set = comment;
  set_operating(set, "I=1");
  EXPECT_EQ(set.operating.at("I"), 1.0);
  EXPECT_EQ(set.operating_source.at("I"), "--set");
  EXPECT_EQ(set.operating_source.at("amp"), "file comment");  // untouched

  const Dataset sine = make_sine(parse_sine_option("amp=0.01,freq=2,cycles=1,fs=100"));
  EXPECT_EQ(sine.operating_source.at("amp"), "sine excitation");
  EXPECT_EQ(sine.operating_source.at("freq"), "sine excitation");
}

TEST(OperatingSources, FileNameConditionsAreNamed) {
  const auto dir = std::filesystem::temp_directory_path() / "dampbench_operating_sources";
  std::filesystem::create_directories(dir);
  const auto path = dir / "10mm1Hz0x5A.csv";
  std::ofstream(path) << record_text("I=2", "");
  RecordOptions options;
  options.path = path.string();
  options.conditions = "utfsm";
  Dataset data = load_record(options, true);
  EXPECT_EQ(data.operating.at("I"), 0.5);  // the file name overrides the comment
  EXPECT_EQ(data.operating_source.at("I"), "file name");
  EXPECT_EQ(data.operating_source.at("amp"), "file name");
  EXPECT_EQ(data.operating_source.at("freq"), "file name");
  options.set = "freq=1.5";
  data = load_record(options, true);
  EXPECT_EQ(data.operating_source.at("freq"), "--set");
  EXPECT_EQ(data.operating_source.at("amp"), "file name");
}

TEST(OperatingSources, SignalsNameTheirEstimates) {
  const Signals bare = prepare_signals(parse_rig(record_text("", "")));
  EXPECT_EQ(bare.law_variable_source.at("amp"), "record estimate (half peak-to-peak)");
  EXPECT_EQ(bare.law_variables.at("amp"), 0.1);  // half of 0.1 − (−0.1)
  EXPECT_EQ(bare.law_variable_source.at("freq"), "record estimate (fdsp eq. 15)");
  EXPECT_EQ(bare.law_variable_source.at("w"), "record estimate (fdsp eq. 15)");
  EXPECT_EQ(bare.law_variable_source.size(), bare.law_variables.size());

  const Signals stated = prepare_signals(parse_rig(record_text("amp=0.2,I=0.5", "")));
  EXPECT_EQ(stated.law_variables.at("amp"), 0.2);
  EXPECT_EQ(stated.law_variable_source.at("amp"), "file comment");
  EXPECT_EQ(stated.law_variable_source.at("I"), "file comment");
  EXPECT_EQ(stated.law_variable_source.at("freq"), "record estimate (fdsp eq. 15)");

  Dataset in_code;  // built in code: no source recorded
  in_code.t_s = {0, 1, 2, 3};
  in_code.x_m = in_code.v_m_s = in_code.a_m_s2 = {0, 1, 0, -1};
  in_code.operating["I"] = 1;
  EXPECT_EQ(prepare_signals(in_code).law_variable_source.at("I"), "dataset");
}

// The rule: a column varies beyond noise when max − min > 5 % of max(|mean|, 0.1). 0.5 ± 0.02 A passes (above);
// a step from 0.4 to 0.6 A does not, nor does 0 to 0.01 A around zero (the floor: 10 % of 0.1 A). A law in I follows
// such a column sample by sample; a stated constant replaces it.
TEST(OperatingSources, ATimeVaryingCurrentIsFollowedByLaws) {
  const std::vector<double> step{0.4, 0.4, 0.4, 0.4, 0.4, 0.6, 0.6, 0.6, 0.6, 0.6};
  Dataset varying = parse_rig(record_text("", "I", step), "step.csv");
  EXPECT_NEAR(varying.operating.at("I"), 0.5, 1e-12);  // kept for tables
  EXPECT_EQ(varying.operating_source.at("I"),
            "column varying from 0.4 to 0.6: the mean shown, laws follow the column sample by sample");
  ASSERT_TRUE(varying.operating_refused.count("I"));  // for a model that cannot be stepped
  const std::string why = varying.operating_refused.at("I");
  for (const char* part : {"step.csv", "column I varies", "min 0.4", "max 0.6", "spread 0.2", "40 %",
                           "a law in it follows the column sample by sample, which needs a model that can be stepped"})
    EXPECT_NE(why.find(part), std::string::npos) << part << " in: " << why;
  EXPECT_EQ(varying.operating_signals.at("I"), step);  // the column, followed sample by sample
  const Dataset near_zero = parse_rig(record_text("", "I", {0, 0.01, 0, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_TRUE(near_zero.operating_refused.count("I"));
  const Dataset quiet_zero = parse_rig(record_text("", "I", {0, 0.004, 0, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_FALSE(quiet_zero.operating_refused.count("I"));

  const LawModel law(find_model("fvd.linear_viscous"), parse_laws("C=poly(I,1)", "--laws"));
  EXPECT_NO_THROW(law.check_variables(prepare_signals(varying)));
  EXPECT_TRUE(law.follows_columns(prepare_signals(varying)));
  const LawModel in_amp(find_model("fvd.linear_viscous"), parse_laws("C=poly(amp,1)", "--laws"));
  EXPECT_NO_THROW(in_amp.check_variables(prepare_signals(varying)));  // a law that does not use I
  EXPECT_FALSE(in_amp.follows_columns(prepare_signals(varying)));

  set_operating(varying, "I=0.5");  // the user states the constant current
  EXPECT_FALSE(varying.operating_refused.count("I"));
  EXPECT_FALSE(varying.operating_signals.count("I"));
  EXPECT_FALSE(law.follows_columns(prepare_signals(varying)));
  EXPECT_NO_THROW(law.check_variables(prepare_signals(varying)));
}

}  // namespace
}  // namespace dampbench
