// Parameter laws (engine/model/parameter_law.cpp): parsing, coefficient names and hand-computed values.
#include "engine/model/parameter_law.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/test_support.hpp"

namespace dampbench {
namespace {
using testing::error_of;
const std::map<std::string, double> kVars{{"I", 2.0}, {"amp", 0.01}, {"freq", 1.5}, {"phi", 90.0}};
}  // namespace

TEST(ParameterLaw, PolynomialByHorner) {
  const auto law = parse_law("poly(I,2)", "test");
  EXPECT_EQ(law.coefficient_names("c0"), (std::vector<std::string>{"c0_I0", "c0_I1", "c0_I2"}));
  const double c[] = {1.0, -3.0, 0.5};
  EXPECT_DOUBLE_EQ(law.evaluate(c, kVars), 1.0 - 6.0 + 2.0);  // 1 − 3·2 + 0.5·4
}

TEST(ParameterLaw, ProductOfPolynomials) {
  const auto law = parse_law("prod(poly(I,1), poly(amp,1), poly(freq,0))", "test");
  EXPECT_EQ(law.coefficient_names("A"), (std::vector<std::string>{"A_I0", "A_I1", "A_amp0", "A_amp1", "A_freq0"}));
  const double c[] = {1.0, 2.0, 3.0, 100.0, 0.5};
  EXPECT_DOUBLE_EQ(law.evaluate(c, kVars), (1.0 + 4.0) * (3.0 + 1.0) * 0.5);
  EXPECT_EQ(parse_law(law.text(), "t").text(), law.text());
}

TEST(ParameterLaw, PowerAndGaussian) {
  const double p[] = {2.0, 0.5, -1.0};
  EXPECT_DOUBLE_EQ(parse_law("power(freq)", "t").evaluate(p, kVars), 2.0 * std::sqrt(1.5) - 1.0);
  const double g[] = {10.0, 1.5, 2.0, 4.0, 0.5, 1.0};  // first Gaussian centred on freq: exp(0) = 1
  EXPECT_DOUBLE_EQ(parse_law("gauss2(freq)", "t").evaluate(g, kVars), 10.0 + 4.0 * std::exp(-1.0));
}

TEST(ParameterLaw, FixedAndFree) {
  EXPECT_EQ(parse_law("0.9929", "t").coefficient_names("n").size(), 0u);
  EXPECT_DOUBLE_EQ(parse_law("0.9929", "t").evaluate(nullptr, kVars), 0.9929);
  const double c[] = {7.0};
  EXPECT_DOUBLE_EQ(parse_law("free", "t").evaluate(c, kVars), 7.0);
}

TEST(ParameterLaw, MissingVariableGivesNaNNotACrash) {
  const double c[] = {1.0, 1.0};
  EXPECT_TRUE(std::isnan(parse_law("poly(V,1)", "t").evaluate(c, kVars)));
}

TEST(ParameterLaw, ParsesLists) {
  const auto laws = parse_laws("c0=poly(I,1); alpha = poly(I,1);n=0.9929;", "--laws");
  ASSERT_EQ(laws.size(), 3u);
  EXPECT_EQ(laws.at("n").kind, ParameterLaw::Kind::fixed);
  EXPECT_EQ(laws.at("alpha").factors[0].variable, "I");
}

TEST(ParameterLaw, BadLawsAreReported) {
  EXPECT_EQ(error_of([] { parse_law("poly(T,1)", "--laws c0"); }),
            "--laws c0: unknown operating variable 'T' (known: I, V, phi, amp, freq, w, vamp)");
  EXPECT_EQ(error_of([] { parse_law("poly(I,1.5)", "--laws c0"); }),
            "--laws c0: polynomial degree must be a whole number from 0 to 6, got '1.5'");
  EXPECT_EQ(error_of([] { parse_law("spline(I)", "--laws c0"); }),
            "--laws c0: unknown law 'spline' (known: poly, prod, power, gauss2, sat, hill, tanh, mono, free, or a number)");
  EXPECT_NE(error_of([] { parse_law("poly I", "--laws c0"); }).find("--laws c0: expected a number, poly(VAR,DEGREE)"),
            std::string::npos);
  EXPECT_EQ(error_of([] { parse_laws("c0=poly(I,1);c0=1", "--laws"); }), "--laws: law for 'c0' given twice");
  EXPECT_EQ(error_of([] { parse_laws("c0", "--laws"); }), "--laws: expected PARAM=LAW, got 'c0'");
}

}  // namespace dampbench
