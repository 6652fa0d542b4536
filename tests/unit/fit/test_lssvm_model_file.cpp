// LS-SVM model files (engine/fit/lssvm_model_file.hpp): a trained model read back predicts with the same bits as the
// model that was written (one step ahead and in free run), and a wrong file is refused naming the file and the key.
#include "engine/fit/lssvm_model_file.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <nlohmann/json.hpp>

#include "tests/test_support.hpp"

namespace dampbench {
namespace {

/// A sinusoidal record at `freq` Hz with a viscous-plus-friction force and a current I (the LS-SVM's regressors).
Dataset sine_record(const std::string& name, double freq, double current) {
  Dataset d;
  d.name = name;
  d.operating["I"] = current;
  const double w = 2 * std::numbers::pi * freq, amp = 0.01;
  for (int k = 0; k < 300; ++k) {
    const double t = k * 0.005;
    d.t_s.push_back(t);
    d.x_m.push_back(amp * std::sin(w * t));
    d.v_m_s.push_back(amp * w * std::cos(w * t));
    d.a_m_s2.push_back(-amp * w * w * std::sin(w * t));
    d.F_N.push_back(2000 * d.v_m_s.back() + (50 + 100 * current) * std::tanh(d.v_m_s.back() / 0.01) + 300 * d.x_m.back());
  }
  return d;
}

lssvm::Model trained_model() {
  const lssvm::Lags lags;  // d = v = y = 2
  const std::vector<Dataset> train{sine_record("a", 1.0, 0.0), sine_record("b", 2.0, 1.0)};
  return lssvm::Model::train(lssvm::build_rows(train, lags), lags, 50, 2.0);
}

void expect_same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k)
    ASSERT_EQ(std::bit_cast<std::uint64_t>(a[k]), std::bit_cast<std::uint64_t>(b[k])) << "sample " << k;
}

TEST(LssvmModelFile, AModelReadBackPredictsWithTheSameBits) {
  const lssvm::Model written = trained_model();
  const auto path = testing::test_temp_dir("lssvm_model_file") / "model.json";
  write_lssvm_model_file(path.string(), written, {"a", "b"}, "test");
  ASSERT_TRUE(is_lssvm_model_file(path.string()));
  const lssvm::Model read = load_lssvm_model_file(path.string());
  EXPECT_EQ(read.c(), written.c());
  EXPECT_EQ(read.sigma(), written.sigma());
  const Dataset test = sine_record("test", 1.5, 0.5);  // a current and a frequency it was not trained at
  expect_same_bits(read.simulate(test), written.simulate(test));
  expect_same_bits(read.predict_one_step(test), written.predict_one_step(test));
  const auto file = nlohmann::json::parse(std::ifstream(path));
  EXPECT_EQ(file.at("trained_on"), nlohmann::json({"a", "b"}));
  EXPECT_EQ(file.at("points").size(), file.at("alpha").size());

  // Another JSON file, or none, is not an LS-SVM model file.
  const auto other = path.parent_path() / "other.json";
  std::ofstream(other) << R"({"format": "dampbench-model"})";
  EXPECT_FALSE(is_lssvm_model_file(other.string()));
  EXPECT_FALSE(is_lssvm_model_file((path.parent_path() / "missing.json").string()));
}

TEST(LssvmModelFile, AWrongFileIsRefusedNamingTheKey) {
  const auto good = nlohmann::ordered_json::parse(lssvm_model_file_text(trained_model(), {"a"}, "test"));
  const auto error_of = [](const nlohmann::ordered_json& j) {
    return testing::error_of([&] { (void)parse_lssvm_model_file(j.dump(), "m.json"); });
  };
  auto j = good;
  j["format"] = "dampbench-model";
  EXPECT_EQ(error_of(j), "m.json: key 'format': expected \"dampbench-lssvm-model\", got \"dampbench-model\"");
  j = good;
  j.erase("alpha");
  EXPECT_EQ(error_of(j), "m.json: key 'alpha': missing");
  j = good;
  j["points"].erase(j["points"].begin());
  EXPECT_EQ(error_of(j), fmt::format("m.json: key 'points': expected an array of {} points (one per alpha)",
                                     good["alpha"].size()));
  j = good;
  j["points"][0].erase(j["points"][0].begin());
  EXPECT_EQ(error_of(j), "m.json: key 'points[0].point': expected 8 numbers, got 7");
  j = good;
  j["normalizer"]["scale"][1] = "x";
  EXPECT_EQ(error_of(j), "m.json: key 'normalizer.scale': entry 1 is not a number: \"x\"");
  j = good;
  j["sigma"] = 0;
  EXPECT_EQ(error_of(j), "lssvm model: c and sigma must be positive, got c = 50, sigma = 0");
  EXPECT_NE(testing::error_of([] { (void)parse_lssvm_model_file("{", "m.json"); }).find("m.json: not JSON"),
            std::string::npos);
}

}  // namespace
}  // namespace dampbench
