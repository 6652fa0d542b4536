// Synthetic grids generated on first use (datasets/synthetic/grids.cpp, engine/sweep/spec.cpp
// ensure_generated): generated once, found again, regenerated for another build, never half-written, and
// found by a sweep that names "@generated/..." from any working folder.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include "datasets/synthetic/grids.hpp"
#include "engine/sweep/spec.hpp"
#include "test_support.hpp"

namespace dampbench::synthetic {
namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class SyntheticGrids : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            fmt::format("dampbench-grids-{}", std::chrono::steady_clock::now().time_since_epoch().count());
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_;
};

TEST_F(SyntheticGrids, FvdGridEqualsTheCommittedRecords) {
  // datasets/fvd holds the fvd grid as written by the same generator with the same seed.
  ASSERT_EQ(ensure_grid(root_, "fvd", "build A"), GridState::kGenerated);
  const fs::path committed = fs::path(DAMPBENCH_SOURCE_DIR) / "datasets" / "fvd";
  int compared = 0;
  for (const auto& e : fs::directory_iterator(committed)) {
    if (e.path().extension() != ".csv") continue;
    EXPECT_EQ(read_file(root_ / "fvd" / e.path().filename()), read_file(e.path())) << e.path().filename();
    ++compared;
  }
  EXPECT_EQ(compared, 4);
}

TEST_F(SyntheticGrids, GeneratedOnceThenFoundAndRegeneratedForAnotherBuild) {
  ASSERT_EQ(ensure_grid(root_, "fvd", "build A"), GridState::kGenerated);
  const std::string stamp = read_file(root_ / "fvd" / "stamp");
  EXPECT_NE(stamp.find("build A"), std::string::npos);
  EXPECT_EQ(ensure_grid(root_, "fvd", "build A"), GridState::kPresent);

  // A record changed by hand, or a grid made by another build, is replaced by this build's.
  const fs::path record = root_ / "fvd" / "test1_20mm_92mms.csv";
  const std::string original = read_file(record);
  std::ofstream(record) << "tampered\n";
  EXPECT_EQ(ensure_grid(root_, "fvd", "build B"), GridState::kRegenerated);
  EXPECT_EQ(read_file(record), original);
  EXPECT_NE(read_file(root_ / "fvd" / "stamp").find("build B"), std::string::npos);
  for (const auto& e : fs::directory_iterator(root_))  // no temporary folder left behind
    EXPECT_EQ(e.path().filename().string().rfind(".fvd.tmp", 0), std::string::npos) << e.path();
}

TEST_F(SyntheticGrids, UnwritableFolderIsAClearErrorAndLeavesNothing) {
  const fs::path not_a_folder = root_ / "file";
  std::ofstream(not_a_folder) << "x";
  const std::string message = testing::error_of([&] { (void)ensure_grid(not_a_folder, "fvd", "build A"); });
  EXPECT_NE(message.find("cannot write the synthetic grid 'fvd' into '" + not_a_folder.string() + "'"), std::string::npos)
      << message;
  EXPECT_NE(message.find("DAMPBENCH_GENERATED_DIR"), std::string::npos) << message;
  EXPECT_EQ(testing::error_of([&] { (void)ensure_grid(root_, "nope", "build A"); }),
            "unknown synthetic grid 'nope' (known: fvd, crfd, crfd-neutral, mfm, mfm-neutral, fdsp, fdsp-neutral)");
}

TEST_F(SyntheticGrids, SweepGeneratesTheGridItNamesOnFirstUse) {
  const fs::path spec = root_ / "sweep.toml";
  std::ofstream(spec) << R"(name = "g"
runs = 1
models = ["fvd.linear_viscous"]
[optimizer]
name = "pso"
population = 4
iterations = 2
[[datasets]]
name = "fvd"
glob = "@generated/fvd/*.csv"
)";
  ::setenv("DAMPBENCH_GENERATED_DIR", (root_ / "cache").c_str(), 1);
  sweep::SweepSpec loaded;
  const std::string error = testing::error_of([&] { loaded = sweep::load_sweep(spec.string()); });
  const std::string again = testing::error_of([&] { (void)sweep::load_sweep(spec.string()); });
  ::unsetenv("DAMPBENCH_GENERATED_DIR");
  ASSERT_EQ(error, "no error");
  ASSERT_EQ(again, "no error");
  EXPECT_TRUE(fs::exists(root_ / "cache" / "fvd" / "test4_17mm_460mms.csv"));
  ASSERT_EQ(loaded.notes.size(), 1u);
  EXPECT_NE(loaded.notes[0].find("generated the synthetic grid 'fvd'"), std::string::npos) << loaded.notes[0];

  std::string text = read_file(spec);
  text.replace(text.find("@generated/fvd"), 14, "@generated/xyz");
  std::ofstream(spec) << text;
  const std::string unknown = testing::error_of([&] { (void)sweep::load_sweep(spec.string()); });
  EXPECT_NE(unknown.find("sweep.toml:10: key 'datasets[0].glob': '@generated/xyz/*.csv' names no synthetic grid"),
            std::string::npos)
      << unknown;
}

TEST_F(SyntheticGrids, DatasetsGenerateCommandWritesEveryGridAskedFor) {
  const auto r = testing::run_dampbench(fmt::format("datasets generate fvd --into {}", root_.string()));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("fvd: generated into " + (root_ / "fvd").string()), std::string::npos) << r.output;
  const auto again = testing::run_dampbench(fmt::format("datasets generate fvd --into {}", root_.string()));
  EXPECT_NE(again.output.find("fvd: already in"), std::string::npos) << again.output;
  const auto bad = testing::run_dampbench(fmt::format("datasets generate nope --into {}", root_.string()));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("dampbench: error: unknown synthetic grid 'nope'"), std::string::npos) << bad.output;
}

}  // namespace
}  // namespace dampbench::synthetic
