// The commands that run an identified damper outside a fit: simulate --fixed-step (a varying current column),
// inverse, structure. Their outputs, their files, their messages for bad input, and the figures docs/examples.md
// and README.md quote from them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "tests/test_support.hpp"

namespace dampbench {
namespace {

namespace fs = std::filesystem;

/// ±10 mm at 1 Hz, 1 kHz, two cycles; with a current column that steps from `low` to `high` halfway when given.
fs::path sine_record(const fs::path& dir, const std::string& name, bool with_current, double low = 0.2, double high = 0.8) {
  std::string text = with_current ? "t,x,I\n" : "t,x\n";
  for (int k = 0; k <= 2000; ++k) {
    const double t = k / 1000.0, x = 0.01 * std::sin(2 * M_PI * t);
    text += with_current ? fmt::format("{},{},{}\n", t, x, k < 1000 ? low : high) : fmt::format("{},{}\n", t, x);
  }
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path;
}

std::vector<std::vector<double>> read_csv(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream s(line);
    for (std::string field; std::getline(s, field, ',');) row.push_back(std::stod(field));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

TEST(ControlCli, SimulateFollowsAVaryingCurrentColumnWithAndWithoutFixedSteps) {
  const auto dir = testing::test_temp_dir("control_cli");
  const auto record = sine_record(dir, "step_current.csv", true);
  auto r = run_dampbench("simulate --fixture mfm.table3 --input " + record.string() + " -o " + (dir / "batch.csv").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_dampbench("simulate --fixture mfm.table3 --fixed-step 4 --input " + record.string() + " -o " + (dir / "stepped.csv").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The same record at constant 0.2 A and 0.8 A: the stepped force is the first's until the step, and the
  // second's hysteresis loop afterwards (the state carries over, so only once the loop has settled).
  const auto low = sine_record(dir, "low.csv", true, 0.2, 0.2), high = sine_record(dir, "high.csv", true, 0.8, 0.8);
  ASSERT_EQ(run_dampbench("simulate --fixture mfm.table3 --fixed-step 4 --input " + low.string() + " -o " + (dir / "low_F.csv").string()).exit_code, 0);
  ASSERT_EQ(run_dampbench("simulate --fixture mfm.table3 --fixed-step 4 --input " + high.string() + " -o " + (dir / "high_F.csv").string()).exit_code, 0);
  const auto stepped = read_csv(dir / "stepped.csv"), at_low = read_csv(dir / "low_F.csv"), at_high = read_csv(dir / "high_F.csv");
  ASSERT_EQ(stepped.size(), 2001U);
  // (column F; the command at sample 1000 holds after it; the constant record's current is its column's mean,
  // 0.2 up to rounding)
  for (int k = 0; k <= 1000; ++k) ASSERT_NEAR(stepped[k][4], at_low[k][4], 1e-9 * std::fabs(at_low[k][4]) + 1e-9) << k;
  for (int k = 1900; k <= 2000; ++k) EXPECT_NEAR(stepped[k][4], at_high[k][4], 1e-3 * std::fabs(at_high[k][4]) + 1e-6) << k;
  // Without --fixed-step the batch kernels' sub-step rule: the same force to the discretization error, and the
  // column written back beside it (so that `fit` reads the record again).
  const auto batch = read_csv(dir / "batch.csv");
  ASSERT_EQ(batch.size(), stepped.size());
  double diff = 0, norm = 0;
  for (std::size_t k = 0; k < batch.size(); ++k) {
    diff += (batch[k][4] - stepped[k][4]) * (batch[k][4] - stepped[k][4]);
    norm += stepped[k][4] * stepped[k][4];
    ASSERT_EQ(batch[k].size(), 6U);
    EXPECT_EQ(batch[k][5], k < 1000 ? 0.2 : 0.8) << k;
  }
  EXPECT_LT(std::sqrt(diff / norm), 1e-3);
}

TEST(ControlCli, InverseFindsTheConstantCurrentOfAForceRecord) {
  const auto dir = testing::test_temp_dir("control_cli_inverse");
  const auto motion = sine_record(dir, "motion.csv", true, 0.4, 0.4);
  ASSERT_EQ(run_dampbench("simulate --fixture mfm.table3 --fixed-step 4 --input " + motion.string() + " -o " +
                          (dir / "desired.csv").string()).exit_code, 0);
  auto r = run_dampbench_json("inverse --fixture mfm.table3 --data " + (dir / "desired.csv").string() +
                              " --range I=0:1 --format json -o " + (dir / "command.csv").string());
  ASSERT_EQ(r.exit_code, 0) << r.output << r.errors;
  const auto j = nlohmann::json::parse(r.output);
  EXPECT_GT(j["share_reachable"].get<double>(), 0.99);
  EXPECT_LT(j["tracking_error"].get<double>(), 1e-6);
  const auto rows = read_csv(dir / "command.csv");  // t, I, F_desired, F_model, reachable
  int moving = 0, found = 0;
  for (const auto& row : rows) {
    const double v = 0.02 * M_PI * std::cos(2 * M_PI * row[0]);
    if (std::fabs(v) < 0.02 || row[0] > 1.998) continue;
    ++moving;
    found += std::fabs(row[1] - 0.4) < 1e-3;
  }
  EXPECT_GT(found, 0.95 * moving) << found << " of " << moving;
  r = run_dampbench("inverse --fixture mfm.table3 --data " + (dir / "desired.csv").string() + " --range I=1");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("--range: expected VARIABLE=LOW:HIGH"), std::string::npos) << r.output;
  r = run_dampbench("inverse --model fvd.linear_viscous --params m=0,C=1000 --data " + (dir / "desired.csv").string() + " --range I=0:1");
  EXPECT_NE(r.output.find("has no law in I"), std::string::npos) << r.output;
}

TEST(ControlCli, StructureWritesPeaksEnergiesAndTimeHistories) {
  const auto dir = testing::test_temp_dir("control_cli_structure");
  const auto ground = dir / "pulse.csv";
  {
    std::ofstream out(ground);
    out << "t,ag\n";
    for (int k = 0; k <= 400; ++k) out << k / 100.0 << "," << (k < 100 ? 2.0 * std::sin(2 * M_PI * 3.0 * k / 100.0) : 0.0) << "\n";
  }
  const std::string building = std::string(DAMPBENCH_SOURCE_DIR) + "/datasets/buildings/utfsm_case_1.toml";
  auto r = run_dampbench_json("structure --model fvd.linear_viscous --params m=0,C=20000 --building " + building +
                              " --ground " + ground.string() + " --format json -o " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output << r.errors;
  const auto j = nlohmann::json::parse(r.output);
  EXPECT_LT(j["damped"]["peak_drift_m"][0].get<double>(), j["bare"]["peak_drift_m"][0].get<double>());
  EXPECT_LT(j["damped"]["energy_balance_error"].get<double>(), 1e-9);
  EXPECT_GT(j["damped"]["energy_J"]["damper"].get<double>(), 0.0);
  const auto rows = read_csv(dir / "structure.csv");  // t, ag, u1-3, drift1-3, abs_acc1-3, F, command
  ASSERT_GT(rows.size(), 100U);
  EXPECT_EQ(rows.front().size(), 13U);
  EXPECT_TRUE(fs::exists(dir / "structure.md"));
  std::ifstream svg(dir / "structure.svg");
  const std::string page((std::istreambuf_iterator<char>(svg)), std::istreambuf_iterator<char>());
  EXPECT_NE(page.find("<svg"), std::string::npos);
  EXPECT_EQ(std::count(page.begin(), page.end(), '\n'), 1);  // one page, one line
  EXPECT_NE(page.find("storey 1 drift, bare [mm]"), std::string::npos);
  r = run_dampbench("structure --model fvd.linear_viscous --params m=0,C=20000 --building " + building +
                    " --ground " + (dir / "missing.csv").string());
  EXPECT_NE(r.output.find("missing.csv: cannot read the ground-motion file"), std::string::npos) << r.output;
  r = run_dampbench("structure --model fvd.linear_viscous --params m=0,C=20000 --building " + building + " --ground " +
                    ground.string() + " --control on-off --command I=0:1");
  EXPECT_NE(r.output.find("has no law in I"), std::string::npos) << r.output;
}

TEST(ControlCli, ExamplesBuildingTableIsTheCommandsOutput) {
  const std::string root = DAMPBENCH_SOURCE_DIR, shared = DAMPBENCH_SHARED_DATA_DIR;
  const std::string ground = shared + "/earthquakes/el_centro.csv", record = shared + "/utfsm-mr-damper/10mm1Hz0x5A.txt";
  if (!fs::exists(ground) || !fs::exists(record)) GTEST_SKIP() << "shared data absent: " << ground;
  std::ifstream in(root + "/docs/examples.md");
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string base = "structure --model-file " + root + "/datasets/models/utfsm_spencer_I.json --building " + root +
                           "/datasets/buildings/utfsm_case_1.toml --ground " + ground + " --format json ";
  const std::vector<std::pair<std::string, std::string>> runs{
      {"passive, 0 A", "--set I=0"}, {"passive, 1 A", "--set I=1"},
      {"on/off, 0–1 A (LQR, R = 1e-6)", "--control on-off --command I=0:1"}};
  std::vector<double> reductions;  // of the storey-1 peak drift, for README's bullet
  for (const auto& [label, args] : runs) {
    const auto r = run_dampbench_json(base + args);
    ASSERT_EQ(r.exit_code, 0) << r.output << r.errors;
    const auto j = nlohmann::json::parse(r.output);
    const auto& bare = j["bare"];
    const auto& damped = j["damped"];
    const double drift0 = bare["peak_drift_m"][0], drift = damped["peak_drift_m"][0];
    const double acc0 = bare["peak_absolute_acceleration_m_s2"][2], acc = damped["peak_absolute_acceleration_m_s2"][2];
    const double share = damped["energy_J"]["damper"].get<double>() / damped["energy_J"]["input"].get<double>();
    const std::string bare_row = fmt::format("| bare building | {:.3f} | | {:.3f} | | | |", 1e3 * drift0, acc0);
    const std::string row = fmt::format("| {} | {:.3f} | {:.1f} % | {:.3f} | {:.1f} % | {:.0f} | {:.1f} % |", label,
                                        1e3 * drift, 100 * (1 - drift / drift0), acc, 100 * (1 - acc / acc0),
                                        damped["peak_damper_force_N"].get<double>(), 100 * share);
    reductions.push_back(100 * (1 - drift / drift0));
    EXPECT_NE(doc.find(bare_row), std::string::npos) << bare_row;
    EXPECT_NE(doc.find(row), std::string::npos) << row;
    if (j["damper"].contains("command")) {
      EXPECT_NE(doc.find(fmt::format("keeps 1 A on {:.0f} % of the steps", 100 * damped["high_command_share"].get<double>())),
                std::string::npos);
    }
  }
  std::ifstream readme_file(root + "/README.md");
  const std::string readme((std::istreambuf_iterator<char>(readme_file)), std::istreambuf_iterator<char>());
  const std::string bullet = fmt::format("cuts El Centro's peak drift by {:.1f} % at 1 A ({:.1f} % at 0 A; on/off {:.1f} %)",
                                         reductions[1], reductions[0], reductions[2]);
  EXPECT_NE(readme.find(bullet), std::string::npos) << bullet;
  // The inverse example: its reachable share and the median and quartiles of the current found.
  const auto dir = testing::test_temp_dir("control_cli_examples");
  const auto r = run_dampbench_json("inverse --model-file " + root + "/datasets/models/utfsm_spencer_I.json --range I=0:1 --data " +
                                    record + " --columns t,x,v,F --units x=mm,v=mm/s --format json -o " +
                                    (dir / "command.csv").string());
  ASSERT_EQ(r.exit_code, 0) << r.output << r.errors;
  std::vector<double> found;
  for (const auto& row : read_csv(dir / "command.csv"))
    if (row[4] > 0) found.push_back(row[1]);
  std::sort(found.begin(), found.end());
  const auto quantile = [&](double q) { return found[static_cast<std::size_t>(q * static_cast<double>(found.size() - 1))]; };
  const std::string text = fmt::format("{:.1f} % of the samples are reachable and the current found has median {:.3f} A\n"
                                       "(quartiles {:.3f}–{:.3f} A)",
                                       100 * nlohmann::json::parse(r.output)["share_reachable"].get<double>(), quantile(0.5),
                                       quantile(0.25), quantile(0.75));
  EXPECT_NE(doc.find(text), std::string::npos) << text;
}

}  // namespace dampbench
