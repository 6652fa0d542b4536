// A building under ground motion with a stepped damper (engine/structure): the reference buildings as the data's
// README gives them, classical modal damping, the LQR gain against its Riccati equation, a linear viscous damper
// against the closed-form harmonic steady state, the energy balance on El Centro, and the on/off rule.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/model/law_model.hpp"
#include "engine/structure/lqr.hpp"
#include "engine/structure/seismic.hpp"
#include "models/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench::structure {
namespace {

namespace fs = std::filesystem;

Building case_building(int n) {
  return read_building_file(fmt::format("{}/datasets/buildings/utfsm_case_{}.toml", DAMPBENCH_SOURCE_DIR, n));
}

/// ag = amplitude·sin(ω t), sampled at the building's own step so that no interpolation enters.
GroundMotion harmonic(double amplitude, double omega, double duration, double step) {
  GroundMotion g;
  g.name = "harmonic";
  for (double t = 0; t <= duration + 0.5 * step; t += step) {
    g.t_s.push_back(t);
    g.ag_m_s2.push_back(amplitude * std::sin(omega * t));
  }
  return g;
}

std::string building_error(const std::string& toml) {
  const fs::path path = fs::temp_directory_path() / "dampbench_test_building.toml";
  std::ofstream(path) << toml;
  return testing::error_of([&] { (void)read_building_file(path.string()); });
}

}  // namespace

TEST(Building, ReferenceCasesAreTheDataReadmesBuildings) {
  const double K[3][3] = {{2.6055e7, -2.3134e7, 0.5937e7}, {-2.3134e7, 3.2561e7, -1.4420e7}, {0.5937e7, -1.4420e7, 0.9267e7}};
  const double mass[] = {1000, 1100, 1300}, zeta[] = {0.05, 0.04, 0.03};
  for (int c = 1; c <= 3; ++c) {
    const Building b = case_building(c);
    ASSERT_EQ(b.storeys(), 3);
    EXPECT_EQ(b.damper_storey, 1);
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(b.mass_kg[i], mass[c - 1]);
      EXPECT_EQ(b.modal_damping[i], zeta[c - 1]);
      for (int j = 0; j < 3; ++j) EXPECT_DOUBLE_EQ(b.stiffness_N_m(i, j), K[i][j]);
    }
  }
}

TEST(Building, ClassicalDampingHasTheModalRatios) {
  const Building b = case_building(2);
  const Modes m = modes_of(b);
  const Eigen::MatrixXd modal = m.shapes.transpose() * m.damping_N_s_m * m.shapes;  // diag(2ζω) for Φᵀ M Φ = I
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(modal(i, j), i == j ? 2 * 0.04 * m.omega_rad_s[i] : 0.0, 1e-9 * m.omega_rad_s[2]) << i << "," << j;
  EXPECT_LT(m.omega_rad_s[0], m.omega_rad_s[1]);
}

TEST(Building, BadFilesSayWhatWasExpected) {
  EXPECT_NE(building_error("name='b'\nmass_kg=[1.0,1.0]\nstiffness_N_m=[[2.0,-1.0],[-1.0]]\nmodal_damping=0.05\n")
                .find("stiffness_N_m[1]: expected 2 numbers"),
            std::string::npos);
  EXPECT_NE(building_error("name='b'\nmass_kg=[1.0,1.0]\nstiffness_N_m=[[2.0,-1.0],[-1.5,1.0]]\nmodal_damping=0.05\n")
                .find("symmetric"),
            std::string::npos);
  EXPECT_NE(building_error("name='b'\nmass_kg=[1.0]\nstiffness_N_m=[[-1.0]]\nmodal_damping=0.05\n").find("positive definite"),
            std::string::npos);
  EXPECT_NE(building_error("name='b'\nmass_kg=[1.0]\nstiffness_N_m=[[1.0]]\nmodal_damping=0.05\ndamper_storey=2\n")
                .find("damper_storey: expected a storey from 1 to 1"),
            std::string::npos);
  EXPECT_NE(building_error("name='b'\nstiffness_N_m=[[1.0]]\nmodal_damping=0.05\n").find("mass_kg: expected an array"),
            std::string::npos);
}

TEST(Lqr, GainSolvesTheRiccatiEquationAndStabilizes) {
  const Building b = case_building(1);
  const StateSpace ss = state_space(b, modes_of(b));
  const LqrGain gain = lqr_gain(ss, energy_weight(b), 1e-6);
  EXPECT_LT(gain.riccati_residual, 1e-9);
  const Eigen::VectorXcd poles = (ss.A - ss.B * gain.G).eigenvalues();
  for (const auto& p : poles) EXPECT_LT(p.real(), 0.0);
  // The optimal cost xᵀPx is below that of no control (G = 0), whose P solves AᵀP + PA = −Q.
  const LqrGain open = lqr_gain(ss, energy_weight(b), 1e12);  // a force that costs everything: G → 0
  EXPECT_LT(gain.P.trace(), open.P.trace());
  EXPECT_THROW(lqr_gain(ss, energy_weight(b), 0.0), InputError);
}

