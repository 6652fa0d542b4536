// Tests for engine/key_values: name=value lists, strict numbers, name lists.
#include "engine/common/key_values.hpp"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "engine/common/error.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

/// The message of the InputError thrown by `fn`, or "no error".
using testing::error_of;

TEST(KeyValues, KeepsOrderAndTrims) {
  const auto entries = parse_key_values(" C = 1.5 , alpha=0.3,k=2e4", "--params");
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_EQ(entries[0], (std::pair<std::string, std::string>{"C", "1.5"}));
  EXPECT_EQ(entries[1], (std::pair<std::string, std::string>{"alpha", "0.3"}));
  EXPECT_EQ(entries[2], (std::pair<std::string, std::string>{"k", "2e4"}));
}

TEST(KeyValues, EmptyTextGivesEmptyList) {
  EXPECT_TRUE(parse_key_values("", "--params").empty());
  EXPECT_TRUE(parse_key_values("   ", "--params").empty());
}

TEST(KeyValues, ValueMayContainColons) {
  const auto entries = parse_key_values("C=1:100", "--bounds");
  ASSERT_EQ(entries.size(), 1u);
  EXPECT_EQ(entries[0].second, "1:100");
}

TEST(KeyValues, RejectsMissingEquals) {
  EXPECT_EQ(error_of([] { parse_key_values("C", "--params"); }), "--params: expected name=value, got 'C'");
  EXPECT_EQ(error_of([] { parse_key_values("C=1,alpha", "--params"); }), "--params: expected name=value, got 'alpha'");
}

TEST(KeyValues, RejectsEmptyValueEmptyNameAndEmptyEntry) {
  EXPECT_EQ(error_of([] { parse_key_values("C=", "--params"); }), "--params: expected name=value, got 'C='");
  EXPECT_EQ(error_of([] { parse_key_values("=3", "--params"); }), "--params: empty name in '=3'");
  EXPECT_EQ(error_of([] { parse_key_values("C=1,,k=2", "--params"); }), "--params: expected name=value, got ''");
}

TEST(KeyValues, RejectsDuplicates) {
  EXPECT_EQ(error_of([] { parse_key_values("C=1,alpha=0.3,C=2", "--params"); }), "--params: 'C' given twice");
}

TEST(ParseNumber, AcceptsPlainSignedAndExponentForms) {
  EXPECT_DOUBLE_EQ(parse_number("1.5", "v"), 1.5);
  EXPECT_DOUBLE_EQ(parse_number("+2e3", "v"), 2000.0);
  EXPECT_DOUBLE_EQ(parse_number("-1.25E-2", "v"), -0.0125);
  EXPECT_DOUBLE_EQ(parse_number(".5", "v"), 0.5);
  EXPECT_DOUBLE_EQ(parse_number("7", "v"), 7.0);
}

TEST(ParseNumber, RejectsNonNumbersWithMessage) {
  EXPECT_EQ(error_of([] { parse_number("1.2x", "--sine amp"); }), "--sine amp: expected a number, got '1.2x'");
  for (const char* text : {"", "abc", "1e", "+-1", "++1", " 1", "1 ", "0x10", "1,5", "--1"})
    EXPECT_NE(error_of([&] { parse_number(text, "v"); }).find("expected a number"), std::string::npos) << text;
}

TEST(ParseNumber, RejectsNonFiniteAndOutOfRange) {
  for (const char* text : {"nan", "inf", "-inf", "+inf", "NaN", "infinity"})
    EXPECT_EQ(error_of([&] { parse_number(text, "v"); }),
              std::string("v: expected a finite number, got '") + text + "'")
        << text;
  EXPECT_EQ(error_of([] { parse_number("1e999", "v"); }), "v: number out of range, got '1e999'");
}

TEST(TryParseNumber, ReportsStatus) {
  EXPECT_EQ(try_parse_number("2.5").status, NumberStatus::ok);
  EXPECT_DOUBLE_EQ(try_parse_number("2.5").value, 2.5);
  EXPECT_EQ(try_parse_number("nan").status, NumberStatus::ok);
  EXPECT_TRUE(std::isnan(try_parse_number("nan").value));
  EXPECT_EQ(try_parse_number("-inf").status, NumberStatus::ok);
  EXPECT_TRUE(std::isinf(try_parse_number("-inf").value));
  EXPECT_EQ(try_parse_number("1e-999").status, NumberStatus::out_of_range);
  EXPECT_EQ(try_parse_number("abc").status, NumberStatus::not_a_number);
  EXPECT_EQ(try_parse_number("").status, NumberStatus::not_a_number);
  EXPECT_EQ(try_parse_number("+").status, NumberStatus::not_a_number);
}

TEST(SplitList, TrimsNames) {
  EXPECT_EQ(split_list(" t, x ,v,F", "--columns"), (std::vector<std::string>{"t", "x", "v", "F"}));
  EXPECT_EQ(split_list("t,x[mm],F [kN]", "--columns"), (std::vector<std::string>{"t", "x[mm]", "F [kN]"}));
  EXPECT_EQ(split_list("t", "--columns"), (std::vector<std::string>{"t"}));
}

TEST(SplitList, RejectsEmptyEntries) {
  EXPECT_EQ(error_of([] { split_list("t,,x", "--columns"); }), "--columns: empty entry in 't,,x'");
  EXPECT_EQ(error_of([] { split_list("t,x,", "--columns"); }), "--columns: empty entry in 't,x,'");
  EXPECT_EQ(error_of([] { split_list("", "--columns"); }), "--columns: empty entry in ''");
}

TEST(Trim, RemovesSurroundingWhitespaceOnly) {
  EXPECT_EQ(trim("  a b \t\r\n"), "a b");
  EXPECT_EQ(trim(""), "");
  EXPECT_EQ(trim(" \t "), "");
}

}  // namespace
}  // namespace dampbench
