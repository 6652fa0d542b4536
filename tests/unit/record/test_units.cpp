// Tests for engine/units: factors to SI for every column and unit, and header cells "x[mm]".
#include "engine/record/units.hpp"

#include <string>

#include <gtest/gtest.h>

#include "engine/common/error.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

using testing::error_of;

struct Case {
  const char* column;
  const char* unit;
  double factor;  // written out by hand from the unit definitions
};

TEST(Units, FactorsToSi) {
  const Case cases[] = {
      {"t", "s", 1.0},
      {"t", "ms", 0.001},
      {"x", "m", 1.0},
      {"x", "mm", 0.001},
      {"x", "cm", 0.01},
      {"x", "um", 1e-6},
      {"x", "in", 0.0254},
      {"x", "rad", 1.0},
      {"x", "deg", 0.017453292519943295},
      {"v", "m/s", 1.0},
      {"v", "mm/s", 0.001},
      {"v", "cm/s", 0.01},
      {"v", "in/s", 0.0254},
      {"v", "rad/s", 1.0},
      {"v", "deg/s", 0.017453292519943295},
      {"a", "m/s^2", 1.0},
      {"a", "mm/s^2", 0.001},
      {"a", "g", 9.80665},
      {"a", "rad/s^2", 1.0},
      {"F", "N", 1.0},
      {"F", "kN", 1000.0},
      {"F", "lbf", 4.4482216152605},
      {"F", "kip", 4448.2216152605},
      {"F", "N*m", 1.0},
      {"F", "N.m", 1.0},
      {"F", "Nm", 1.0},
      {"F", "kN*m", 1000.0},
      {"I", "A", 1.0},
      {"I", "mA", 0.001},
      {"V", "V", 1.0},
      {"V", "mV", 0.001},
      {"phi", "deg", 1.0},
      {"phi", "rad", 57.29577951308232},
  };
  for (const Case& c : cases)
    EXPECT_NEAR(unit_to_si(c.column, c.unit), c.factor, 1e-12 * c.factor) << c.column << " " << c.unit;
}

TEST(Units, UnknownUnitListsKnownOnes) {
  EXPECT_EQ(error_of([] { unit_to_si("x", "furlong"); }),
            "unknown unit 'furlong' for column 'x' (known: m, mm, cm, um, in, rad, deg)");
  EXPECT_EQ(error_of([] { unit_to_si("F", "kgf"); }),
            "unknown unit 'kgf' for column 'F' (known: N, kN, lbf, kip, N*m, N.m, Nm, kN*m)");
}

TEST(Units, UnitOfAnotherColumnOrWrongCaseIsUnknown) {
  EXPECT_NE(error_of([] { unit_to_si("t", "mm"); }).find("unknown unit 'mm' for column 't'"), std::string::npos);
  EXPECT_NE(error_of([] { unit_to_si("x", "MM"); }).find("unknown unit 'MM'"), std::string::npos);
  EXPECT_NE(error_of([] { unit_to_si("x", ""); }).find("unknown unit ''"), std::string::npos);
}

TEST(Units, UnknownColumnListsKnownOnes) {
  EXPECT_EQ(error_of([] { unit_to_si("q", "m"); }), "unknown column 'q' (known: t, x, v, a, F, y, u, I, V, phi)");
  EXPECT_EQ(known_columns_text(), "t, x, v, a, F, y, u, I, V, phi");
  EXPECT_TRUE(is_known_column("phi"));
  EXPECT_FALSE(is_known_column("f"));
}

TEST(SplitNameUnit, Forms) {
  EXPECT_EQ(split_name_unit("x[mm]"), (std::pair<std::string, std::string>{"x", "mm"}));
  EXPECT_EQ(split_name_unit("x [mm]"), (std::pair<std::string, std::string>{"x", "mm"}));
  EXPECT_EQ(split_name_unit(" F [ kN ] "), (std::pair<std::string, std::string>{"F", "kN"}));
  EXPECT_EQ(split_name_unit("a[m/s^2]"), (std::pair<std::string, std::string>{"a", "m/s^2"}));
  EXPECT_EQ(split_name_unit("x"), (std::pair<std::string, std::string>{"x", ""}));
  EXPECT_EQ(split_name_unit("x[]"), (std::pair<std::string, std::string>{"x", ""}));
}

TEST(SplitNameUnit, RejectsBrokenBrackets) {
  for (const char* cell : {"x[mm", "xmm]", "x]mm[", "x[mm]y"})
    EXPECT_NE(error_of([&] { split_name_unit(cell); }).find("expected name or name[unit]"), std::string::npos) << cell;
}

}  // namespace
}  // namespace dampbench
