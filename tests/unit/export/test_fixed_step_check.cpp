// The step size `export` states (engine/export/fixed_step_check.hpp): at the dt it states the fixed-step scheme
// is stable and accurate on other motions of the same stroke and velocity, and not far above it; an algebraic
// model holds at any dt; a law model is checked at the stiffer end of its fitted variables.
#include "engine/export/fixed_step_check.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "engine/model/law_model.hpp"
#include "engine/model/stepped_simulation.hpp"
#include "models/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench::exporting {
namespace {

/// The model's parameters from names, in its order.
std::vector<double> by_name(const Model& model, const std::map<std::string, double>& values) {
  std::vector<double> p;
  for (const auto& info : model.parameters()) p.push_back(values.at(info.name));
  return p;
}

/// mfm Table 3's Spencer at 1 A: β·X and A in the thousands make the hysteresis stiff.
const std::map<std::string, double> kSpencer1A{{"c0", 4110},    {"c1", 4.542e5},   {"k0", 42.83},
                                               {"k1", 561.2},   {"x0", -6.678e-2}, {"alpha", 166.01},
                                               {"beta", 6.079e3}, {"gamma", 1.083e4}, {"A", 5.021e4},
                                               {"n", 0.9929}};

/// A two-tone motion inside the check's envelope (stroke 20 mm, peak |v| at most 0.126 m/s) sampled at dt.
Signals two_tone(double dt_s) {
  Dataset d;
  const double w = 2 * M_PI * 1.0;
  for (int k = 0; k * dt_s <= 2.0; ++k) {
    const double t = k * dt_s;
    d.t_s.push_back(t);
    d.x_m.push_back(0.006 * std::sin(w * t) + 0.003 * std::sin(3 * w * t + 0.4));
    d.v_m_s.push_back(0.006 * w * std::cos(w * t) + 0.009 * w * std::cos(3 * w * t + 0.4));
  }
  return prepare_signals(d);
}

/// The motion checked: stroke [m], peak velocity [m/s], the variables' points.
CheckedMotion envelope(double stroke_m, double velocity_m_s, std::vector<std::map<std::string, double>> variables = {{}}) {
  CheckedMotion m;
  m.stroke_m = stroke_m;
  m.velocity_max_abs_m_s = velocity_m_s;
  m.variables = std::move(variables);
  return m;
}

}  // namespace

TEST(FixedStepCheck, StableAtTheStatedStepOnAnotherMotionAndNotFourTimesAbove) {
  const Model& spencer = find_model("mrd.spencer");
  const auto p = by_name(spencer, kSpencer1A);
  const FixedStepCheck c = check_fixed_step(spencer, p, 4, envelope(0.02, 0.126));
  ASSERT_TRUE(c.has_states);
  ASSERT_GT(c.dt_max_s, 0);
  EXPECT_FALSE(c.period_bound);  // the stiffness limits it, not the motion's sampling
  EXPECT_GE(c.dt_max_s, 0.5 * 4 * kRk4StabilityBound / c.stiffness_per_s);  // the estimate is not far off
  // Another motion of the same envelope, at the stated dt and at four times it.
  const Signals at = two_tone(c.dt_max_s), above = two_tone(4 * c.dt_max_s);
  const auto coarse = simulate_stepped(spencer, p, at, 4), fine = simulate_stepped(spencer, p, at, 64);
  for (double f : coarse) ASSERT_TRUE(std::isfinite(f));
  EXPECT_LT(testing::relative_l2(coarse, fine), 0.02);
  const auto coarse4 = simulate_stepped(spencer, p, above, 4), fine4 = simulate_stepped(spencer, p, above, 64);
  bool finite = true;
  for (double f : coarse4) finite = finite && std::isfinite(f);
  EXPECT_TRUE(!finite || testing::relative_l2(coarse4, fine4) > 0.01) << "the stated dt is over 4 times too cautious";
}

TEST(FixedStepCheck, MoreSubstepsAllowALargerStep) {
  const Model& spencer = find_model("mrd.spencer");
  const auto p = by_name(spencer, kSpencer1A);
  const CheckedMotion m = envelope(0.02, 0.126);
  EXPECT_GT(check_fixed_step(spencer, p, 16, m).dt_max_s, 2 * check_fixed_step(spencer, p, 4, m).dt_max_s);
}

