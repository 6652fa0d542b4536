// Record transforms (engine/record/record_transforms.cpp): crfd slider-crank kinematics, cycle averaging and
// UTFSM file-name conditions, against hand-computed values.
#include "engine/record/record_transforms.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/test_support.hpp"

namespace dampbench {
namespace {
constexpr double kDeg = std::numbers::pi / 180;
}

TEST(SliderCrank, RestPoseIsThetaZeroGamma5515) {
  const SliderCrank rig;
  const auto pose = rig.solve(0.0);
  // H = 114.89 mm is the printed rounding of √(140² − 80²) = 114.8913 mm: θ = −0.0013 mm / 80 mm ≈ −1.6e-5 rad.
  EXPECT_NEAR(pose.theta_rad, -(std::sqrt(140.0 * 140 - 80.0 * 80) - 114.89) / 80.0, 1e-7);
  EXPECT_NEAR(pose.gamma_rad / kDeg, 55.15, 0.01);  // acos(80/140)
  // Statics at θ = 0: T = F·L_AB·sin γ / sin γ = F·L_AB; printed: F·L_AB·sin²γ.
  EXPECT_NEAR(rig.torque(100.0, pose), 100.0 * 0.080 * std::sin(pose.theta_rad + pose.gamma_rad) / std::sin(pose.gamma_rad), 1e-12);
  EXPECT_NEAR(rig.torque(100.0, {0.0, pose.gamma_rad}), 8.0, 1e-12);
  SliderCrank printed;
  printed.printed_torque = true;
  EXPECT_NEAR(printed.torque(100.0, {0.0, pose.gamma_rad}), 8.0 * std::pow(std::sin(pose.gamma_rad), 2), 1e-12);
}

TEST(SliderCrank, PlusMinus3mmSatisfyBothLoopEquations) {
  const SliderCrank rig;
  for (double x_e : {0.003, -0.003}) {
    const auto p = rig.solve(x_e);
    EXPECT_NEAR(0.080 * std::cos(p.theta_rad) - 0.140 * std::cos(p.gamma_rad), 0.0, 1e-13);
    EXPECT_NEAR(0.080 * std::sin(p.theta_rad) + 0.140 * std::sin(p.gamma_rad) - 0.11489 - x_e, 0.0, 1e-13);
    // Small-motion estimate: dθ/dx_e = 1/(L_AB cos θ + L_AB sin θ cot γ) ≈ 1/L_AB at θ ≈ 0 → ±37.5 mrad.
    EXPECT_NEAR(p.theta_rad, x_e / 0.080, 0.1 * std::fabs(x_e / 0.080));
    EXPECT_GT(p.theta_rad * x_e, 0.0);
  }
}

TEST(SliderCrank, OutOfReachIsReported) {
  EXPECT_EQ(testing::error_of([] { (void)SliderCrank().solve(0.2); }),
            "slider-crank: actuator displacement 200 mm is outside the rig's reach");
}

TEST(SliderCrank, RecordBecomesAngleAndTorque) {
  Dataset mts;
  mts.name = "mts";
  for (int k = 0; k < 200; ++k) {
    const double t = k / 200.0;
    mts.t_s.push_back(t);
    mts.x_m.push_back(0.003 * std::sin(2 * std::numbers::pi * t));
    mts.v_m_s.push_back(0);
    mts.a_m_s2.push_back(0);
    mts.F_N.push_back(50.0);
  }
  const SliderCrank rig;
  const Dataset rot = to_rotary(mts, rig);
  for (std::size_t k = 0; k < rot.size(); k += 37) {
    const auto p = rig.solve(mts.x_m[k]);
    EXPECT_DOUBLE_EQ(rot.x_m[k], p.theta_rad);
    EXPECT_DOUBLE_EQ(rot.F_N[k], rig.torque(50.0, p));
  }
  // θ̇ recomputed: near t = 0 it is ẋ_e·dθ/dx_e ≈ (0.003·2π)/0.080.
  EXPECT_NEAR(rot.v_m_s[0], 0.003 * 2 * std::numbers::pi / 0.080, 0.02);
}

TEST(AverageCycles, KeepsFourToSevenOfTen) {
  // F = sin(2πt) + 0.1·(cycle index): cycles 4–7 (indices 3..6) average to sin(2πt) + 0.45.
  Dataset r;
  r.name = "ten";
  r.source = "ten.csv";
  const int per_cycle = 100;
  for (int k = 0; k <= 10 * per_cycle; ++k) {
    const double t = static_cast<double>(k) / per_cycle;
    const int cycle = std::min(k / per_cycle, 9);
    r.t_s.push_back(t);
    r.x_m.push_back(std::sin(2 * std::numbers::pi * t));
    r.v_m_s.push_back(0);
    r.a_m_s2.push_back(0);
    r.F_N.push_back(std::sin(2 * std::numbers::pi * t) + 0.1 * cycle);
  }
  const Dataset avg = average_cycles(r, 10, 3);
  ASSERT_EQ(avg.size(), static_cast<std::size_t>(per_cycle));
  EXPECT_EQ(avg.t_s.front(), 0.0);
  for (std::size_t k = 0; k < avg.size(); ++k) {
    EXPECT_NEAR(avg.F_N[k], std::sin(2 * std::numbers::pi * avg.t_s[k]) + 0.45, 1e-9) << k;
    EXPECT_NEAR(avg.x_m[k], std::sin(2 * std::numbers::pi * avg.t_s[k]), 1e-9);
  }
  EXPECT_NE(testing::error_of([&] { average_cycles(r, 10, 5); }).find("at least one kept cycle"), std::string::npos);
}

TEST(UtfsmConditions, ParsesFileNames) {
  const auto c = utfsm_conditions("25mm0x25Hz0x75A");
  EXPECT_DOUBLE_EQ(c.at("amp"), 0.025);
  EXPECT_DOUBLE_EQ(c.at("freq"), 0.25);
  EXPECT_DOUBLE_EQ(c.at("I"), 0.75);
  EXPECT_DOUBLE_EQ(utfsm_conditions("2mm5Hz1A").at("freq"), 5.0);
  EXPECT_NE(testing::error_of([] { utfsm_conditions("test1_20mm"); }).find("'test1_20mm': expected a UTFSM file name"),
            std::string::npos);
}

}  // namespace dampbench
