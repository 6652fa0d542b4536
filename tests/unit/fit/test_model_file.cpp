// Model files (engine/fit/model_file.hpp): numbers read back to the same bits, and every way a file can be wrong
// is reported naming the file and the key.
#include "engine/fit/model_file.hpp"

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "tests/test_support.hpp"

namespace dampbench {
namespace {

using testing::error_of;

ModelFile law_model_file() {
  ModelFile f;
  f.dampbench_version = "0.0.0";
  f.vector_level = "avx2";
  f.choice.model = "fvd.linear_viscous";
  f.choice.laws = "C=poly(I,1)";
  f.model_id = "fvd.linear_viscous[C=poly(I,1)]";
  // Numbers whose shortest decimal form has fewer than 17 digits, and ones that need all 17.
  f.coefficients = {{"m", 0.1}, {"C_I0", 1.0 / 3.0}, {"C_I1", 2.2250738585072014e-308 * 3}};
  f.metric = "of_abs";
  f.fitted_value = std::nextafter(1.0, 2.0);
  f.records.push_back({"a", "dir/a.csv", 5e-324, nlohmann::ordered_json::object(), 0.02, 1.0 / 7.0});
  f.records.back().operating["I"] = {{"value", 0.7}, {"source", "--set"}};
  return f;
}

std::string write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("dampbench_model_file_" + name + ".json");
  std::ofstream(path) << text;
  return path.string();
}

TEST(ModelFile, NumbersReadBackToTheSameBits) {
  const ModelFile f = law_model_file();
  const std::string text = model_file_text(f);
  EXPECT_NE(text.find("0.33333333333333331"), std::string::npos) << text;  // %.17g, not the shortest form
  EXPECT_NE(text.find("\"m\": 0.10000000000000001"), std::string::npos) << text;
  const ModelFile back = parse_model_file(text, "f.json");
  ASSERT_EQ(back.coefficients.size(), f.coefficients.size());
  for (std::size_t i = 0; i < f.coefficients.size(); ++i) {
    EXPECT_EQ(back.coefficients[i].first, f.coefficients[i].first);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(back.coefficients[i].second),
              std::bit_cast<std::uint64_t>(f.coefficients[i].second));
  }
  EXPECT_EQ(std::bit_cast<std::uint64_t>(back.fitted_value), std::bit_cast<std::uint64_t>(f.fitted_value));
  EXPECT_EQ(std::bit_cast<std::uint64_t>(back.records[0].metric_value), std::bit_cast<std::uint64_t>(5e-324));
  EXPECT_EQ(back.choice.model, "fvd.linear_viscous");
  EXPECT_EQ(back.choice.laws, "C=poly(I,1)");
  EXPECT_EQ(back.records[0].operating["I"]["source"], "--set");
  EXPECT_EQ(back.records[0].path, "dir/a.csv");
  EXPECT_EQ(back.records[0].displacement_ptp_m, 0.02);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(back.records[0].velocity_max_abs_m_s), std::bit_cast<std::uint64_t>(1.0 / 7.0));
  EXPECT_EQ(model_file_text(back), text);

  const LoadedModel loaded = load_model_file(write_temp("good", text));
  EXPECT_EQ(loaded.model.model->dim(), 3);
  EXPECT_EQ(loaded.params[loaded.model.model->parameter_index("C_I0")], 1.0 / 3.0);
}

// A file may name a published law fixture instead of a base model; its coefficients come back in order.
TEST(ModelFile, AFixtureModelLoadsWithItsCoefficients) {
  ModelChoice choice;
  choice.fixture = "mfm.table3";
  const ResolvedModel fixture = resolve_model(choice);
  ModelFile f;
  f.dampbench_version = "0.0.0";
  f.vector_level = "sse2";
  f.choice.fixture = "mfm.table3";
  for (int i = fixture.model->dim() - 1; i >= 0; --i)  // any order: read by name
    f.coefficients.emplace_back(fixture.model->parameters()[i].name, fixture.defaults[i]);
  f.metric = "nrmse";
  const LoadedModel loaded = load_model_file(write_temp("fixture", model_file_text(f)));
  EXPECT_EQ(loaded.model.model->id(), fixture.model->id());
  EXPECT_EQ(loaded.params, fixture.defaults);
  EXPECT_TRUE(loaded.file.records.empty());
}