TEST(FixedStepCheck, AnAlgebraicModelHoldsAtAnyStep) {
  const Model& bingham = find_model("mrd.bingham");
  const FixedStepCheck c =
      check_fixed_step(bingham, by_name(bingham, {{"f_c", 300}, {"c0", 2000}, {"f0", -5}}), 4, envelope(0.02, 0.126));
  EXPECT_FALSE(c.has_states);
  EXPECT_NE(fixed_step_statement(c, 4).find("any dt"), std::string::npos);
}

TEST(FixedStepCheck, ALawModelIsCheckedAtItsStifferFittedEnd) {
  // A = poly(I, 1) grows tenfold from 0 to 1 A, and with it the hysteresis' stiffness.
  const LawModel model(find_model("mrd.bouc_wen"), parse_laws("A=poly(I,1)", "--laws"));
  const auto p = by_name(model, {{"c0", 2000}, {"k0", 1000}, {"x0", 0}, {"alpha", 500}, {"A_I0", 600},
                                 {"A_I1", 5400}, {"beta", 3000}, {"gamma", 3000}, {"n", 1.5}});
  const auto at = [&](std::vector<std::map<std::string, double>> variables) {
    return check_fixed_step(model, p, 4, envelope(0.02, 0.126, std::move(variables))).dt_max_s;
  };
  const double both = at({{{"I", 0.0}}, {{"I", 1.0}}}), low = at({{{"I", 0.0}}}), high = at({{{"I", 1.0}}});
  EXPECT_EQ(both, high);
  EXPECT_LT(high, low);
}

TEST(FixedStepCheck, ALawStiffestInsideItsRangeIsCheckedThere) {
  // A = 600 + 21600 I − 21600 I²: 600 at 0 and 1 A, 6000 at 0.5 A.
  const LawModel model(find_model("mrd.bouc_wen"), parse_laws("A=poly(I,2)", "--laws"));
  const auto p = by_name(model, {{"c0", 2000}, {"k0", 1000}, {"x0", 0}, {"alpha", 500}, {"A_I0", 600},
                                 {"A_I1", 21600}, {"A_I2", -21600}, {"beta", 3000}, {"gamma", 3000}, {"n", 1.5}});
  CheckedMotion ends = envelope(0.02, 0.126, {{{"I", 0.0}}, {{"I", 1.0}}});
  const double at_ends = check_fixed_step(model, p, 4, ends).dt_max_s;
  for (int i = 0; i <= 8; ++i) ends.probes.push_back({{"I", i / 8.0}});
  const FixedStepCheck c = check_fixed_step(model, p, 4, ends);
  ASSERT_EQ(c.motion.variables.size(), 3u);
  EXPECT_EQ(c.motion.variables.back().at("I"), 0.5);
  EXPECT_LT(c.dt_max_s, at_ends);
  EXPECT_NE(fixed_step_statement(c, 4).find("at I = 0 and at I = 1 and at I = 0.5"), std::string::npos);
}

TEST(FixedStepCheck, TheStatedStepIsRoundedDown) {
  const Model& spencer = find_model("mrd.spencer");
  const FixedStepCheck c = check_fixed_step(spencer, by_name(spencer, kSpencer1A), 4, envelope(0.02, 0.126));
  EXPECT_LE(std::stod(printed_step(c)), c.dt_max_s);
  EXPECT_GT(std::stod(printed_step(c)), 0.99 * c.dt_max_s);
}

TEST(FixedStepCheck, AMotionWithoutStrokeIsRefused) {
  const Model& spencer = find_model("mrd.spencer");
  EXPECT_NE(testing::error_of([&] { check_fixed_step(spencer, by_name(spencer, kSpencer1A), 4, envelope(0, 0.1)); })
                .find("expected a finite stroke and peak velocity above 0"),
            std::string::npos);
  EXPECT_NE(testing::error_of([&] { check_fixed_step(spencer, by_name(spencer, kSpencer1A), 4, envelope(INFINITY, 0.1)); })
                .find("expected a finite stroke"),
            std::string::npos);
}

}  // namespace dampbench::exporting