TEST(Seismic, LinearViscousDamperReachesTheClosedFormSteadyState) {
  Building b = case_building(1);
  const Modes modes = modes_of(b);
  const double omega = modes.omega_rad_s[0], c_d = 2e4, amplitude = 0.5, step = 1.0 / 4096;
  const Model& viscous = find_model("fvd.linear_viscous");
  SeismicRun run;
  run.building = b;
  run.step_s = step;
  run.output_every = 1;
  run.ground = harmonic(amplitude, omega, 12.0, step);
  run.damper = Damper{&viscous, {0.0, c_d}, {}, 1};
  const SeismicResponse r = simulate_seismic(run);
  // (K − ω²M + iω(C + c_d e₁e₁ᵀ))·U = −M·1·amplitude: the steady amplitudes |U|.
  Eigen::MatrixXcd dynamic = (b.stiffness_N_m - omega * omega * Eigen::MatrixXd(b.mass_kg.asDiagonal())).cast<std::complex<double>>();
  Eigen::MatrixXd C = modes.damping_N_s_m;
  C(0, 0) += c_d;
  dynamic += std::complex<double>(0, omega) * C.cast<std::complex<double>>();
  const Eigen::VectorXcd U = dynamic.fullPivLu().solve((-b.mass_kg * amplitude).cast<std::complex<double>>());
  const double period = 2 * M_PI / omega;
  for (int i = 0; i < 3; ++i) {
    double peak = 0;
    for (std::size_t k = 0; k < r.t_s.size(); ++k)
      if (r.t_s[k] > r.t_s.back() - 2 * period) peak = std::max(peak, std::fabs(r.u_m(static_cast<Eigen::Index>(k), i)));
    EXPECT_NEAR(peak / std::abs(U[i]), 1.0, 1e-3) << "storey " << i + 1;
  }
  EXPECT_LT(r.energy.balance_error, 1e-9);
  EXPECT_EQ(r.unconverged_steps, 0);
}

TEST(Seismic, EnergyBalancesOnElCentroWithASpencerDamper) {
  const std::string path = std::string(DAMPBENCH_SHARED_DATA_DIR) + "/earthquakes/el_centro.csv";
  if (!fs::exists(path)) GTEST_SKIP() << "shared data absent: " << path;
  const Model& spencer = find_model("mrd.spencer");
  SeismicRun run;
  run.building = case_building(1);
  run.ground = read_ground_motion(path, 1.0);
  // mfm Table 3 at 1 A (tests/unit/kernels/test_ode_models.cpp)
  run.damper = Damper{&spencer, {4110.0, 4.542e5, 42.83, 561.2, -6.678e-2, 166.01, 6.079e3, 1.083e4, 5.021e4, 0.9929}, {}, 4};
  const SeismicResponse damped = simulate_seismic(run);
  run.damper.reset();
  const SeismicResponse bare = simulate_seismic(run);
  EXPECT_LT(damped.energy.balance_error, 1e-3);
  EXPECT_LT(bare.energy.balance_error, 1e-3);
  EXPECT_GT(damped.energy.damper_J, 0.0);
  EXPECT_EQ(damped.unconverged_steps, 0);
  EXPECT_LT(damped.peak_drift_m[0], bare.peak_drift_m[0]);
  std::printf("El Centro, case 1: peak drift 1 %.3f mm bare, %.3f mm with Spencer at mfm 1 A; damper %.1f J of %.1f J\n",
              1e3 * bare.peak_drift_m[0], 1e3 * damped.peak_drift_m[0], damped.energy.damper_J, damped.energy.input_J);
}

TEST(Seismic, OnOffSwitchesTheCommandByTheLqrRule) {
  // C = 1000 + 30000·I N·s/m: on/off between I = 0 and 1 at resonance, with an R that asks for forces the damper
  // can give part of the time (R = 1e-6 keeps it high 96 % of the steps, 1e-3 low 99 %).
  const Model& viscous = find_model("fvd.linear_viscous");
  const LawModel law(viscous, parse_laws("C=poly(I,1)", "test"));
  const Building b = case_building(1);
  SeismicRun run;
  run.building = b;
  run.ground = harmonic(1.0, modes_of(b).omega_rad_s[0], 6.0, 1.0 / 4096);
  run.damper = Damper{&law, {0.0, 1e3, 3e4}, {{"I", 0.0}}, 1};
  const double low_drift = simulate_seismic(run).peak_drift_m[0];
  run.damper->variables["I"] = 1.0;
  const double high_drift = simulate_seismic(run).peak_drift_m[0];
  run.control = OnOffControl{"I", 0.0, 1.0, lqr_gain(state_space(b, modes_of(b)), energy_weight(b), 1e-5).G};
  const SeismicResponse r = simulate_seismic(run);
  EXPECT_GT(r.high_share, 0.05);
  EXPECT_LT(r.high_share, 0.95);
  EXPECT_LT(r.energy.balance_error, 1e-9);
  EXPECT_GT(r.peak_drift_m[0], high_drift);
  EXPECT_LT(r.peak_drift_m[0], low_drift);
  bool low = false, high = false;
  for (double c : r.command) (c == 0.0 ? low : high) = true;
  EXPECT_TRUE(low && high);
  run.control->variable = "V";
  EXPECT_NE(testing::error_of([&] { (void)simulate_seismic(run); }).find("has no law in V"), std::string::npos);
}

}  // namespace dampbench::structure