/// The error of loading `text` with `from` replaced by `to` (which must occur in it).
std::string load_error(const std::string& name, std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) return "test setup: '" + from + "' not in the file";
  text.replace(at, from.size(), to);
  const std::string path = write_temp(name, text);
  const std::string message = error_of([&] { load_model_file(path); });
  return message.starts_with(path + ": ") ? message.substr(path.size() + 2) : "file not named: " + message;
}

TEST(ModelFile, EveryErrorNamesTheFileAndTheKey) {
  const std::string text = model_file_text(law_model_file());
  EXPECT_EQ(load_error("fmt", text, "\"dampbench-model\"", "\"other\""),
            "key 'format': expected \"dampbench-model\", got \"other\"");
  EXPECT_EQ(load_error("ver", text, "\"format_version\": 1", "\"format_version\": 2"),
            "key 'format_version': expected 1, got 2");
  EXPECT_EQ(load_error("miss", text, "\"metric\": {", "\"metrics\": {"), "key 'metric': missing");
  EXPECT_EQ(load_error("type", text, "\"m\": 0.10000000000000001", "\"m\": \"0.1\""),
            "key 'coefficients.m': expected a number, got \"0.1\"");
  EXPECT_EQ(load_error("laws_type", text, "\"laws\": \"C=poly(I,1)\"", "\"laws\": 3"),
            "key 'model.laws': expected a string, got 3");
  EXPECT_EQ(load_error("records", text, "\"path\": \"dir/a.csv\"", "\"file\": \"dir/a.csv\""),
            "key 'records[0].path': missing");
  EXPECT_EQ(load_error("source", text, "\"source\": \"--set\"", "\"source\": null"),
            "key 'records[0].operating.I.source': expected a string, got null");
  EXPECT_EQ(load_error("motion", text, "\"displacement_ptp_m\": 0.02", "\"displacement_ptp_m\": \"2 cm\""),
            "key 'records[0].motion.displacement_ptp_m': expected a number, got \"2 cm\"");
  const std::string unknown = load_error("unknown", text, "\"base\": \"fvd.linear_viscous\"", "\"base\": \"fvd.nope\"");
  EXPECT_TRUE(unknown.starts_with("key 'model.base': unknown model 'fvd.nope'")) << unknown;
  const std::string laws = load_error("laws", text, "\"laws\": \"C=poly(I,1)\"", "\"laws\": \"C=poly(Q,1)\"");
  EXPECT_TRUE(laws.starts_with("key 'model.laws': ")) << laws;
  EXPECT_NE(laws.find("unknown operating variable 'Q'"), std::string::npos) << laws;
  const std::string name = load_error("name", text, "\"C_I1\":", "\"C_I2\":");
  EXPECT_TRUE(name.starts_with("key 'coefficients.C_I2': not a coefficient of fvd.linear_viscous[")) << name;
  EXPECT_NE(name.find("(its 3: m, C_I0, C_I1)"), std::string::npos) << name;
  const std::string count = load_error("count", text, "\"C_I1\": 6.6752215755216041e-308", "\"m\": 1");
  EXPECT_EQ(count.substr(0, count.find(" (")), "key 'coefficients.C_I1': missing") << count;
  EXPECT_NE(count.find("has 3 coefficients: m, C_I0, C_I1; the file gives 2"), std::string::npos) << count;
  EXPECT_EQ(load_error("both", text, "\"fixture\": \"\"", "\"fixture\": \"mfm.table3\""),
            "key 'model.base': give exactly one of model.base (a model id) and model.fixture (a law fixture)");
  const std::string json = load_error("json", text, "\"records\": [", "\"records\": [[");
  EXPECT_TRUE(json.starts_with("not JSON")) << json;
  EXPECT_NE(error_of([] { load_model_file("/nonexistent/m.json"); }).find("cannot open '/nonexistent/m.json'"),
            std::string::npos);
}

}  // namespace
}  // namespace dampbench
